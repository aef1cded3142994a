//! A BVH traversal's steps (node indices) turned into boxes and depths, for
//! drawing the descent of one ray.

use std::collections::HashMap;

use crate::geometry::Aabb;

use super::super::visits::{TraversalStep, Visit};
use super::Bvh;

impl Bvh {
    /// The visits of `steps` told by one traversal of this tree. A node is
    /// only reached through a parent visited before it, which gives its box
    /// and depth: only the visited nodes are read.
    pub(in crate::accel) fn visits(
        &self,
        steps: impl ExactSizeIterator<Item = TraversalStep>,
    ) -> Vec<Visit> {
        // (first, count) of a slot -> its box and depth; the root is (0, 0).
        let mut known: HashMap<(u32, u32), (Aabb, u32)> = HashMap::new();
        if let Some(scene) = self.scene_box() {
            known.insert((0, 0), (scene, 0));
        }
        let mut out = Vec::with_capacity(steps.len());
        for step in steps {
            let (key, leaf) = match step {
                TraversalStep::Node(index) => ((index, 0), false),
                TraversalStep::Leaf(first, count) => ((first, count), true),
                TraversalStep::Cell(_) => continue,
            };
            let Some(&(bounds, depth)) = known.get(&key) else {
                continue;
            };
            if leaf {
                out.push(Visit::Leaf {
                    bounds,
                    depth,
                    primitives: key.1,
                });
                continue;
            }
            let node = &self.nodes[key.0 as usize];
            out.push(Visit::Node {
                bounds,
                depth,
                boxes: node.used_slots().count() as u32,
            });
            for slot in node.used_slots() {
                known.insert(
                    (node.first[slot], node.count[slot]),
                    (node.bounds(slot), depth + 1),
                );
            }
        }
        out
    }
}
