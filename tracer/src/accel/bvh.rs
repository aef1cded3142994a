//! A bounding volume hierarchy: binned SAH build (parallel for large
//! subtrees), flattened into a compact node array with siblings adjacent,
//! traversed with a small stack, nearer child first.

use std::mem::MaybeUninit;

use glam::{UVec3, Vec3A, Vec4, Vec4Swizzles};
use rayon::prelude::*;

use crate::geometry::{Aabb, Ray, Shape};
use crate::stats::Counters;

use super::Hit;

/// Build parameters, as a documented struct with named presets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BvhParams {
    /// SAH bins per axis, 2 to 32 (more are clamped).
    pub bins: usize,
    /// A node with more primitives than this is always split.
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
            max_leaf_size: 4,
            traversal_cost: 1.0,
            parallel_threshold: 4096,
        }
    }
}

/// Deepest tree allowed: traversal's fixed stack holds this many nodes.
const MAX_DEPTH: usize = 64;

/// Most SAH bins per axis: the bins live in fixed arrays on the stack
/// rather than in a dozen small allocations per node.
const MAX_BINS: usize = 32;

/// A node: 32 bytes, so two siblings share a cache line, and two aligned
/// SIMD loads fetch its box. The `w` lanes carry the integers (as float
/// bits): `count > 0` marks a leaf holding primitives `first..first +
/// count`; otherwise the children are nodes `first` and `first + 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
struct Node {
    /// Box minimum; `w` = first.
    lo: Vec4,
    /// Box maximum; `w` = count.
    hi: Vec4,
}

impl Node {
    fn new(bounds: Aabb, first: u32, count: u32) -> Self {
        let (min, max) = if bounds.is_empty() {
            (Vec3A::ZERO, Vec3A::ZERO)
        } else {
            (bounds.min, bounds.max)
        };
        Self {
            lo: min.extend(f32::from_bits(first)),
            hi: max.extend(f32::from_bits(count)),
        }
    }

    #[inline]
    fn first(&self) -> u32 {
        self.lo.w.to_bits()
    }

    #[inline]
    fn count(&self) -> u32 {
        self.hi.w.to_bits()
    }

    #[inline]
    fn bounds(&self) -> Aabb {
        Aabb::new(Vec3A::from_vec4(self.lo), Vec3A::from_vec4(self.hi))
    }

    #[inline]
    fn hit(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        self.bounds()
            .intersect(ray, t_min, t_max)
            .map(|(near, _)| near)
    }
}

/// The entry distances of the two sibling boxes `pair[0]` and `pair[1]`
/// (`None` where the ray misses), tested together.
///
/// Each box gets exactly the per-lane arithmetic of [`Aabb::intersect`];
/// only the horizontal max and min that turn three slab intervals into one
/// are shared, one shuffle sequence for both boxes instead of one each, and
/// a single comparison decides both. Max and min return one of their
/// operands, so reducing in another order gives the same distances (up to
/// the sign of a zero, which no comparison sees): traversal visits the same
/// nodes as testing each box alone. Measured: -6% instructions on
/// balls_medium.
#[inline]
fn hit_pair(pair: &[Node; 2], ray: &Ray, t_min: f32, t_max: f32) -> [Option<f32>; 2] {
    let lo = Vec3A::splat(t_min);
    let hi = Vec3A::splat(t_max);
    let interval = |node: &Node| {
        let t0 = (Vec3A::from_vec4(node.lo) - ray.origin) * ray.inv_dir;
        let t1 = (Vec3A::from_vec4(node.hi) - ray.origin) * ray.inv_dir;
        (t0.max(lo).min(t1.max(lo)), t0.min(hi).max(t1.min(hi)))
    };
    let (near_l, far_l) = interval(&pair[0]);
    let (near_r, far_r) = interval(&pair[1]);
    // Lanes [l.x, l.y, r.x, r.y] against [l.z, l.z, r.z, r.z], then each
    // pair of lanes against its neighbour: lane 0 is the left box's value,
    // lane 2 the right box's.
    let near = Vec4::new(near_l.x, near_l.y, near_r.x, near_r.y)
        .max(Vec4::new(near_l.z, near_l.z, near_r.z, near_r.z));
    let near = near.max(near.yxwz());
    let far = Vec4::new(far_l.x, far_l.y, far_r.x, far_r.y)
        .min(Vec4::new(far_l.z, far_l.z, far_r.z, far_r.z));
    let far = far.min(far.yxwz());
    let inside = near.cmple(far);
    [
        inside.test(0).then_some(near.x),
        inside.test(2).then_some(near.z),
    ]
}

