//! The 8-wide node: the boxes of up to eight children stored lane by lane
//! (structure of arrays), so one ray meets all eight in a handful of SIMD
//! instructions (one AVX register a plane, or two SSE ones), and a binary
//! build collapses into a third as many levels. Embree's single-ray kernels
//! use the same node on AVX2 machines: a shadow ray that must open every
//! box on its way waits on fewer nodes.

use glam::{Vec3A, Vec4};

use crate::geometry::{Aabb, Ray};

use super::build::{BuildNode, BuildTree, NodeRef, leaf_cost};

/// Children a node holds: the lanes of an AVX register.
pub(super) const WIDTH: usize = 8;

/// `count` of a slot that holds no child.
pub(super) const EMPTY: u32 = u32::MAX;

/// A node: 256 bytes, four cache lines, aligned to them. Slot `i` is
/// child `i`: its box is lane `i` of the planes; `count[i] == 0` makes it
/// the inner node `first[i]`, `count[i] == EMPTY` an unused slot, any
/// other count a leaf of `count[i]` primitives whose packed records
/// `first[i]` locates (see `packed::leaf_first`). Used slots come first.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub(super) struct Node {
    /// The children's boxes plane by plane: `min` x, y, z, then `max` x,
    /// y, z, one child a lane.
    planes: [[f32; WIDTH]; 6],
    pub(super) first: [u32; WIDTH],
    pub(super) count: [u32; WIDTH],
}

impl Node {
    /// Unused slots hold an inverted box (`min` +inf, `max` -inf): every
    /// ray enters it at +inf and leaves it at -inf on every axis, so it is
    /// never met and the node test needs no mask of used slots.
    const BLANK: Node = Node {
        planes: [
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        first: [0; WIDTH],
        count: [EMPTY; WIDTH],
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

    /// Sets the box of slot `i`, keeping its child.
    pub(super) fn set_bounds(&mut self, i: usize, bounds: &Aabb) {
        let (first, count) = (self.first[i], self.count[i]);
        self.set(i, bounds, first, count);
    }

    /// The box around all of its children's boxes.
    pub(super) fn union(&self) -> Aabb {
        self.used_slots()
            .fold(Aabb::empty(), |b, slot| b.union(&self.bounds(slot)))
    }

    /// The slots that hold a child (they come first).
    pub(super) fn used_slots(&self) -> impl Iterator<Item = usize> + '_ {
        (0..WIDTH).take_while(|&i| self.count[i] != EMPTY)
    }

    /// The box of slot `i`.
    pub(super) fn bounds(&self, i: usize) -> Aabb {
        let p = |plane: usize| self.planes[plane][i];
        Aabb::new(Vec3A::new(p(0), p(1), p(2)), Vec3A::new(p(3), p(4), p(5)))
    }

    /// Plane `plane`'s lanes `4 * half..4 * half + 4`.
    #[inline(always)]
    fn quarter(&self, plane: usize, half: usize) -> Vec4 {
        Vec4::from_slice(&self.planes[plane][4 * half..4 * half + 4])
    }
}

/// How the traversal tests a node's boxes: the instructions it is compiled
/// to, chosen once per tree from what the CPU has (`Bvh::build`). Every
/// code computes, lane by lane, the same IEEE operations in the same
/// order, so the nodes visited, the hits and the counts do not depend on
/// the CPU.
pub(super) trait NodeCode: Copy {
    /// A ray as this code's node test reads it.
    type Ray;

    fn ray(self, ray: &Ray) -> Self::Ray;

