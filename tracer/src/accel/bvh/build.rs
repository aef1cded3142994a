//! The binned SAH builder: a binary tree over the primitives' boxes,
//! built top-down with rayon for large subtrees; [`super::node`] turns it
//! into the 4-wide nodes traversal uses.

use glam::{UVec3, Vec3A};

use crate::geometry::Aabb;

use super::{BvhParams, MAX_DEPTH};

/// Most SAH bins per axis: the bins live in fixed arrays on the stack
/// rather than in a dozen small allocations per node.
const MAX_BINS: usize = 32;

/// A primitive during the build: 48 bytes. The centroid is recomputed
/// from the box where needed rather than stored, as the build is bound by
/// the passes over this array, not by arithmetic.
#[derive(Clone, Copy)]
pub(super) struct BuildPrim {
    pub(super) bounds: Aabb,
    pub(super) id: u32,
}

impl BuildPrim {
    #[inline]
    fn centroid(&self) -> Vec3A {
        self.bounds.centre()
    }
}

/// The tree before flattening.
pub(super) enum BuildNode {
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

/// Builds the subtree over `prims`, which start at `offset` in the final
/// primitive order.
pub(super) fn build_node(
    prims: &mut [BuildPrim],
    offset: u32,
    depth: usize,
    params: &BvhParams,
) -> BuildNode {
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