/// The hierarchy, with its own copy of the shapes in leaf order so a leaf's
/// primitives are contiguous in memory.
#[derive(Debug, Clone)]
pub struct Bvh {
    nodes: Vec<Node>,
    shapes: Vec<Shape>,
    /// Index in the world's shapes of each entry of `shapes`.
    ids: Vec<u32>,
}

/// A primitive during the build: 48 bytes. The centroid is recomputed
/// from the box where needed rather than stored, as the build is bound by
/// the passes over this array, not by arithmetic.
#[derive(Clone, Copy)]
struct BuildPrim {
    bounds: Aabb,
    id: u32,
}

impl BuildPrim {
    #[inline]
    fn centroid(&self) -> Vec3A {
        self.bounds.centre()
    }
}

/// The tree before flattening.
enum BuildNode {
    Leaf {
        bounds: Aabb,
        first: u32,
        count: u32,
    },
    Inner {
        bounds: Aabb,
        children: Box<[BuildNode; 2]>,
    },
}

impl Bvh {
    /// Builds a hierarchy over the bounded shapes `ids` of `shapes`.
    pub fn build(shapes: &[Shape], ids: &[u32], params: &BvhParams) -> Bvh {
        let mut prims: Vec<BuildPrim> = ids
            .par_iter()
            .filter_map(|&id| {
                let bounds = shapes[id as usize].bounds()?;
                Some(BuildPrim { bounds, id })
            })
            .collect();
        let root = build_node(&mut prims, 0, 0, params);
        let mut nodes = Vec::with_capacity(2 * prims.len().max(1));
        nodes.push(Node::new(Aabb::empty(), 0, 0));
        flatten(&root, 0, &mut nodes);
        let ids: Vec<u32> = prims.iter().map(|p| p.id).collect();
        Bvh {
            nodes,
            shapes: ids
                .par_iter()
                .map(|&i| shapes[i as usize].clone())
                .collect(),
            ids,
        }
    }

    /// The two children of an inner node, stored side by side from `first`.
    #[inline]
    fn children(&self, first: usize) -> &[Node; 2] {
        self.nodes[first..first + 2]
            .try_into()
            .expect("an inner node's children are adjacent nodes")
    }

