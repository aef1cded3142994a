//! A Whitted ray tracer: NFF/P3F scenes, Blinn-Phong shading with shadows,
//! reflection and refraction, stochastic sampling, acceleration structures
//! and a progressive renderer. It knows nothing of any user interface:
//! settings go in, images and statistics come out.

pub mod geometry;
pub mod scene;
