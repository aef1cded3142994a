//! The acceleration structure as geometry to draw: BVH boxes at a depth,
//! the grid's box and lattice. Read only; traversal never uses it.

use glam::Vec3A;

use crate::geometry::Aabb;

use super::{SceneIndex, Structure, Visit};

/// What of the structure to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StructureLayer {
    /// The BVH's boxes at this depth of the 8-wide tree (the scene box is
    /// 0), leaves above it too.
    BvhDepth(u32),
    /// Every BVH leaf.
    BvhLeaves,
    /// The grid's box with its cell lattice on the box's faces.
    Grid,
}

impl SceneIndex {
    /// The 3D segments of `layer`, empty when this index is not of that
    /// structure.
    pub fn wireframe(&self, layer: StructureLayer) -> Vec<[Vec3A; 2]> {
        match (&self.structure, layer) {
            (Structure::Bvh(bvh), StructureLayer::BvhDepth(d)) => box_edges(&bvh.boxes(Some(d))),
            (Structure::Bvh(bvh), StructureLayer::BvhLeaves) => box_edges(&bvh.boxes(None)),
            (Structure::Grid(grid), StructureLayer::Grid) => {
                let (bounds, cells) = grid.lattice();
                lattice_edges(&bounds, cells)
            }
            _ => Vec::new(),
        }
    }
}

impl Visit {
    /// The 12 edges of the visited cell's, node's or leaf's box.
    pub fn edges(&self) -> Vec<[Vec3A; 2]> {
        box_edges(&[self.bounds()])
    }
}

/// The 12 edges of each box.
fn box_edges(boxes: &[Aabb]) -> Vec<[Vec3A; 2]> {
    let mut out = Vec::with_capacity(boxes.len() * 12);
    for b in boxes.iter().filter(|b| !b.is_empty()) {
        let corner = |i: usize| {
            Vec3A::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            )
        };
        for i in 0..8 {
            for axis in [1, 2, 4] {
                if i & axis == 0 {
                    out.push([corner(i), corner(i | axis)]);
                }
            }
        }
    }
    out
}

/// The cell boundaries drawn on the six faces of the grid's box: on each
/// face, the lines of both in-face axes at every cell boundary.
fn lattice_edges(bounds: &Aabb, cells: [u32; 3]) -> Vec<[Vec3A; 2]> {
    let mut out = Vec::new();
    if bounds.is_empty() {
        return out;
    }
    let (min, max) = (bounds.min, bounds.max);
    let size = max - min;
    for normal in 0..3 {
        for face in [min[normal], max[normal]] {
            // Lines along axis `along`, placed at boundaries of axis `across`.
            for (along, across) in [
                ((normal + 1) % 3, (normal + 2) % 3),
                ((normal + 2) % 3, (normal + 1) % 3),
            ] {
                let n = cells[across].max(1);
                for i in 0..=n {
                    let mut a = min;
                    a[normal] = face;
                    a[across] = min[across] + size[across] * i as f32 / n as f32;
                    let mut b = a;
                    a[along] = min[along];
                    b[along] = max[along];
                    out.push([a, b]);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::AccelKind;
    use crate::geometry::{Shape, Sphere};

    fn spheres() -> Vec<Shape> {
        (0..8)
            .map(|i| Shape::Sphere(Sphere::new(Vec3A::new(i as f32 * 3.0, 0.0, 0.0), 1.0)))
            .collect()
    }

    #[test]
    fn bvh_depths_cover_the_scene_and_leaves_bound_each_primitive() {
        let index = SceneIndex::build(&spheres(), AccelKind::Bvh, 2.0);
        let root = index.wireframe(StructureLayer::BvhDepth(0));
        assert_eq!(root.len(), 12, "one box");
        let xs: Vec<f32> = root.iter().flat_map(|[a, b]| [a.x, b.x]).collect();
        assert_eq!(xs.iter().copied().fold(f32::INFINITY, f32::min), -1.0);
        assert_eq!(xs.iter().copied().fold(f32::NEG_INFINITY, f32::max), 22.0);
        // The root of the 8-wide tree has two to eight children.
        let children = index.wireframe(StructureLayer::BvhDepth(1)).len() / 12;
        assert!((2..=8).contains(&children), "{children}");
        let leaves = index.wireframe(StructureLayer::BvhLeaves).len() / 12;
        assert!((1..=8).contains(&leaves), "{leaves}");
        assert!(index.wireframe(StructureLayer::Grid).is_empty());
    }

    #[test]
    fn the_grid_lattice_has_a_line_per_cell_boundary_on_each_face() {
        let index = SceneIndex::build(&spheres(), AccelKind::Grid, 2.0);
        let (bounds, cells) = match &index.structure {
            Structure::Grid(g) => g.lattice(),
            _ => unreachable!(),
        };
        let lines = index.wireframe(StructureLayer::Grid);
        let per_pair: u32 = (0..3)
            .map(|n| (cells[(n + 1) % 3] + 1) + (cells[(n + 2) % 3] + 1))
            .sum();
        assert_eq!(lines.len() as u32, 2 * per_pair);
        for [a, b] in &lines {
            for p in [a, b] {
                assert!((p.cmpge(bounds.min - 1e-4) & p.cmple(bounds.max + 1e-4)).all());
            }
        }
        assert!(index.wireframe(StructureLayer::BvhLeaves).is_empty());
    }
}