    /// Nodes in the flattened tree.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Bytes used by nodes, shapes and ids.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>()
            + self.shapes.len() * std::mem::size_of::<Shape>()
            + self.ids.len() * 4
    }

    /// Checks the structural invariants: every primitive is reachable from
    /// the root exactly once, child bounds nest in their parent's, leaves
    /// bound their primitives. Returns a description of the first violation.
    pub fn validate(&self) -> Result<(), String> {
        let mut seen = vec![0u32; self.shapes.len()];
        let mut stack = vec![(0usize, 0usize)];
        while let Some((index, depth)) = stack.pop() {
            let node = self
                .nodes
                .get(index)
                .ok_or(format!("node {index} missing"))?;
            if depth > MAX_DEPTH {
                return Err(format!("node {index} is deeper than {MAX_DEPTH}"));
            }
            let bounds = node.bounds();
            let inside = |b: &Aabb| {
                (b.min.cmpge(bounds.min) & b.max.cmple(bounds.max)).all() || b.is_empty()
            };
            if node.count() > 0 {
                let range = node.first() as usize..(node.first() + node.count()) as usize;
                for p in range {
                    let shape = self
                        .shapes
                        .get(p)
                        .ok_or(format!("leaf {index}: primitive {p} missing"))?;
                    seen[p] += 1;
                    if let Some(b) = shape.bounds() {
                        if !inside(&b) {
                            return Err(format!("leaf {index} does not bound primitive {p}"));
                        }
                    }
                }
            } else {
                if self.shapes.is_empty() {
                    continue;
                }
                for child in [node.first() as usize, node.first() as usize + 1] {
                    let c = self
                        .nodes
                        .get(child)
                        .ok_or(format!("child {child} of {index} missing"))?;
                    if child <= index {
                        return Err(format!("child {child} of {index} points backwards"));
                    }
                    if !inside(&c.bounds()) {
                        return Err(format!("child {child} is not inside its parent {index}"));
                    }
                    stack.push((child, depth + 1));
                }
            }
        }
        match seen.iter().position(|&n| n != 1) {
            Some(p) => Err(format!("primitive {p} is reached {} times", seen[p])),
            None => Ok(()),
        }
    }

    /// The nearest hit in `(t_min, t_max)`.
    #[inline]
    pub fn closest_hit(
        &self,
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
        counters: &mut Counters,
    ) -> Option<Hit> {
        if self.shapes.is_empty() {
            return None;
        }
        let mut best = None;
        // Deferred far children with their entry distance, so a pop can
        // skip a node beyond the closest hit without re-testing its box.
        let mut stack = NodeStack::<(u32, f32)>::new();
        let mut node = &self.nodes[0];
        node.hit(ray, t_min, t_max)?;
        let mut visited = 0u64;
        let mut tests = 0u64;
        loop {
            visited += 1;
            let first = node.first() as usize;
            let count = node.count() as usize;
            if count > 0 {
                tests += count as u64;
                for (i, shape) in self.shapes[first..first + count].iter().enumerate() {
                    if let Some(t) = shape.intersect(ray, t_min, t_max) {
                        t_max = t;
                        best = Some(first + i);
                    }
                }
            } else {
                let pair = self.children(first);
                let (left, right) = (&pair[0], &pair[1]);
                match hit_pair(pair, ray, t_min, t_max) {
                    [Some(l), Some(r)] => {
                        let (near, far, far_t) = if l <= r {
                            (left, first + 1, r)
                        } else {
                            (right, first, l)
                        };
                        stack.push((far as u32, far_t));
                        node = near;
                        continue;
                    }
                    [Some(_), None] => {
                        node = left;
                        continue;
                    }
                    [None, Some(_)] => {
                        node = right;
                        continue;
                    }
                    [None, None] => {}
                }
            }
            // Pop the next node, skipping those now beyond the closest hit.
            loop {
                let Some((index, entry)) = stack.pop() else {
                    counters.nodes_visited += visited;
                    counters.intersection_tests += tests;
                    return best.map(|i| Hit {
                        t: t_max,
                        shape: self.ids[i],
                    });
                };
                if entry <= t_max {
                    node = &self.nodes[index as usize];
                    break;
                }
            }
        }
    }

    /// Whether anything lies on the ray in `(t_min, t_max)`.
    #[inline]
    pub fn any_hit(&self, ray: &Ray, t_min: f32, t_max: f32, counters: &mut Counters) -> bool {
        if self.shapes.is_empty() {
            return false;
        }
        let mut node = &self.nodes[0];
        if node.hit(ray, t_min, t_max).is_none() {
            return false;
        }
        // Children are tested at their parent and only boxes the ray meets
        // are deferred, left before right: the same nodes are visited in
        // the same order as popping every child and testing it then, with
        // fewer stack operations.
        let mut stack = NodeStack::<u32>::new();
        let mut found = false;
        let mut visited = 0u64;
        let mut tests = 0u64;
        loop {
            visited += 1;
            let first = node.first() as usize;
            let count = node.count() as usize;
            if count > 0 {
                for shape in &self.shapes[first..first + count] {
                    tests += 1;
                    if shape.intersect(ray, t_min, t_max).is_some() {
                        found = true;
                        break;
                    }
                }
                if found {
                    break;
                }
            } else {
                let pair = self.children(first);
                let (left, right) = (&pair[0], &pair[1]);
                match hit_pair(pair, ray, t_min, t_max).map(|entry| entry.is_some()) {
                    [true, true] => {
                        stack.push(first as u32 + 1);
                        node = left;
                        continue;
                    }
                    [true, false] => {
                        node = left;
                        continue;
                    }
                    [false, true] => {
                        node = right;
                        continue;
                    }
                    [false, false] => {}
                }
            }
            match stack.pop() {
                Some(index) => node = &self.nodes[index as usize],
                None => break,
            }
        }
        counters.nodes_visited += visited;
        counters.intersection_tests += tests;
        found
    }
}