    /// The entry distance of each slot's box, and which boxes the ray
    /// meets in `(t_min, t_max)` (unused slots never: see [`Node::BLANK`]).
    ///
    /// Per axis, the ray enters a slab by its `min` plane when it goes up
    /// the axis and by its `max` plane when it goes down ([`Slabs`] picks
    /// them once per ray): the entry distance only raises `near`, the exit
    /// distance only lowers `far`, six operations a slab instead of the twelve
    /// of sorting the two planes and clamping each. It is the arithmetic of [`Aabb::intersect`] rearranged:
    /// there `min(max(t0, t_min), max(t1, t_min))` is `max(min(t0, t1),
    /// t_min)`, and `min(t0, t1)` is the entry plane's distance. A ray
    /// parallel to a slab whose origin lies on one of its planes gives
    /// `0 * inf = NaN` for that plane, which `max` and `min` drop here as
    /// the clamping drops it there (SSE and AVX return the second operand
    /// when one is NaN, and the running interval is the second operand):
    /// the ray counts as inside that slab. So a box is met here exactly
    /// when [`Aabb::intersect`] says so, at the same distance (up to the
    /// sign of a zero), and the choice of nodes to visit does not depend on
    /// the layout.
    fn hit(self, node: &Node, ray: &Self::Ray, t_min: f32, t_max: f32) -> ([f32; WIDTH], u32);
}

/// Per axis, the planes a ray enters and leaves a box's slab by, as
/// indices into [`Node::planes`]: `min` then `max` where the ray goes up
/// the axis, the other way round where it goes down.
#[derive(Clone, Copy)]
pub(super) struct Slabs {
    entry: [usize; 3],
    exit: [usize; 3],
}

impl Slabs {
    #[inline(always)]
    fn of(ray: &Ray) -> Self {
        // Bit `axis` set where the ray goes down that axis (-0.0 included).
        let down = ray.inv_dir.is_negative_bitmask() as usize;
        let entry = |axis: usize| axis + 3 * ((down >> axis) & 1);
        let exit = |axis: usize| axis + 3 * (!(down >> axis) & 1);
        Self {
            entry: [entry(0), entry(1), entry(2)],
            exit: [exit(0), exit(1), exit(2)],
        }
    }
}

/// The node test on four lanes at a time, twice: SSE on every x86-64 CPU,
/// glam's own vectors elsewhere.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Baseline;

/// A ray's origin and reciprocal direction, each coordinate in all four
/// lanes: made once per traversal, not once per node.
pub(super) struct WideRay {
    origin: [Vec4; 3],
    inv_dir: [Vec4; 3],
    slabs: Slabs,
}

impl NodeCode for Baseline {
    type Ray = WideRay;

    /// Written out lane by lane: built with `[0, 1, 2].map`, the compiler
    /// left a call per ray to an outlined `try_map` with bounds-checked
    /// `Vec3A` indexing.
    #[inline(always)]
    fn ray(self, ray: &Ray) -> WideRay {
        let (o, d) = (ray.origin, ray.inv_dir);
        WideRay {
            origin: [Vec4::splat(o.x), Vec4::splat(o.y), Vec4::splat(o.z)],
            inv_dir: [Vec4::splat(d.x), Vec4::splat(d.y), Vec4::splat(d.z)],
            slabs: Slabs::of(ray),
        }
    }

    #[inline(always)]
    fn hit(self, node: &Node, ray: &WideRay, t_min: f32, t_max: f32) -> ([f32; WIDTH], u32) {
        let half = |half: usize| {
            let mut near = Vec4::splat(t_min);
            let mut far = Vec4::splat(t_max);
            for axis in 0..3 {
                let entry = node.quarter(ray.slabs.entry[axis], half);
                let exit = node.quarter(ray.slabs.exit[axis], half);
                let t_entry = (entry - ray.origin[axis]) * ray.inv_dir[axis];
                let t_exit = (exit - ray.origin[axis]) * ray.inv_dir[axis];
                near = t_entry.max(near);
                far = t_exit.min(far);
            }
            (near, near.cmple(far).bitmask())
        };
        let ((low, low_mask), (high, high_mask)) = (half(0), half(1));
        let mut near = [0.0; WIDTH];
        near[..4].copy_from_slice(&low.to_array());
        near[4..].copy_from_slice(&high.to_array());
        (near, low_mask | high_mask << 4)
    }
}

/// The node test on all eight lanes at once with AVX. Made only by
/// [`Avx2::detect`], so holding one proves the CPU runs AVX2.
#[cfg(target_arch = "x86_64")]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Avx2(());

#[cfg(target_arch = "x86_64")]
impl Avx2 {
    /// The code, where the CPU reports AVX2.
    pub(super) fn detect() -> Option<Self> {
        is_x86_feature_detected!("avx2").then_some(Avx2(()))
    }
}

/// A ray's origin and reciprocal direction in all eight lanes of an AVX
/// register.
#[cfg(target_arch = "x86_64")]
pub(super) struct Avx2Ray {
    origin: [std::arch::x86_64::__m256; 3],
    inv_dir: [std::arch::x86_64::__m256; 3],
    slabs: Slabs,
}

#[cfg(target_arch = "x86_64")]
impl NodeCode for Avx2 {
    type Ray = Avx2Ray;

