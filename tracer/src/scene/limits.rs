//! Bounds that protect the parser (and the renderer after it) against
//! hostile or mistaken input: no count read from a file is trusted before it
//! has been checked against these.

use super::rules::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES};

/// Bounds that protect against hostile or mistaken input. The defaults are
/// far above any real scene (the largest SPD scenes have a few hundred
/// thousand objects) yet keep memory use bounded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Largest scene file or text in bytes: 512 MiB.
    pub max_file_bytes: u64,
    /// Largest width or height accepted by `resolution`: 16384.
    pub max_resolution: u32,
    /// Largest width x height: 64 Mi pixels (8192 x 8192, or 16384 x 4096).
    pub max_pixels: u64,
    /// Largest `spp n` (n x n samples per pixel): 64, i.e. 4096 samples.
    pub max_spp: u32,
    /// Most vertices in one `p` polygon or `pp` patch: 1 Mi.
    pub max_polygon_vertices: usize,
    /// Most vertices in one `mesh`: 10 million.
    pub max_mesh_vertices: usize,
    /// Most triangles in one `mesh`: 10 million.
    pub max_mesh_triangles: usize,
    /// Most objects in a scene: 10 million.
    pub max_objects: usize,
    /// Most primitives in a scene once polygons and meshes count as their
    /// triangles: 20 million. Each costs about 300 bytes at peak while the
    /// world and its BVH are built, so this bounds that to about 6 GiB; the
    /// per-mesh and per-object limits alone would not (a 512 MiB file can
    /// hold 90 million `1 2 3` triangles).
    pub max_primitives: usize,
    /// Most `f` materials in a scene: 10 million.
    pub max_materials: usize,
    /// Most lights (`l` and `al`) in a scene: 65536; every light costs a
    /// shadow ray per shading point, so more is never sensible.
    pub max_lights: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_file_bytes: 512 << 20,
            max_resolution: MAX_IMAGE_SIDE,
            max_pixels: MAX_IMAGE_PIXELS,
            max_spp: MAX_SAMPLES,
            max_polygon_vertices: 1 << 20,
            max_mesh_vertices: 10_000_000,
            max_mesh_triangles: 10_000_000,
            max_objects: 10_000_000,
            max_primitives: 20_000_000,
            max_materials: 10_000_000,
            max_lights: 1 << 16,
        }
    }
}
