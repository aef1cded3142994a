//! A bounding volume hierarchy: a binned SAH build (parallel for large
//! subtrees) collapsed into 8-wide nodes whose eight boxes are tested at
//! once with SIMD (AVX2 where the CPU has it, SSE elsewhere), primitives
//! packed in leaf order, traversed with a small stack, nearest child first
//! for closest hits.

mod build;
mod node;
mod refit;
mod visit_boxes;

use std::mem::MaybeUninit;

use glam::Vec3A;
use rayon::prelude::*;

use crate::geometry::{Aabb, Ray, Shape};
use crate::stats::Counters;

use super::packed::{
    PackedShape, leaf_bounds, leaf_first, leaf_len, leaf_occluder, leaf_start, offer_leaf,
    pack_leaf,
};
use super::visits::{TraversalStep, VisitLog};
use super::{Hit, Nearest};
use build::{BuildPrim, build_tree};
#[cfg(target_arch = "x86_64")]
use node::Avx2;
use node::{Baseline, EMPTY, Node, NodeCode, WIDTH, flatten};

/// Build parameters, as a documented struct with named presets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BvhParams {
    /// SAH bins per axis, 2 to 32 (more are clamped).
    pub bins: usize,
    /// A node with more primitives than this is always split; at or below
    /// it, the SAH decides. 32 by default: the SAH keeps leaves that large
    /// only where boxes overlap so much that splitting saves nothing (the
    /// `shells` scene, whose spheres leaves test four at once: fewer nodes
    /// a ray and faster frames than with 16 or 4); the other scenes' trees
    /// are the same.
    pub max_leaf_size: usize,
    /// Cost of visiting a node relative to one primitive test.
    pub traversal_cost: f32,
    /// Subtrees with at least this many primitives are built in parallel.
    pub parallel_threshold: usize,
}

impl Default for BvhParams {
    /// Good trees for rendering, fast enough to build 1M triangles in well
    /// under a second on two cores.
    fn default() -> Self {
        Self {
            bins: 16,
            max_leaf_size: 32,
            traversal_cost: 1.0,
            parallel_threshold: 4096,
        }
    }
}

/// The id marking a shape without bounds while the build's primitives are
/// gathered.
const UNBOUNDED: u32 = u32::MAX;

/// Deepest tree allowed: traversal's fixed stack holds this many nodes.
/// Deepest binary tree the build makes; the 8-wide tree is no deeper.
const MAX_DEPTH: usize = 64;

/// Deferred children a traversal can hold: all but one per level, plus a
/// node's worth.
const STACK_SIZE: usize = (WIDTH - 1) * MAX_DEPTH + WIDTH;

/// The hierarchy, with its own packed copy of the primitives in leaf order
/// so a leaf's primitives are contiguous in memory.
#[derive(Debug, Clone)]
pub struct Bvh {
    nodes: Vec<Node>,
    prims: Vec<PackedShape>,
    /// The tree's cost ([`refit::tree_cost`]) when it was built, which a
    /// refit compares its own to.
    built_cost: f64,
    /// The AVX2 node test, where the CPU runs it; SSE's otherwise.
    #[cfg(target_arch = "x86_64")]
    avx2: Option<Avx2>,
}

/// A child waiting on the traversal stack: its slot's `first` and `count`
/// and the distance at which the ray enters its box.
#[derive(Clone, Copy)]
struct Deferred {
    first: u32,
    count: u32,
    entry: f32,
}

impl Bvh {
    /// Builds a hierarchy over the bounded shapes `ids` of `shapes`.
    pub fn build(shapes: &[Shape], ids: &[u32], params: &BvhParams) -> Bvh {
        // An indexed collect writes each thread's part in place; shapes
        // without bounds (callers pass none) are marked, then dropped.
        let mut prims: Vec<BuildPrim> = ids
            .par_iter()
            .map(|&id| match shapes[id as usize].bounds() {
                Some(bounds) => BuildPrim {
                    bounds,
                    id,
                    triangle: matches!(shapes[id as usize], Shape::Triangle(_)),
                },
                None => BuildPrim {
                    bounds: Aabb::empty(),
                    id: UNBOUNDED,
                    triangle: false,
                },
            })
            .collect();
        prims.retain(|p| p.id != UNBOUNDED);
        let root = build_tree(&mut prims, params);
        let mut nodes = flatten(&root, prims.len(), params.traversal_cost);
        let ids: Vec<u32> = prims.iter().map(|p| p.id).collect();
        let prims = pack_leaves(&mut nodes, &ids, shapes);
        Bvh {
            built_cost: refit::tree_cost(&nodes),
            nodes,
            prims,
            #[cfg(target_arch = "x86_64")]
            avx2: Avx2::detect(),
        }
    }