    #[inline(always)]
    fn ray(self, ray: &Ray) -> Avx2Ray {
        // SAFETY: an `Avx2` exists only where the CPU runs AVX2.
        unsafe { avx2::ray(ray) }
    }

    #[inline(always)]
    fn hit(self, node: &Node, ray: &Avx2Ray, t_min: f32, t_max: f32) -> ([f32; WIDTH], u32) {
        // SAFETY: an `Avx2` exists only where the CPU runs AVX2.
        unsafe { avx2::hit(node, ray, t_min, t_max) }
    }
}

/// [`Avx2`]'s instructions: compiled for AVX2 and inlined into the
/// traversals compiled for it (`Bvh::closest_hit_avx2`, `occluder_avx2`).
#[cfg(target_arch = "x86_64")]
mod avx2 {
    use std::arch::x86_64::*;

    use super::{Avx2Ray, Node, Ray, Slabs, WIDTH};

    /// # Safety
    /// The CPU must run AVX2.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub(super) unsafe fn ray(ray: &Ray) -> Avx2Ray {
        let (o, d) = (ray.origin, ray.inv_dir);
        Avx2Ray {
            origin: [
                _mm256_set1_ps(o.x),
                _mm256_set1_ps(o.y),
                _mm256_set1_ps(o.z),
            ],
            inv_dir: [
                _mm256_set1_ps(d.x),
                _mm256_set1_ps(d.y),
                _mm256_set1_ps(d.z),
            ],
            slabs: Slabs::of(ray),
        }
    }

    /// [`super::NodeCode::hit`], the operations of [`super::Baseline`]'s
    /// eight lanes at once, in its order and with its operand order (the
    /// running interval second, so a NaN distance leaves it be).
    ///
    /// # Safety
    /// The CPU must run AVX2.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub(super) unsafe fn hit(
        node: &Node,
        ray: &Avx2Ray,
        t_min: f32,
        t_max: f32,
    ) -> ([f32; WIDTH], u32) {
        let mut near = _mm256_set1_ps(t_min);
        let mut far = _mm256_set1_ps(t_max);
        for axis in 0..3 {
            let (entry, exit) = (ray.slabs.entry[axis], ray.slabs.exit[axis]);
            // SAFETY: each plane is WIDTH = 8 floats, what one unaligned
            // load reads.
            let (entry, exit) = unsafe {
                (
                    _mm256_loadu_ps(node.planes[entry].as_ptr()),
                    _mm256_loadu_ps(node.planes[exit].as_ptr()),
                )
            };
            let t_entry = _mm256_mul_ps(_mm256_sub_ps(entry, ray.origin[axis]), ray.inv_dir[axis]);
            let t_exit = _mm256_mul_ps(_mm256_sub_ps(exit, ray.origin[axis]), ray.inv_dir[axis]);
            near = _mm256_max_ps(t_entry, near);
            far = _mm256_min_ps(t_exit, far);
        }
        let mask = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OQ>(near, far)) as u32;
        let mut out = [0.0; WIDTH];
        // SAFETY: `out` holds the eight floats one unaligned store writes.
        unsafe { _mm256_storeu_ps(out.as_mut_ptr(), near) };
        (out, mask)
    }
}

/// Flattens the binary tree `tree` into 8-wide nodes, root first; every
/// node's children are opened, largest box first, until it has eight (or
/// only leaves remain), and inner children holding just two leaves become
/// one leaf where the SAH prefers it (see [`merged_leaves`]);
/// `traversal_cost` is the build's.
pub(super) fn flatten(tree: &BuildTree, prims: usize, traversal_cost: f32) -> Vec<Node> {
    let mut nodes = Vec::with_capacity(prims.div_ceil(4).max(1));
    nodes.push(Node::BLANK);
    if tree.is_empty() {
        return nodes;
    }
    let root = tree.node(NodeRef::ROOT);
    if root.is_leaf() {
        nodes[0].set(0, &root.bounds, root.first, root.count);
    } else {
        fill(tree, NodeRef::ROOT, 0, traversal_cost, &mut nodes);
    }
    nodes
}

