//! Whatever the parser accepts must render: a tiny image, few samples and
//! bounces, one thread, so each input takes milliseconds. The scene's own
//! features (soft shadows come from `al` lights, DOF from `aperture`, the
//! structure from `accel`) are kept, with soft shadows forced on too.
//! Every value of the film must be finite.
#![no_main]

use std::sync::Arc;

use libfuzzer_sys::fuzz_target;
use tracer::accel::SceneIndex;
use tracer::render::{RenderSettings, render};
use tracer::scene::{Limits, parse_scene};
use tracer::world::World;

/// Small enough that the fuzzer spends its time on variety, not pixels.
fn limits() -> Limits {
    Limits {
        max_objects: 2_000,
        max_primitives: 20_000,
        max_mesh_triangles: 20_000,
        max_mesh_vertices: 20_000,
        max_polygon_vertices: 2_000,
        max_lights: 16,
        ..Limits::default()
    }
}

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let Ok(mut scene) = parse_scene(&text, None, &limits()) else {
        return;
    };
    // No file system access from the fuzzer: `env` would load real folders.
    scene.env = None;
    let world = Arc::new(World::build(&scene));
    let mut settings = RenderSettings::from_scene(&scene);
    settings.width = settings.width.min(8);
    settings.height = settings.height.min(8);
    settings.samples = settings.samples.min(2);
    settings.max_depth = settings.max_depth.min(3);
    settings.soft_shadows = true;
    let index = Arc::new(SceneIndex::build(
        &world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    // A refused camera or setting is an error value, which is fine; a panic
    // inside the render threads is reported as `RenderError::Panicked`.
    let film = match render(world, index, settings, Some(1)) {
        Ok((film, _)) => film,
        Err(tracer::render::RenderError::Panicked(message)) => {
            panic!("render panicked: {message}")
        }
        Err(_) => return,
    };
    // A NaN or infinite value would be encoded as black or white and pass
    // unseen: every film value must be a number.
    for y in 0..film.height() {
        for x in 0..film.width() {
            let value = film.pixel(x, y).unwrap_or_default();
            assert!(value.is_finite(), "pixel ({x}, {y}) is {value}");
        }
    }
});
