//! The 4-wide node: the boxes of up to four children stored lane by lane
//! (structure of arrays), so one ray meets all four in a handful of SIMD
//! instructions, and a binary build collapses into half as many levels.

use glam::{BVec4A, Vec3A, Vec4};

use crate::geometry::{Aabb, Ray};

use super::build::{BuildTree, NodeRef};

/// `count` of a slot that holds no child.
pub(super) const EMPTY: u32 = u32::MAX;

/// A node: 128 bytes, two cache lines, aligned to them. Slot `i` is
/// child `i`: its box is lane `i` of `min` and `max`; `count[i] == 0`
/// makes it the inner node `first[i]`, `count[i] == EMPTY` an unused slot,
/// any other count a leaf of `count[i]` primitives whose packed records
/// `first[i]` locates (see `packed::leaf_first`).
/// Used slots come first.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(super) struct Node4 {
    min: [Vec4; 3],
    max: [Vec4; 3],
    pub(super) first: [u32; 4],
    pub(super) count: [u32; 4],
}

impl Node4 {
    const BLANK: Node4 = Node4 {
        min: [Vec4::ZERO; 3],
        max: [Vec4::ZERO; 3],
        first: [0; 4],
        count: [EMPTY; 4],
    };

    /// Sets slot `i` to a child with box `bounds`.
    fn set(&mut self, i: usize, bounds: &Aabb, first: u32, count: u32) {
        let (lo, hi) = if bounds.is_empty() {
            (Vec3A::ZERO, Vec3A::ZERO)
        } else {
            (bounds.min, bounds.max)
        };
        for axis in 0..3 {
            self.min[axis][i] = lo[axis];
            self.max[axis][i] = hi[axis];
        }
        self.first[i] = first;
        self.count[i] = count;
    }

    /// The slots that hold a child (they come first).
    pub(super) fn used_slots(&self) -> impl Iterator<Item = usize> + '_ {
        (0..4).take_while(|&i| self.count[i] != EMPTY)
    }

    /// The box of slot `i`.
    pub(super) fn bounds(&self, i: usize) -> Aabb {
        Aabb::new(
            Vec3A::new(self.min[0][i], self.min[1][i], self.min[2][i]),
            Vec3A::new(self.max[0][i], self.max[1][i], self.max[2][i]),
        )
    }

    /// The entry distance of each slot's box, and which boxes the ray
    /// meets in `(t_min, t_max)` (unused slots never).
    ///
    /// Each lane gets exactly the arithmetic of [`Aabb::intersect`] on
    /// that lane's box: both planes of a slab clamped to the interval
    /// before they are combined (so a NaN from `0 * inf` drops out), then
    /// the three slabs reduced with max and min, which return one of their
    /// operands whatever the order. So a box is met here exactly when
    /// [`Aabb::intersect`] says so, at the same distance, and the choice of
    /// nodes to visit does not depend on the layout.
    #[inline]
    pub(super) fn hit(&self, ray: &WideRay, t_min: f32, t_max: f32) -> (Vec4, u32) {
        let lo = Vec4::splat(t_min);
        let hi = Vec4::splat(t_max);
        let mut near = lo;
        let mut far = hi;
        for axis in 0..3 {
            let t0 = (self.min[axis] - ray.origin[axis]) * ray.inv_dir[axis];
            let t1 = (self.max[axis] - ray.origin[axis]) * ray.inv_dir[axis];
            near = near.max(t0.max(lo).min(t1.max(lo)));
            far = far.min(t0.min(hi).max(t1.min(hi)));
        }
        let used = BVec4A::new(
            self.count[0] != EMPTY,
            self.count[1] != EMPTY,
            self.count[2] != EMPTY,
            self.count[3] != EMPTY,
        );
        (near, (near.cmple(far) & used).bitmask())
    }
}

/// A ray's origin and reciprocal direction, each coordinate in all four
/// lanes: made once per traversal, not once per node.
pub(super) struct WideRay {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
}

impl WideRay {
    #[inline]
    pub(super) fn new(ray: &Ray) -> Self {
        Self {
            origin: [0, 1, 2].map(|axis| Vec4::splat(ray.origin[axis])),
            inv_dir: [0, 1, 2].map(|axis| Vec4::splat(ray.inv_dir[axis])),
        }
    }
}

/// Flattens the binary tree `tree` into 4-wide nodes, root first; every
/// node's children are opened, largest box first, until it has four (or
/// only leaves remain).
pub(super) fn flatten(tree: &BuildTree, prims: usize) -> Vec<Node4> {
    let mut nodes = Vec::with_capacity(prims.div_ceil(2).max(1));
    nodes.push(Node4::BLANK);
    if tree.is_empty() {
        return nodes;
    }
    let root = tree.node(NodeRef::ROOT);
    if root.is_leaf() {
        nodes[0].set(0, &root.bounds, root.first, root.count);
    } else {
        fill(tree, NodeRef::ROOT, 0, &mut nodes);
    }
    nodes
}

/// Writes the children of the inner node `inner` of `tree` into
/// `nodes[index]`, and their own children into new nodes, recursively.
fn fill(tree: &BuildTree, inner: NodeRef, index: usize, nodes: &mut Vec<Node4>) {
    let mut slots = [inner; 4];
    let mut used = 1;
    // Open the inner child with the largest box until four slots are used.
    while used < 4 {
        let widest = slots[..used]
            .iter()
            .enumerate()
            .map(|(i, &at)| (i, tree.node(at)))
            .filter(|(_, n)| !n.is_leaf())
            .map(|(i, n)| (i, n.bounds.half_area()))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i);
        let Some(i) = widest else { break };
        // The right child goes last, the left one takes the opened slot.
        let opened = tree.node(slots[i]);
        slots[used] = opened.right();
        slots[i] = opened.left(slots[i]);
        used += 1;
    }
    for (slot, &at) in slots[..used].iter().enumerate() {
        let child = tree.node(at);
        if child.is_leaf() {
            nodes[index].set(slot, &child.bounds, child.first, child.count);
        } else {
            let child_index = nodes.len();
            nodes.push(Node4::BLANK);
            nodes[index].set(slot, &child.bounds, child_index as u32, 0);
            fill(tree, at, child_index, nodes);
        }
    }
}
