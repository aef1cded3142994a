//! Planar polygons, possibly concave, split into triangles by ear clipping.

use glam::Vec3A;

/// Why a polygon cannot be triangulated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PolygonError {
    #[error("a polygon needs at least 3 vertices, found {0}")]
    TooFewVertices(usize),
    #[error("the first three vertices are collinear, so they give no normal")]
    Degenerate,
}

/// Splits a planar polygon into triangles (indices into `vertices`). Works
/// for concave polygons (the SPD gears); the first three vertices form a
/// convex corner that gives the polygon's normal and winding.
pub fn triangulate_polygon(vertices: &[Vec3A]) -> Result<Vec<[u32; 3]>, PolygonError> {
    todo!("{vertices:?}")
}
