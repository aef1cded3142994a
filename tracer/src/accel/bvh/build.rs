//! The binned SAH builder: a binary tree over the primitives' boxes,
//! built top-down with rayon for large subtrees; [`super::node`] turns it
//! into the 8-wide nodes traversal uses.
//!
//! Near the root a node holds most of the primitives, and binning them on
//! one core would leave the other idle: there the boxes and the bins are
//! gathered over chunks in parallel ([`PARALLEL_PASS`]) and merged. Unions
//! and counts do not depend on the order they are taken in, so this gives
//! the same tree as one pass, and the number of threads never changes an
//! image or a statistic.

use std::sync::{Mutex, PoisonError};

use glam::{UVec3, Vec3A};
use rayon::prelude::*;

use crate::geometry::Aabb;

use super::{BvhParams, MAX_DEPTH};
use crate::accel::packed::{LANES, MIN_GROUPED_TRIANGLES};

/// Most SAH bins per axis: the bins live in fixed arrays, one set per
/// rayon task reused from node to node, rather than in a dozen small
/// allocations per node.
const MAX_BINS: usize = 32;

/// Primitives per chunk of a parallel pass: enough work per task to hide
/// rayon's overhead, enough chunks to share among the cores.
const CHUNK: usize = 8192;

/// Nodes with at least this many primitives gather their boxes and bins in
/// parallel chunks; smaller ones are left to the subtree parallelism of
/// `rayon::join`, which keeps the cores busy from a few levels down.
const PARALLEL_PASS: usize = 4 * CHUNK;

/// A primitive during the build: 48 bytes. The centroid is recomputed
/// from the box where needed rather than stored, as the build is bound by
/// the passes over this array, not by arithmetic.
#[derive(Clone, Copy)]
pub(super) struct BuildPrim {
    pub(super) bounds: Aabb,
    pub(super) id: u32,
    /// A triangle: leaves test theirs four at once (see `leaf_cost`).
    pub(super) triangle: bool,
}

impl BuildPrim {
    #[inline]
    fn centroid(&self) -> Vec3A {
        self.bounds.centre()
    }
}

/// A node of the binary tree before flattening: with `count > 0` a leaf
/// of primitives `first..first + count`; with `count == 0` an inner node
/// whose left child follows it in its block and whose right child is node
/// `first` of block `block`.
#[derive(Clone, Copy)]
pub(super) struct BuildNode {
    pub(super) bounds: Aabb,
    pub(super) first: u32,
    pub(super) count: u32,
    block: u32,
    /// How many of its primitives are triangles.
    pub(super) triangles: u32,
}

impl BuildNode {
    pub(super) fn is_leaf(&self) -> bool {
        self.count > 0
    }

    /// The left child of this inner node, found at `at`.
    pub(super) fn left(&self, at: NodeRef) -> NodeRef {
        NodeRef {
            block: at.block,
            index: at.index + 1,
        }
    }

    /// The right child of this inner node.
    pub(super) fn right(&self) -> NodeRef {
        NodeRef {
            block: self.block,
            index: self.first,
        }
    }
}

/// Where a node of a [`BuildTree`] is.
#[derive(Clone, Copy)]
pub(super) struct NodeRef {
    block: u32,
    index: u32,
}

impl NodeRef {
    pub(super) const ROOT: NodeRef = NodeRef { block: 0, index: 0 };
}

/// The binary tree in a few arrays (blocks), one per subtree built on its
/// own rayon task, nodes in depth-first order: no allocation per node, and
/// nothing to free node by node (a large share of a large mesh's build).
/// The root is the first node of block 0; an empty tree has
/// no node.
pub(super) struct BuildTree {
    blocks: Vec<Vec<BuildNode>>,
}

impl BuildTree {
    pub(super) fn is_empty(&self) -> bool {
        self.blocks.iter().all(Vec::is_empty)
    }

    pub(super) fn node(&self, at: NodeRef) -> &BuildNode {
        &self.blocks[at.block as usize][at.index as usize]
    }
}

/// What the SAH needs of a set of primitives: the box around them, the
/// box around their centroids and how many are triangles. Gathered by the
/// partition that makes the set, so a child costs no pass of its own.
#[derive(Clone, Copy)]
struct Extent {
    bounds: Aabb,
    centroids: Aabb,
    triangles: u32,
}

impl Extent {
    const EMPTY: Extent = Extent {
        bounds: Aabb::empty(),
        centroids: Aabb::empty(),
        triangles: 0,
    };

    #[inline]
    fn add(&mut self, p: &BuildPrim) {
        self.bounds = self.bounds.union(&p.bounds);
        self.centroids = self.centroids.grow(p.centroid());
        self.triangles += u32::from(p.triangle);
    }

