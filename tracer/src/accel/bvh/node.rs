//! The 4-wide node: the boxes of up to four children stored lane by lane
//! (structure of arrays), so one ray meets all four in a handful of SIMD
//! instructions, and a binary build collapses into half as many levels.

use glam::{Vec3A, Vec4};

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
    /// The children's boxes plane by plane: `min` x, y, z, then `max` x,
    /// y, z, one child a lane.
    planes: [Vec4; 6],
    pub(super) first: [u32; 4],
    pub(super) count: [u32; 4],
}

impl Node4 {
    /// Unused slots hold an inverted box (`min` +inf, `max` -inf): every
    /// ray enters it at +inf and leaves it at -inf on every axis, so it is
    /// never met and the node test needs no mask of used slots.
    const BLANK: Node4 = Node4 {
        planes: [
            Vec4::INFINITY,
            Vec4::INFINITY,
            Vec4::INFINITY,
            Vec4::NEG_INFINITY,
            Vec4::NEG_INFINITY,
            Vec4::NEG_INFINITY,
        ],
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
            self.planes[axis][i] = lo[axis];
            self.planes[3 + axis][i] = hi[axis];
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
            Vec3A::new(self.planes[0][i], self.planes[1][i], self.planes[2][i]),
            Vec3A::new(self.planes[3][i], self.planes[4][i], self.planes[5][i]),
        )
    }

    /// The entry distance of each slot's box, and which boxes the ray
    /// meets in `(t_min, t_max)` (unused slots never: see [`Node4::BLANK`]).
    ///
    /// Per axis, the ray enters a slab by its `min` plane when it goes up
    /// the axis and by its `max` plane when it goes down ([`WideRay`] picks
    /// them once per ray): the entry distance only raises `near`, the exit
    /// distance only lowers `far`, six operations a slab instead of the twelve
    /// of sorting the two planes and clamping each (frames 1-8% shorter on six
    /// scenes). It is the arithmetic of [`Aabb::intersect`] rearranged:
    /// there `min(max(t0, t_min), max(t1, t_min))` is `max(min(t0, t1),
    /// t_min)`, and `min(t0, t1)` is the entry plane's distance. A ray
    /// parallel to a slab whose origin lies on one of its planes gives
    /// `0 * inf = NaN` for that plane, which `max` and `min` drop here as
    /// the clamping drops it there (SSE returns the second operand when
    /// one is NaN, and the running interval is the second operand): the
    /// ray counts as inside that slab. So a box is met here exactly when
    /// [`Aabb::intersect`] says so, at the same distance (up to the sign of
    /// a zero), and the choice of nodes to visit does not depend on the
    /// layout.
    #[inline]
    pub(super) fn hit(&self, ray: &WideRay, t_min: f32, t_max: f32) -> (Vec4, u32) {
        let mut near = Vec4::splat(t_min);
        let mut far = Vec4::splat(t_max);
        for axis in 0..3 {
            let entry = self.planes[ray.entry_plane[axis]];
            let exit = self.planes[ray.exit_plane[axis]];
            let t_entry = (entry - ray.origin[axis]) * ray.inv_dir[axis];
            let t_exit = (exit - ray.origin[axis]) * ray.inv_dir[axis];
            near = t_entry.max(near);
            far = t_exit.min(far);
        }
        (near, near.cmple(far).bitmask())
    }
}

/// A ray's origin and reciprocal direction, each coordinate in all four
/// lanes: made once per traversal, not once per node.
pub(super) struct WideRay {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
    /// Per axis, the planes the ray enters and leaves a box's slab by, as
    /// indices into [`Node4::planes`]: `min` then `max` where the ray goes
    /// up the axis, the other way round where it goes down.
    entry_plane: [usize; 3],
    exit_plane: [usize; 3],
}

impl WideRay {
    /// Written out lane by lane: built with `[0, 1, 2].map`, the compiler
    /// left a call per ray to an outlined `try_map` with bounds-checked
    /// `Vec3A` indexing (4% of balls_medium's instructions, callgrind).
    #[inline]
    pub(super) fn new(ray: &Ray) -> Self {
        let (o, d) = (ray.origin, ray.inv_dir);
        // Bit `axis` set where the ray goes down that axis (-0.0 included).
        let down = d.is_negative_bitmask() as usize;
        let entry = |axis: usize| axis + 3 * ((down >> axis) & 1);
        let exit = |axis: usize| axis + 3 * (!(down >> axis) & 1);
        Self {
            origin: [Vec4::splat(o.x), Vec4::splat(o.y), Vec4::splat(o.z)],
            inv_dir: [Vec4::splat(d.x), Vec4::splat(d.y), Vec4::splat(d.z)],
            entry_plane: [entry(0), entry(1), entry(2)],
            exit_plane: [exit(0), exit(1), exit(2)],
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

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// Coordinates on a half-unit lattice (so ray origins often lie on a
    /// box's planes) or anywhere.
    fn coordinate() -> impl Strategy<Value = f32> {
        prop_oneof![(-4i32..=4).prop_map(|i| i as f32 * 0.5), -4.0f32..4.0]
    }

    fn point() -> impl Strategy<Value = Vec3A> {
        (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| Vec3A::new(x, y, z))
    }

    /// Direction components with zeros of both signs, whose reciprocals
    /// are infinite.
    fn component() -> impl Strategy<Value = f32> {
        prop_oneof![Just(0.0f32), Just(-0.0f32), -1.0f32..1.0]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2048))]
        /// Flat and solid boxes, rays along and across their planes, from
        /// their planes and edges: each lane says what `Aabb::intersect`
        /// says of its box, at the same entry distance.
        #[test]
        fn a_node_meets_each_box_as_aabb_intersect_does(
            corners in prop::collection::vec((point(), point()), 1..=4),
            origin in point(),
            dir in (component(), component(), component()),
            t_min in prop_oneof![Just(0.0f32), 0.0f32..3.0],
            t_max in prop_oneof![Just(f32::INFINITY), 0.0f32..12.0],
        ) {
            let dir = Vec3A::new(dir.0, dir.1, dir.2);
            prop_assume!(dir.length() > 1e-3);
            let ray = Ray::new(origin, dir);
            let boxes: Vec<Aabb> = corners.iter().map(|&(a, b)| Aabb::new(a.min(b), a.max(b))).collect();
            let mut node = Node4::BLANK;
            for (slot, b) in boxes.iter().enumerate() {
                node.set(slot, b, 0, 1);
            }
            let (near, mask) = node.hit(&WideRay::new(&ray), t_min, t_max);
            for slot in 0..4 {
                let expected = boxes.get(slot).and_then(|b| b.intersect(&ray, t_min, t_max));
                prop_assert_eq!(mask >> slot & 1 == 1, expected.is_some(), "slot {}", slot);
                if let Some((entry, _)) = expected {
                    prop_assert_eq!(near[slot], entry, "slot {}", slot);
                }
            }
        }
    }
}
