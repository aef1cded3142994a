//! A Whitted ray tracer: NFF/P3F scenes, Blinn-Phong shading with shadows,
//! reflection and refraction, stochastic sampling, acceleration structures
//! and a progressive renderer. It knows nothing of any user interface:
//! settings go in, images and statistics come out.

pub mod accel;
pub mod camera;
pub mod generate;
pub mod geometry;
pub mod mesh_io;
pub mod metrics;
pub mod optics;
pub mod ray_set;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod skybox;
pub mod stats;
pub mod world;

/// Scratch folders for unit tests, shared with `tests/` (one file).
#[cfg(test)]
#[path = "../../tests/common/scratch.rs"]
mod scratch;