    fn merge(self, other: Extent) -> Extent {
        Extent {
            bounds: self.bounds.union(&other.bounds),
            centroids: self.centroids.union(&other.centroids),
            triangles: self.triangles + other.triangles,
        }
    }

    /// The extent of `prims`, in parallel chunks when they are many.
    fn of(prims: &[BuildPrim]) -> Extent {
        let serial = |chunk: &[BuildPrim]| {
            chunk.iter().fold(Extent::EMPTY, |mut e, p| {
                e.add(p);
                e
            })
        };
        if prims.len() < PARALLEL_PASS {
            return serial(prims);
        }
        prims
            .par_chunks(CHUNK)
            .map(serial)
            .reduce(|| Extent::EMPTY, Extent::merge)
    }
}

/// Builds the tree over `prims`, reordering them into leaf order.
pub(super) fn build_tree(prims: &mut [BuildPrim], params: &BvhParams) -> BuildTree {
    let builder = Builder {
        params,
        blocks: Mutex::new(Vec::new()),
    };
    if !prims.is_empty() {
        let extent = Extent::of(prims);
        builder.block(prims, extent, 0, 0);
    }
    BuildTree {
        blocks: builder
            .blocks
            .into_inner()
            .unwrap_or_else(PoisonError::into_inner),
    }
}

/// The state shared by a build's tasks.
struct Builder<'a> {
    params: &'a BvhParams,
    /// The blocks finished so far, by number; a block's number is taken
    /// (with an empty block) when its subtree starts.
    blocks: Mutex<Vec<Vec<BuildNode>>>,
}

impl Builder<'_> {
    /// Builds the subtree over `prims` into a block of its own.
    fn block(&self, prims: &mut [BuildPrim], extent: Extent, offset: u32, depth: usize) -> u32 {
        let number = {
            let mut blocks = self.blocks.lock().unwrap_or_else(PoisonError::into_inner);
            blocks.push(Vec::new());
            blocks.len() as u32 - 1
        };
        let mut task = Task {
            // A subtree has at most two nodes per primitive; untouched
            // capacity costs nothing.
            nodes: Vec::with_capacity(2 * prims.len()),
            block: number,
            bins: Box::new(Bins::EMPTY),
        };
        self.subtree(prims, extent, offset, depth, &mut task);
        self.blocks.lock().unwrap_or_else(PoisonError::into_inner)[number as usize] = task.nodes;
        number
    }

    /// Builds the subtree over `prims`, whose extent is `extent` and which
    /// start at `offset` in the final primitive order, at the end of the
    /// task's block.
    fn subtree(
        &self,
        prims: &mut [BuildPrim],
        extent: Extent,
        offset: u32,
        depth: usize,
        task: &mut Task,
    ) {
        let params = self.params;
        let at = task.nodes.len();
        let block = task.block;
        task.nodes.push(BuildNode {
            bounds: extent.bounds,
            first: offset,
            count: prims.len() as u32,
            block,
            triangles: extent.triangles,
        });
        if prims.len() <= 1 || depth >= MAX_DEPTH - 1 {
            return;
        }
        let split = match best_split(prims, extent, params, &mut task.bins) {
            Some((axis, position, cost)) => {
                let leaf_cost = leaf_cost(prims.len() as u32, extent.triangles);
                if cost >= leaf_cost && prims.len() <= params.max_leaf_size {
                    return;
                }
                Some(partition(prims, |p| p.centroid()[axis] < position))
            }
            None if prims.len() <= params.max_leaf_size => return,
            // All centroids coincide: no plane separates them, so halve the list.
            None => None,
        };
        let (split, left_extent, right_extent) = match split {
            Some((split, l, r)) if split != 0 && split != prims.len() => (split, l, r),
            _ => {
                let half = prims.len() / 2;
                (half, Extent::of(&prims[..half]), Extent::of(&prims[half..]))
            }
        };
        let parallel = prims.len() >= params.parallel_threshold;
        let (left, right) = prims.split_at_mut(split);
        let right_offset = offset + split as u32;
        let depth = depth + 1;
        let right_child = if parallel {
            let (_, right_block) = rayon::join(
                || self.subtree(left, left_extent, offset, depth, task),
                || self.block(right, right_extent, right_offset, depth),
            );
            (right_block, 0)
        } else {
            self.subtree(left, left_extent, offset, depth, task);
            let right_index = task.nodes.len() as u32;
            self.subtree(right, right_extent, right_offset, depth, task);
            (block, right_index)
        };
        let node = &mut task.nodes[at];
        (node.block, node.first) = right_child;
        node.count = 0;
    }
}

