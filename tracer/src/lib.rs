//! A Whitted ray tracer: NFF/P3F scenes, Blinn-Phong shading with shadows,
//! reflection and refraction, stochastic sampling, acceleration structures
//! and a progressive renderer. It knows nothing of any user interface:
//! settings go in, images and statistics come out.
//!
//! A scene is parsed ([`scene`]), prepared for rendering ([`world`]),
//! indexed by an acceleration structure ([`accel`]) and rendered
//! ([`render`]):
//!
//! ```
//! use std::sync::Arc;
//! use tracer::accel::SceneIndex;
//! use tracer::render::{Encoding, RenderSettings, render};
//! use tracer::scene::{Limits, parse_scene};
//! use tracer::world::World;
//!
//! // A red sphere under one light, seen from 5 units away, 32 x 24 pixels.
//! let text = "v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 resolution 32 24\n\
//!             l 2 4 6\n\
//!             f 1 0 0 1 0 0 0 0\n\
//!             s 0 0 0 1\n";
//! let scene = parse_scene(text, None, &Limits::default())?;
//! let settings = RenderSettings::from_scene(&scene);
//! let world = Arc::new(World::build(&scene));
//! let index = Arc::new(SceneIndex::build(&world.shapes, settings.accel, settings.grid_multiplier));
//! let (film, stats) = render(world, index, settings, None)?;
//!
//! let image = film.to_image(Encoding::Srgb);
//! assert_eq!(image.dimensions(), (32, 24));
//! // The centre sees the sphere: red, no green.
//! let centre = image.get_pixel(16, 12).0;
//! assert!(centre[0] > 100 && centre[1] == 0, "{centre:?}");
//! assert_eq!(stats.counters.eye_rays, 32 * 24);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

#![deny(missing_docs)]

pub mod accel;
pub mod camera;
pub mod generate;
pub mod geometry;
pub mod metrics;
pub mod optics;
pub mod ray_set;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod skybox;
pub mod stats;
pub mod world;

#[cfg(any(test, feature = "test-util"))]
pub mod optional_input;
#[cfg(any(test, feature = "test-util"))]
pub mod scratch;
#[cfg(any(test, feature = "test-util"))]
pub mod waiting;
