//! Refitting: after some shapes changed in place (an object moved, a
//! sphere grew), the tree keeps its topology and its leaves their shapes;
//! the leaves holding a changed shape get their box and packed records
//! again, and their ancestors' boxes grow or shrink with them, bottom-up.
//! A tree whose boxes grew too much is worse to trace than a new one: the
//! refit then gives up ([`MAX_COST_GROWTH`]) and the caller builds anew.

use std::ops::Range;

use crate::geometry::{Aabb, Shape};

use super::node::{NODE_VISIT_COST, Node};
use super::{Bvh, leaf_len, leaf_start, pack_leaf};
use crate::accel::packed::{leaf_grouped, leaf_ids};

/// The most a refit may raise the tree's cost ([`tree_cost`]) over the
/// cost it had when it was built: above it, rays would pay more than a
/// build costs. Measured on balls_high, one sphere moved (see
/// docs/PERFORMANCE.md, "Scene edits").
pub(in crate::accel) const MAX_COST_GROWTH: f64 = 1.1;

/// The SAH cost of a tree in absolute units (not divided by the root's
/// area, so that a box pulled far out counts in full): every child's box's
/// half area times what entering it costs, a node visit for an inner child
/// ([`NODE_VISIT_COST`]), a test per primitive for a leaf. Read from the
/// nodes alone, a pass over them that reads no primitive.
pub(super) fn tree_cost(nodes: &[Node]) -> f64 {
    nodes
        .iter()
        .flat_map(|node| {
            node.used_slots().map(move |slot| {
                let weight = match node.count[slot] {
                    0 => NODE_VISIT_COST,
                    count => count as f32,
                };
                f64::from(node.bounds(slot).half_area() * weight)
            })
        })
        .sum()
}

impl Bvh {
    /// This tree with the shapes `moved` of `shapes` (bounded shapes that
    /// kept their kind and index, as they were when it was built) refitted
    /// around their new place, or `None` when it cannot be: a leaf's
    /// records would change size (a shape changed kind), or the tree's cost
    /// would grow above [`MAX_COST_GROWTH`] times its cost when built.
    pub(in crate::accel) fn refit(&self, shapes: &[Shape], moved: Range<u32>) -> Option<Bvh> {
        let mut bvh = self.clone();
        let nodes = &mut bvh.nodes;
        // Children follow their parents, so one pass in order meets every
        // node's parent slot before the node.
        let mut parent = vec![(0u32, 0u8); nodes.len()];
        let mut dirty = vec![false; nodes.len()];
        let mut ids = Vec::new();
        for n in 0..nodes.len() {
            let used = nodes[n].used_slots().count();
            for slot in 0..used {
                let (first, count) = (nodes[n].first[slot] as usize, nodes[n].count[slot] as usize);
                if count == 0 {
                    parent[first] = (n as u32, slot as u8);
                    continue;
                }
                ids.clear();
                let records = leaf_ids(&bvh.prims, first, count, &mut ids)?;
                if !ids.iter().any(|id| moved.contains(id)) {
                    continue;
                }
                let bounds = ids.iter().try_fold(Aabb::empty(), |b, &id| {
                    Some(b.union(&shapes.get(id as usize)?.bounds()?))
                })?;
                if leaf_len(shapes, &ids) != (records, leaf_grouped(first)) {
                    return None;
                }
                let start = leaf_start(first);
                pack_leaf(shapes, &ids, &mut bvh.prims[start..start + records]);
                nodes[n].set_bounds(slot, &bounds);
                dirty[n] = true;
            }
        }
        for n in (1..nodes.len()).rev() {
            if dirty[n] {
                let bounds = nodes[n].union();
                let (p, slot) = parent[n];
                nodes[p as usize].set_bounds(slot as usize, &bounds);
                dirty[p as usize] = true;
            }
        }
        let cost = tree_cost(nodes);
        (cost <= MAX_COST_GROWTH * self.built_cost).then_some(bvh)
    }
}