    /// Whether `other` has the same nodes and packed records, to the bit
    /// (unused lanes of a group hold NaN).
    #[cfg(test)]
    pub(in crate::accel) fn same_as(&self, other: &Bvh) -> bool {
        let bits = |prims: &[PackedShape]| prims.iter().map(PackedShape::bits).collect::<Vec<_>>();
        self.nodes == other.nodes && bits(&self.prims) == bits(&other.prims)
    }

    /// Nodes in the flattened tree (each holds up to eight children).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Bytes used by nodes and packed primitives.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>()
            + self.prims.len() * std::mem::size_of::<PackedShape>()
    }

    /// Checks the structural invariants: every primitive is reachable from
    /// the root exactly once, child boxes nest in their parent's, leaves
    /// bound their packed primitives (spheres and triangles; other shapes'
    /// data stays in the world), children point forwards, used slots come
    /// first. Returns a description of the first violation.
    pub fn validate(&self) -> Result<(), String> {
        let mut seen = vec![0u32; self.prims.len()];
        let whole = Aabb::new(Vec3A::NEG_INFINITY, Vec3A::INFINITY);
        let mut stack = vec![(0usize, 0usize, whole)];
        while let Some((index, depth, parent)) = stack.pop() {
            let node = self
                .nodes
                .get(index)
                .ok_or(format!("node {index} missing"))?;
            if depth > MAX_DEPTH {
                return Err(format!("node {index} is deeper than {MAX_DEPTH}"));
            }
            let inside = |outer: &Aabb, b: &Aabb| {
                (b.min.cmpge(outer.min) & b.max.cmple(outer.max)).all() || b.is_empty()
            };
            let used = node.used_slots().count();
            if node.count[used..].iter().any(|&c| c != EMPTY) {
                return Err(format!("node {index} has a gap between its children"));
            }
            for slot in 0..used {
                let bounds = node.bounds(slot);
                if !inside(&parent, &bounds) {
                    return Err(format!(
                        "child {slot} of node {index} is outside its parent"
                    ));
                }
                let (first, count) = (node.first[slot] as usize, node.count[slot] as usize);
                if count == 0 {
                    if first <= index {
                        return Err(format!("child {slot} of {index} points backwards"));
                    }
                    stack.push((first, depth + 1, bounds));
                    continue;
                }
                let (records, boxes) = leaf_bounds(&self.prims, first, count)
                    .ok_or(format!("leaf {slot} of {index}: primitives missing"))?;
                let start = leaf_start(first);
                seen[start..start + records]
                    .iter_mut()
                    .for_each(|n| *n += 1);
                for (p, b) in boxes.iter().enumerate() {
                    if b.is_some_and(|b| !inside(&bounds, &b)) {
                        return Err(format!(
                            "leaf {slot} of {index} does not bound its primitive {p}"
                        ));
                    }
                }
            }
        }
        match seen.iter().position(|&n| n != 1) {
            Some(p) => Err(format!("primitive {p} is reached {} times", seen[p])),
            None => Ok(()),
        }
    }

    /// The nearest hit in `(t_min, t_max)`, telling `log` each node
    /// visited and each leaf tested.
    #[inline]
    pub(in crate::accel) fn closest_hit(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
        log: &mut impl VisitLog,
    ) -> Option<Hit> {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = self.avx2 {
            // SAFETY: an `Avx2` exists only where the CPU runs AVX2.
            return unsafe {
                self.closest_hit_avx2(avx2, shapes, ray, t_min, t_max, counters, log)
            };
        }
        self.closest_hit_in(Baseline, shapes, ray, t_min, t_max, counters, log)
    }

    /// [`Bvh::closest_hit`] compiled for AVX2.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[allow(clippy::too_many_arguments)]
    unsafe fn closest_hit_avx2(
        &self,
        avx2: Avx2,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
        log: &mut impl VisitLog,
    ) -> Option<Hit> {
        self.closest_hit_in(avx2, shapes, ray, t_min, t_max, counters, log)
    }

    /// The closest-hit traversal with `code`'s node test, inlined into the
    /// function compiled for it.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn closest_hit_in<C: NodeCode>(
        &self,
        code: C,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
        counters: &mut Counters,
        log: &mut impl VisitLog,
    ) -> Option<Hit> {
        if self.prims.is_empty() {
            return None;
        }
        let wide = code.ray(ray);
        let mut nearest = Nearest::new(t_max);
        let mut stack = NodeStack::<Deferred>::new();
        let mut visited = 0u64;
        let mut tests = 0u64;
        let mut next = Deferred {
            first: 0,
            count: 0,
            entry: t_min,
        };
        loop {
            if next.count > 0 {
                let (first, count) = (next.first as usize, next.count as usize);
                log.step(TraversalStep::Leaf(next.first, next.count), tests);
                let prims = &self.prims;
                offer_leaf(
                    prims,
                    first,
                    count,
                    shapes,
                    ray,
                    t_min,
                    &mut nearest,
                    &mut tests,
                );
                t_max = nearest.t_max(t_max);
            } else {
                visited += 1;
                log.step(TraversalStep::Node(next.first), tests);
                let node = &self.nodes[next.first as usize];
                let (near, mask) = code.hit(node, &wide, t_min, t_max);
                if mask != 0 {
                    next = visit_nearest(node, near, mask, &mut stack);
                    continue;
                }
            }
            // Pop the next child, skipping those now beyond the closest hit.
            loop {
                let Some(deferred) = stack.pop() else {
                    counters.nodes_visited += visited;
                    counters.intersection_tests += tests;
                    return nearest.best;
                };
                if deferred.entry <= t_max {
                    next = deferred;
                    break;
                }
            }
        }
    }

    /// The first shape found on the ray in `(t_min, t_max)`.
    #[inline]
    pub fn occluder(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> Option<u32> {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = self.avx2 {
            // SAFETY: an `Avx2` exists only where the CPU runs AVX2.
            return unsafe { self.occluder_avx2(avx2, shapes, ray, t_min, t_max, counters) };
        }
        self.occluder_in(Baseline, shapes, ray, t_min, t_max, counters)
    }

    /// [`Bvh::occluder`] compiled for AVX2.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn occluder_avx2(
        &self,
        avx2: Avx2,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> Option<u32> {
        self.occluder_in(avx2, shapes, ray, t_min, t_max, counters)
    }

    /// The any-hit traversal with `code`'s node test, inlined into the
    /// function compiled for it.
    #[inline(always)]
    fn occluder_in<C: NodeCode>(
        &self,
        code: C,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> Option<u32> {
        if self.prims.is_empty() {
            return None;
        }
        let wide = code.ray(ray);
        // Children are deferred in slot order; any occluder ends the search,
        // so no sorting.
        let mut stack = NodeStack::<(u32, u32)>::new();
        let mut next = (0u32, 0u32);
        let mut found = None;
        let mut visited = 0u64;
        let mut tests = 0u64;
        loop {
            let (first, count) = (next.0 as usize, next.1 as usize);
            if count > 0 {
                let prims = &self.prims;
                found = leaf_occluder(prims, first, count, shapes, ray, t_min, t_max, &mut tests);
                if found.is_some() {
                    break;
                }
            } else {
                visited += 1;
                let node = &self.nodes[first];
                let (_, mut mask) = code.hit(node, &wide, t_min, t_max);
                while mask != 0 {
                    let slot = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    stack.push((node.first[slot], node.count[slot]));
                }
            }
            match stack.pop() {
                Some(deferred) => next = deferred,
                None => break,
            }
        }
        counters.nodes_visited += visited;
        counters.intersection_tests += tests;
        found
    }
}

/// The packed primitives of the leaves of `nodes`, leaf after leaf in the
/// build's order `ids` (packed in parallel), each leaf slot's `first`
/// turned from its place in `ids` into the place of its records. Leaves
/// without groups keep the records and places they had before groups.
fn pack_leaves(nodes: &mut [Node], ids: &[u32], shapes: &[Shape]) -> Vec<PackedShape> {
    let mut leaves: Vec<(usize, usize)> = (0..nodes.len())
        .flat_map(|n| (0..WIDTH).map(move |slot| (n, slot)))
        .filter(|&(n, slot)| !matches!(nodes[n].count[slot], 0 | EMPTY))
        .collect();
    leaves.sort_unstable_by_key(|&(n, slot)| nodes[n].first[slot]);
    let ids_of = |&(n, slot): &(usize, usize)| {
        let (first, count) = (nodes[n].first[slot] as usize, nodes[n].count[slot] as usize);
        &ids[first..first + count]
    };
    let lens: Vec<(usize, bool)> = leaves
        .par_iter()
        .map(|leaf| leaf_len(shapes, ids_of(leaf)))
        .collect();
    // Filled in parallel: the first touch of each page (page faults) is
    // most of the cost of a large buffer.
    let mut prims = Vec::new();
    (0..lens.iter().map(|l| l.0).sum())
        .into_par_iter()
        .map(|_| PackedShape::BLANK)
        .collect_into_vec(&mut prims);
    let mut rest = prims.as_mut_slice();
    let mut outs = Vec::with_capacity(leaves.len());
    for &(len, _) in &lens {
        let (out, tail) = rest.split_at_mut(len);
        outs.push(out);
        rest = tail;
    }
    outs.into_par_iter()
        .zip(&leaves)
        .for_each(|(out, leaf)| pack_leaf(shapes, ids_of(leaf), out));
    let mut start = 0;
    for (&(n, slot), (len, grouped)) in leaves.iter().zip(lens) {
        nodes[n].first[slot] = leaf_first(start, grouped);
        start += len;
    }
    prims
}

/// The hit children of `node` (`mask`, entered at `near`) sorted nearest
/// first, ties in slot order: the others are deferred farthest first and
/// the nearest is returned to visit now. One and two hit children, the
/// common cases, take no sort.
#[inline(always)]
fn visit_nearest(
    node: &Node,
    near: [f32; WIDTH],
    mut mask: u32,
    stack: &mut NodeStack<Deferred>,
) -> Deferred {
    let child = |slot: usize| Deferred {
        first: node.first[slot],
        count: node.count[slot],
        entry: near[slot],
    };
    let a = mask.trailing_zeros() as usize;
    mask &= mask - 1;
    if mask == 0 {
        return child(a);
    }
    let b = mask.trailing_zeros() as usize;
    mask &= mask - 1;
    if mask == 0 {
        let (now, later) = if near[b] < near[a] { (b, a) } else { (a, b) };
        stack.push(child(later));
        return child(now);
    }
    let mut order = [0; WIDTH];
    (order[0], order[1]) = if near[b] < near[a] { (b, a) } else { (a, b) };
    let mut n = 2;
    while mask != 0 {
        let slot = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        let mut j = n;
        while j > 0 && near[order[j - 1]] > near[slot] {
            order[j] = order[j - 1];
            j -= 1;
        }
        order[j] = slot;
        n += 1;
    }
    for &slot in order[1..n].iter().rev() {
        stack.push(child(slot));
    }
    child(order[0])
}

/// The children a traversal has deferred: at most seven per level of the
/// tree (a node pushes the hit children it does not visit at once).
///
/// Its slots start uninitialised: traversal runs once per ray, and zeroing
/// a fixed array of slots on every call was the largest single item of
/// balls_medium's instructions after the traversal itself.
struct NodeStack<T: Copy> {
    slots: [MaybeUninit<T>; STACK_SIZE],
    len: usize,
}

impl<T: Copy> NodeStack<T> {
    #[inline]
    fn new() -> Self {
        Self {
            slots: [const { MaybeUninit::uninit() }; STACK_SIZE],
            len: 0,
        }
    }

    /// Panics (index out of bounds) if the tree is deeper than the build allows.
    #[inline]
    fn push(&mut self, item: T) {
        self.slots[self.len] = MaybeUninit::new(item);
        self.len += 1;
    }

    #[inline]
    fn pop(&mut self) -> Option<T> {
        self.len = self.len.checked_sub(1)?;
        // SAFETY: `push` wrote every slot below the old `len` and `pop` only
        // lowers it, so slot `len` holds a value pushed earlier.
        Some(unsafe { self.slots[self.len].assume_init() })
    }
}

impl Bvh {
    /// The box of depth 0 as drawn and inspected: the union of the root's
    /// children (`None` for an empty tree).
    pub(in crate::accel) fn scene_box(&self) -> Option<Aabb> {
        let root = self.nodes.first()?;
        root.used_slots()
            .map(|i| root.bounds(i))
            .reduce(|a, b| a.union(&b))
    }

    /// The boxes of the 8-wide nodes' children at `depth` (0 is the whole
    /// scene's box, 1 the root's up to eight children), with the leaves above
    /// it so the scene stays covered; every leaf for `None`. Read only, for
    /// drawing the structure over the image.
    pub fn boxes(&self, depth: Option<u32>) -> Vec<Aabb> {
        if depth == Some(0) {
            return self.scene_box().into_iter().collect();
        }
        let mut out = Vec::new();
        let mut stack = vec![(0usize, 1u32)];
        while let Some((index, d)) = stack.pop() {
            let Some(node) = self.nodes.get(index) else {
                continue;
            };
            for i in node.used_slots() {
                if node.count[i] != 0 || depth == Some(d) {
                    out.push(node.bounds(i));
                } else {
                    stack.push((node.first[i] as usize, d + 1));
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::packed::MIN_GROUPED_TRIANGLES;
    use crate::accel::tests::{Rand, boxes_and_bounds, random_query, random_shapes};
    use crate::accel::visits::NoLog;
    use crate::geometry::{Plane, Sphere, Triangle};

    /// The traversals compiled for AVX2 and for the baseline find the same
    /// hit, the same occluder, and count the same nodes and tests, on
    /// scenes of every bounded primitive and rays along their planes and
    /// from their corners: the views' counts do not depend on the CPU.
    /// Without AVX2 there is one traversal only: the test says so and
    /// compares nothing, rather than the baseline with itself.
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn avx2_and_baseline_traversals_agree_hit_for_hit_and_count_for_count() {
        if !is_x86_feature_detected!("avx2") {
            eprintln!("this CPU has no AVX2: the AVX2 traversal is neither used nor compared");
            return;
        }
        for (seed, count) in [(1, 3), (2, 60), (3, 700), (4, 3000)] {
            let shapes = random_shapes(seed, count, 0);
            let ids: Vec<u32> = (0..shapes.len() as u32).collect();
            let fast = Bvh::build(&shapes, &ids, &BvhParams::default());
            assert!(
                fast.avx2.is_some(),
                "the tree uses AVX2 where the CPU has it"
            );
            let baseline = Bvh {
                avx2: None,
                ..fast.clone()
            };
            let (boxes, bounds) = boxes_and_bounds(&shapes);
            let mut r = Rand(seed ^ 0x2b2b);
            for _ in 0..4000 {
                let Some((ray, t_min, t_max)) = random_query(&mut r, &boxes, &bounds) else {
                    continue;
                };
                let run = |bvh: &Bvh| {
                    let (mut closest, mut any) = (Counters::default(), Counters::default());
                    let hit =
                        bvh.closest_hit(&shapes, &ray, t_min, t_max, &mut closest, &mut NoLog);
                    let occluder = bvh.occluder(&shapes, &ray, t_min, t_max, &mut any);
                    let work = |c: &Counters| (c.nodes_visited, c.intersection_tests);
                    (hit, work(&closest), occluder, work(&any))
                };
                assert_eq!(run(&fast), run(&baseline), "{ray:?} in ({t_min}, {t_max})");
            }
        }
    }

    /// The corners of a regular tetrahedron.
    const TETRAHEDRON: [Vec3A; 4] = [
        Vec3A::new(1.0, 1.0, 1.0),
        Vec3A::new(1.0, -1.0, -1.0),
        Vec3A::new(-1.0, 1.0, -1.0),
        Vec3A::new(-1.0, -1.0, 1.0),
    ];

    /// The faces of the Sierpinski tetrahedron of `level` on `corners`.
    fn sierpinski(corners: [Vec3A; 4], level: u32, out: &mut Vec<Shape>) {
        if level == 0 {
            for skip in 0..4 {
                let [a, b, c] = [0, 1, 2].map(|i| corners[(skip + 1 + i) % 4]);
                out.extend(Triangle::new(a, b, c).map(Shape::Triangle));
            }
            return;
        }
        for keep in 0..4 {
            let half = corners.map(|c| (c + corners[keep]) * 0.5);
            sierpinski(half, level - 1, out);
        }
    }

    /// The Sierpinski tetrahedron (`mesh_large`) splits four ways at every
    /// level, two binary levels, and an 8-wide node takes three: at level
    /// 5 (ten binary levels below the root, leaves of one small
    /// tetrahedron) the collapse left bottom nodes holding just two
    /// leaves. Those become one leaf of both, and every primitive is still
    /// reached once.
    #[test]
    fn nodes_of_just_two_leaves_become_one_leaf() {
        let mut shapes = Vec::new();
        sierpinski(TETRAHEDRON, 5, &mut shapes);
        assert_eq!(shapes.len(), 4 * 4usize.pow(5));
        let ids: Vec<u32> = (0..shapes.len() as u32).collect();
        let bvh = Bvh::build(&shapes, &ids, &BvhParams::default());
        assert_eq!(bvh.validate(), Ok(()));
        let two_leaves = bvh
            .nodes
            .iter()
            .filter(|node| {
                let used: Vec<usize> = node.used_slots().collect();
                used.len() == 2 && used.iter().all(|&slot| node.count[slot] != 0)
            })
            .count();
        assert_eq!(two_leaves, 0, "of {} nodes", bvh.nodes.len());
        let largest = bvh
            .nodes
            .iter()
            .flat_map(|n| n.count)
            .filter(|&c| c != EMPTY)
            .max();
        assert_eq!(largest, Some(8), "two tetrahedra a leaf");
    }

    /// A shape without bounds among the ids is left out of the tree, not
    /// given a box: a plane's rays find the spheres only.
    #[test]
    fn shapes_without_bounds_stay_out_of_the_tree() {
        let shapes = [
            Shape::Sphere(Sphere::new(Vec3A::new(0.0, 0.0, 5.0), 1.0)),
            Shape::Plane(Plane::from_points([Vec3A::ZERO, Vec3A::X, Vec3A::Y]).unwrap()),
            Shape::Sphere(Sphere::new(Vec3A::new(3.0, 0.0, 5.0), 1.0)),
        ];
        let bvh = Bvh::build(&shapes, &[0, 1, 2], &BvhParams::default());
        assert_eq!(bvh.validate(), Ok(()));
        let down = Ray::new(Vec3A::new(3.0, 0.0, 10.0), -Vec3A::Z);
        let mut counters = Counters::default();
        let hit = bvh.closest_hit(
            &shapes,
            &down,
            0.0,
            f32::INFINITY,
            &mut counters,
            &mut NoLog,
        );
        assert_eq!(hit.map(|h| h.shape), Some(2));
        let past = Ray::new(Vec3A::new(9.0, 0.0, 10.0), -Vec3A::Z);
        let miss = bvh.closest_hit(
            &shapes,
            &past,
            0.0,
            f32::INFINITY,
            &mut counters,
            &mut NoLog,
        );
        assert_eq!(miss, None, "the plane is not in the tree");
    }

    /// A mesh's leaves hold its triangles in groups of four, which the
    /// leaves test at once: the SAH prices a group, not each triangle.
    /// Priced one test a triangle, this bumpy grid's 2048 triangles went
    /// into 1024 leaves of two, none of them tested in a group.
    #[test]
    fn mesh_leaves_hold_triangles_in_groups() {
        let height = |x: usize, y: usize| ((x * 7 + y * 13) % 5) as f32 * 0.1;
        let corner = |x: usize, y: usize| Vec3A::new(x as f32, y as f32, height(x, y));
        let mut shapes = Vec::new();
        for y in 0..32 {
            for x in 0..32 {
                let [a, b, c, d] =
                    [(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)].map(|(x, y)| corner(x, y));
                shapes.extend(
                    [Triangle::new(a, b, c), Triangle::new(b, d, c)]
                        .map(|t| Shape::Triangle(t.unwrap())),
                );
            }
        }
        let ids: Vec<u32> = (0..shapes.len() as u32).collect();
        let bvh = Bvh::build(&shapes, &ids, &BvhParams::default());
        assert_eq!(bvh.validate(), Ok(()));
        let leaves: Vec<usize> = bvh
            .nodes
            .iter()
            .flat_map(|node| node.count)
            .filter(|&count| !matches!(count, 0 | EMPTY))
            .map(|count| count as usize)
            .collect();
        let grouped: usize = leaves.iter().filter(|&&n| n >= MIN_GROUPED_TRIANGLES).sum();
        assert!(
            grouped * 10 >= shapes.len() * 9,
            "{grouped} of {} triangles in leaves of four or more ({} leaves)",
            shapes.len(),
            leaves.len()
        );
    }
}