/// What visiting a node of this tree costs in the SAH's units: a node
/// holding two leaves and nothing else is four cache lines fetched to
/// test two boxes, twice what a binary (or 4-wide) node costs, which the
/// build's SAH prices at `traversal_cost`.
pub(super) const NODE_VISIT_COST: f32 = 2.0;

/// The leaf that an inner node with two leaf children, `at`, becomes when
/// the SAH, a visit of its node priced as an 8-wide node's, says testing
/// both leaves' primitives at once is cheaper: `(first, count)`. The
/// build's binary SAH split them for a binary node's cost, but in the
/// 8-wide tree such a node is a whole node for two boxes (the Sierpinski
/// tetrahedron's tree was mostly those, and `mesh_large`'s rays are much
/// faster merged). Its primitives are contiguous: the right leaf's follow the
/// left one's.
fn merged_leaves(tree: &BuildTree, at: NodeRef, traversal_cost: f32) -> Option<(u32, u32)> {
    let node = tree.node(at);
    let (left, right) = (tree.node(node.left(at)), tree.node(node.right()));
    if !(left.is_leaf() && right.is_leaf()) {
        return None;
    }
    let cost = |n: &BuildNode| n.bounds.half_area() * leaf_cost(n.count, n.triangles);
    let area = node.bounds.half_area().max(f32::MIN_POSITIVE);
    let split = NODE_VISIT_COST * traversal_cost + (cost(left) + cost(right)) / area;
    let merged = leaf_cost(left.count + right.count, left.triangles + right.triangles);
    (merged <= split).then_some((left.first, left.count + right.count))
}

/// Writes the children of the inner node `inner` of `tree` into
/// `nodes[index]`, and their own children into new nodes, recursively.
fn fill(
    tree: &BuildTree,
    inner: NodeRef,
    index: usize,
    traversal_cost: f32,
    nodes: &mut Vec<Node>,
) {
    let mut slots = [inner; WIDTH];
    let mut used = 1;
    // Open the inner child with the largest box until every slot is used.
    while used < WIDTH {
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
        } else if let Some((first, count)) = merged_leaves(tree, at, traversal_cost) {
            nodes[index].set(slot, &child.bounds, first, count);
        } else {
            let child_index = nodes.len();
            nodes.push(Node::BLANK);
            nodes[index].set(slot, &child.bounds, child_index as u32, 0);
            fill(tree, at, child_index, traversal_cost, nodes);
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
        /// says of its box, at the same entry distance, and the test
        /// compiled for AVX2 says the same to the bit.
        #[test]
        fn a_node_meets_each_box_as_aabb_intersect_does(
            corners in prop::collection::vec((point(), point()), 1..=WIDTH),
            origin in point(),
            dir in (component(), component(), component()),
            t_min in prop_oneof![Just(0.0f32), 0.0f32..3.0],
            t_max in prop_oneof![Just(f32::INFINITY), 0.0f32..12.0],
        ) {
            let dir = Vec3A::new(dir.0, dir.1, dir.2);
            prop_assume!(dir.length() > 1e-3);
            let ray = Ray::new(origin, dir);
            let boxes: Vec<Aabb> = corners.iter().map(|&(a, b)| Aabb::new(a.min(b), a.max(b))).collect();
            let mut node = Node::BLANK;
            for (slot, b) in boxes.iter().enumerate() {
                node.set(slot, b, 0, 1);
            }
            let (near, mask) = Baseline.hit(&node, &Baseline.ray(&ray), t_min, t_max);
            #[cfg(target_arch = "x86_64")]
            if let Some(avx2) = Avx2::detect() {
                let (avx2_near, avx2_mask) = avx2.hit(&node, &avx2.ray(&ray), t_min, t_max);
                prop_assert_eq!(avx2_mask, mask);
                prop_assert_eq!(avx2_near.map(f32::to_bits), near.map(f32::to_bits));
            }
            for (slot, &near) in near.iter().enumerate() {
                let expected = boxes.get(slot).and_then(|b| b.intersect(&ray, t_min, t_max));
                prop_assert_eq!(mask >> slot & 1 == 1, expected.is_some(), "slot {}", slot);
                if let Some((entry, _)) = expected {
                    prop_assert_eq!(near, entry, "slot {}", slot);
                }
            }
        }
    }
}
