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
pub mod render;
pub mod sampling;
pub mod scene;
pub mod skybox;
pub mod stats;
pub mod world;

#[cfg(any(test, feature = "test-util"))]
pub mod scratch;