/// What one rayon task of the build writes to: its block of nodes, and the
/// bins it reuses from node to node (filling 3.4 KB of empty bins for
/// each node showed in a large mesh's build).
struct Task {
    nodes: Vec<BuildNode>,
    block: u32,
    bins: Box<Bins>,
}

/// Each bin's box, primitive count and triangle count on each axis.
#[derive(Clone, Copy)]
struct Bins {
    bounds: [[Aabb; MAX_BINS]; 3],
    counts: [[u32; MAX_BINS]; 3],
    triangles: [[u32; MAX_BINS]; 3],
}

impl Bins {
    const EMPTY: Bins = Bins {
        bounds: [[Aabb::empty(); MAX_BINS]; 3],
        counts: [[0; MAX_BINS]; 3],
        triangles: [[0; MAX_BINS]; 3],
    };

    /// Adds `prims` to the bins of all three axes in one pass: the bin of
    /// a centroid `c` is `(c - origin) * scale`, clamped to `last_bin`.
    /// Triangles are counted apart only when `TRIANGLES` (a node mixing
    /// triangles and other shapes; in the others they are all or none).
    /// In place: a node's bins are 3.8 KB, too much to move by value.
    #[inline]
    fn add<const TRIANGLES: bool>(
        &mut self,
        prims: &[BuildPrim],
        origin: Vec3A,
        scale: Vec3A,
        last_bin: UVec3,
    ) {
        for p in prims {
            let bin = ((p.centroid() - origin) * scale).as_uvec3().min(last_bin);
            for axis in 0..3 {
                let b = bin[axis] as usize;
                self.bounds[axis][b] = self.bounds[axis][b].union(&p.bounds);
                self.counts[axis][b] += 1;
                if TRIANGLES {
                    self.triangles[axis][b] += u32::from(p.triangle);
                }
            }
        }
    }

    /// [`Bins::add`], counting triangles apart when `mixed`.
    #[inline]
    fn add_any(
        &mut self,
        prims: &[BuildPrim],
        origin: Vec3A,
        scale: Vec3A,
        last_bin: UVec3,
        mixed: bool,
    ) {
        if mixed {
            self.add::<true>(prims, origin, scale, last_bin);
        } else {
            self.add::<false>(prims, origin, scale, last_bin);
        }
    }

    /// Empties the first `bins` bins of each axis, the ones in use.
    fn clear(&mut self, bins: usize) {
        for axis in 0..3 {
            self.bounds[axis][..bins].fill(Aabb::empty());
            self.counts[axis][..bins].fill(0);
            self.triangles[axis][..bins].fill(0);
        }
    }

    fn merge(mut self, other: Bins) -> Bins {
        for axis in 0..3 {
            for b in 0..MAX_BINS {
                self.bounds[axis][b] = self.bounds[axis][b].union(&other.bounds[axis][b]);
                self.counts[axis][b] += other.counts[axis][b];
                self.triangles[axis][b] += other.triangles[axis][b];
            }
        }
        self
    }
}

/// What a group of four triangles costs a leaf to test, in single
/// primitive tests: counting each triangle as one test, as for other
/// shapes, made leaves so small that most triangles were tested one by
/// one. Measured on triangle meshes: 1 to 1.5 render equally fast, 0.75
/// slower. Spheres, grouped too, gained nothing from the same treatment,
/// so they count one test each.
const TRIANGLE_GROUP_COST: f32 = 1.25;

/// What testing `count` primitives, `triangles` of them triangles, costs a
/// leaf in primitive tests: a leaf with enough triangles tests them in
/// groups of four (`packed`), each other primitive on its own.
pub(super) fn leaf_cost(count: u32, triangles: u32) -> f32 {
    if (triangles as usize) < MIN_GROUPED_TRIANGLES {
        return count as f32;
    }
    (count - triangles) as f32 + triangles.div_ceil(LANES as u32) as f32 * TRIANGLE_GROUP_COST
}