/// The nodes a traversal has deferred, at most one per level of the tree.
///
/// Its slots start uninitialised: traversal runs once per ray, and zeroing
/// a `[(u32, f32); MAX_DEPTH + 1]` array on every call was 3.8% of all
/// instructions on balls_medium (callgrind), the largest single item after
/// the traversal itself.
struct NodeStack<T: Copy> {
    slots: [MaybeUninit<T>; MAX_DEPTH + 1],
    len: usize,
}

impl<T: Copy> NodeStack<T> {
    #[inline]
    fn new() -> Self {
        Self {
            slots: [const { MaybeUninit::uninit() }; MAX_DEPTH + 1],
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

/// Builds the subtree over `prims`, which start at `offset` in the final
/// primitive order.
fn build_node(prims: &mut [BuildPrim], offset: u32, depth: usize, params: &BvhParams) -> BuildNode {
    // One pass for the node's box and its centroids' box.
    let (bounds, centroids) = prims
        .iter()
        .fold((Aabb::empty(), Aabb::empty()), |(b, c), p| {
            (b.union(&p.bounds), c.grow(p.centroid()))
        });
    let leaf = BuildNode::Leaf {
        bounds,
        first: offset,
        count: prims.len() as u32,
    };
    if prims.len() <= 1 || depth >= MAX_DEPTH - 1 {
        return leaf;
    }
    let split = match best_split(prims, bounds, centroids, params) {
        Some((axis, position, cost)) => {
            let leaf_cost = prims.len() as f32;
            if cost >= leaf_cost && prims.len() <= params.max_leaf_size {
                return leaf;
            }
            partition(prims, |p| p.centroid()[axis] < position)
        }
        None if prims.len() <= params.max_leaf_size => return leaf,
        // All centroids coincide: no plane separates them, so halve the list.
        None => prims.len() / 2,
    };
    let split = if split == 0 || split == prims.len() {
        prims.len() / 2
    } else {
        split
    };
    let (left, right) = prims.split_at_mut(split);
    let right_offset = offset + split as u32;
    let (l, r) = if left.len() + right.len() >= params.parallel_threshold {
        rayon::join(
            || build_node(left, offset, depth + 1, params),
            || build_node(right, right_offset, depth + 1, params),
        )
    } else {
        (
            build_node(left, offset, depth + 1, params),
            build_node(right, right_offset, depth + 1, params),
        )
    };
    BuildNode::Inner {
        bounds,
        children: Box::new([l, r]),
    }
}

/// The cheapest binned SAH split: `(axis, plane position, cost)` in units
/// of primitive tests, or `None` when the centroids (bounded by
/// `centroids`) do not spread. One pass over the primitives bins all three
/// axes.
fn best_split(
    prims: &[BuildPrim],
    bounds: Aabb,
    centroids: Aabb,
    params: &BvhParams,
) -> Option<(usize, f32, f32)> {
    let extent = centroids.extent();
    let splittable = [0, 1, 2].map(|axis| extent[axis] > 0.0 && extent[axis].is_finite());
    if !splittable.contains(&true) {
        return None;
    }
    let bins = params.bins.clamp(2, MAX_BINS);
    let parent_area = bounds.half_area().max(f32::MIN_POSITIVE);
    // Axes that cannot split get an infinite or NaN scale; their bins are
    // filled harmlessly (the cast saturates) and never read.
    let scale = Vec3A::splat(bins as f32) / extent;
    let last_bin = UVec3::splat(bins as u32 - 1);
    let mut bin_bounds = [[Aabb::empty(); MAX_BINS]; 3];
    let mut bin_counts = [[0usize; MAX_BINS]; 3];
    for p in prims {
        let bin = ((p.centroid() - centroids.min) * scale)
            .as_uvec3()
            .min(last_bin);
        for axis in 0..3 {
            let b = bin[axis] as usize;
            bin_bounds[axis][b] = bin_bounds[axis][b].union(&p.bounds);
            bin_counts[axis][b] += 1;
        }
    }
    let mut best: Option<(usize, f32, f32)> = None;
    for axis in (0..3).filter(|&axis| splittable[axis]) {
        let (bin_bounds, bin_counts) = (&bin_bounds[axis], &bin_counts[axis]);
        // Sweep from the right to know each suffix's area and count.
        let mut right_area = [0.0f32; MAX_BINS];
        let mut right_count = [0usize; MAX_BINS];
        let mut acc = Aabb::empty();
        let mut count = 0;
        for i in (1..bins).rev() {
            acc = acc.union(&bin_bounds[i]);
            count += bin_counts[i];
            right_area[i] = acc.half_area();
            right_count[i] = count;
        }
        let mut left = Aabb::empty();
        let mut left_count = 0;
        for i in 1..bins {
            left = left.union(&bin_bounds[i - 1]);
            left_count += bin_counts[i - 1];
            if left_count == 0 || right_count[i] == 0 {
                continue;
            }
            let cost = params.traversal_cost
                + (left.half_area() * left_count as f32 + right_area[i] * right_count[i] as f32)
                    / parent_area;
            if best.is_none_or(|(_, _, c)| cost < c) {
                let position = centroids.min[axis] + i as f32 / scale[axis];
                best = Some((axis, position, cost));
            }
        }
    }
    best
}

/// Reorders `prims` so those satisfying `left` come first; returns how many.
fn partition(prims: &mut [BuildPrim], left: impl Fn(&BuildPrim) -> bool) -> usize {
    let mut split = 0;
    for i in 0..prims.len() {
        if left(&prims[i]) {
            prims.swap(i, split);
            split += 1;
        }
    }
    split
}

/// Writes `node` into `nodes[index]`, its children into two new adjacent
/// slots, recursively.
fn flatten(node: &BuildNode, index: usize, nodes: &mut Vec<Node>) {
    match node {
        BuildNode::Leaf {
            bounds,
            first,
            count,
        } => nodes[index] = Node::new(*bounds, *first, *count),
        BuildNode::Inner { bounds, children } => {
            let first = nodes.len();
            let blank = nodes[index];
            nodes.push(blank);
            nodes.push(blank);
            nodes[index] = Node::new(*bounds, first as u32, 0);
            flatten(&children[0], first, nodes);
            flatten(&children[1], first + 1, nodes);
        }
    }
}

impl Bvh {
    /// The boxes of the nodes at `depth` (the root is 0), with the leaves
    /// above it so the scene stays covered; every leaf for `None`. Read
    /// only, for drawing the structure over the image.
    pub fn boxes(&self, depth: Option<u32>) -> Vec<Aabb> {
        let mut out = Vec::new();
        let mut stack = vec![(0usize, 0u32)];
        while let Some((index, d)) = stack.pop() {
            let Some(node) = self.nodes.get(index) else {
                continue;
            };
            let leaf = node.count() > 0 || self.shapes.is_empty();
            if leaf || depth == Some(d) {
                out.push(node.bounds());
            } else {
                let first = node.first() as usize;
                stack.extend([(first, d + 1), (first + 1, d + 1)]);
            }
        }
        out
    }
}