/// The cheapest binned SAH split: `(axis, plane position, cost)` in units
/// of primitive tests, or `None` when the centroids of `prims` (bounded by
/// `extent.centroids`) do not spread. One pass over the primitives bins all
/// three axes into `binned`, the task's bins, reused.
fn best_split(
    prims: &[BuildPrim],
    extent: Extent,
    params: &BvhParams,
    binned: &mut Bins,
) -> Option<(usize, f32, f32)> {
    let Extent {
        bounds,
        centroids,
        triangles,
    } = extent;
    let mixed = triangles != 0 && triangles as usize != prims.len();
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
    if prims.len() < PARALLEL_PASS {
        binned.clear(bins);
        binned.add_any(prims, centroids.min, scale, last_bin, mixed);
    } else {
        *binned = prims
            .par_chunks(CHUNK)
            .fold(
                || Bins::EMPTY,
                |mut bins, chunk| {
                    bins.add_any(chunk, centroids.min, scale, last_bin, mixed);
                    bins
                },
            )
            .reduce(|| Bins::EMPTY, Bins::merge);
    }
    let mut best: Option<(usize, f32, f32)> = None;
    for axis in (0..3).filter(|&axis| splittable[axis]) {
        let bin_bounds = &binned.bounds[axis];
        let bin_counts = &binned.counts[axis];
        let bin_triangles = match triangles {
            _ if mixed => &binned.triangles[axis],
            0 => &[0; MAX_BINS],
            _ => bin_counts,
        };
        // Sweep from the right to know each suffix's area, count and cost.
        let mut right_area = [0.0f32; MAX_BINS];
        let mut right_count = [0u32; MAX_BINS];
        let mut right_cost = [0.0f32; MAX_BINS];
        let mut acc = Aabb::empty();
        let (mut count, mut triangles) = (0, 0);
        for i in (1..bins).rev() {
            acc = acc.union(&bin_bounds[i]);
            count += bin_counts[i];
            triangles += bin_triangles[i];
            right_area[i] = acc.half_area();
            right_count[i] = count;
            right_cost[i] = leaf_cost(count, triangles);
        }
        let mut left = Aabb::empty();
        let (mut left_count, mut left_triangles) = (0, 0);
        for i in 1..bins {
            left = left.union(&bin_bounds[i - 1]);
            left_count += bin_counts[i - 1];
            left_triangles += bin_triangles[i - 1];
            if left_count == 0 || right_count[i] == 0 {
                continue;
            }
            let left_cost = leaf_cost(left_count, left_triangles);
            let cost = params.traversal_cost
                + (left.half_area() * left_cost + right_area[i] * right_cost[i]) / parent_area;
            if best.is_none_or(|(_, _, c)| cost < c) {
                let position = centroids.min[axis] + i as f32 / scale[axis];
                best = Some((axis, position, cost));
            }
        }
    }
    best
}

/// Reorders `prims` so those satisfying `left` come first, each swapped
/// with the first of those that do not; returns how many, and the extents
/// of both sides. Serial even at the root: one cheap pass, which an exact
/// parallel version made dearer.
fn partition(
    prims: &mut [BuildPrim],
    left: impl Fn(&BuildPrim) -> bool,
) -> (usize, Extent, Extent) {
    let (mut left_extent, mut right_extent) = (Extent::EMPTY, Extent::EMPTY);
    let mut split = 0;
    for i in 0..prims.len() {
        if left(&prims[i]) {
            left_extent.add(&prims[i]);
            prims.swap(i, split);
            split += 1;
        } else {
            right_extent.add(&prims[i]);
        }
    }
    (split, left_extent, right_extent)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    fn prims(xs: &[f32]) -> Vec<BuildPrim> {
        (0u32..)
            .zip(xs)
            .map(|(id, &x)| BuildPrim {
                bounds: Aabb::new(Vec3A::new(x, 0.0, 0.0), Vec3A::new(x + 1.0, 1.0, 1.0)),
                id,
                triangle: false,
            })
            .collect()
    }

    proptest! {
        /// Binning in chunks and merging gives the bins of one pass.
        #[test]
        fn merged_bins_match_one_pass(
            xs in prop::collection::vec(-8.0f32..8.0, 1..300),
            chunk in 1usize..40,
        ) {
            let prims = prims(&xs);
            let (origin, scale, last) = (Vec3A::splat(-8.0), Vec3A::splat(1.0), UVec3::splat(15));
            let mut whole = Bins::EMPTY;
            whole.add::<true>(&prims, origin, scale, last);
            let merged = prims
                .chunks(chunk)
                .map(|c| {
                    let mut bins = Bins::EMPTY;
                    bins.add::<true>(c, origin, scale, last);
                    bins
                })
                .fold(Bins::EMPTY, Bins::merge);
            prop_assert_eq!(whole.counts, merged.counts);
            prop_assert!(whole.bounds == merged.bounds);
            // Bins used before, cleared, bin like new ones.
            let mut reused = merged;
            reused.clear(16);
            reused.add::<true>(&prims, origin, scale, last);
            prop_assert_eq!(whole.counts, reused.counts);
            prop_assert!(whole.bounds == reused.bounds);
        }
    }
}
