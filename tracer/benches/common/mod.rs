//! Scene loading shared by the benchmarks: the project's scenes, parsed and
//! prepared the way `workbench bench` does it.

// Each benchmark is its own crate and uses only part of this module.
#![allow(dead_code)]

use std::path::PathBuf;
use std::sync::Arc;

use tracer::accel::{AccelKind, SceneIndex};
use tracer::render::{RenderPlan, RenderSettings};
use tracer::scene::{Limits, Scene, parse_scene_file};
use tracer::stats::Counters;
use tracer::world::World;

/// A scene file of the project's `scenes/` folder, parsed and prepared.
pub fn load(name: &str) -> (Scene, Arc<World>) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name);
    let scene = parse_scene_file(&path, &Limits::default())
        .unwrap_or_else(|e| panic!("cannot load {}: {e}", path.display()));
    let world = Arc::new(World::build(&scene));
    (scene, world)
}

/// The frame `workbench bench` times: the scene's size and depth, one
/// sample per pixel, hard shadows, with acceleration `accel`.
pub fn bench_frame(scene: &Scene, world: &Arc<World>, accel: AccelKind) -> RenderPlan {
    let settings = RenderSettings {
        antialiasing: false,
        depth_of_field: false,
        soft_shadows: false,
        accel,
        ..RenderSettings::from_scene(scene)
    };
    let index = Arc::new(SceneIndex::build(
        &world.shapes,
        accel,
        settings.grid_multiplier,
    ));
    RenderPlan::new(world.clone(), index, settings).expect("the scene's camera is valid")
}

/// Renders every tile of the first pass on the calling thread: the work of
/// one frame without the thread pool, so instruction counts are stable.
pub fn render_frame(plan: &RenderPlan) -> Counters {
    let mut counters = Counters::default();
    for tile in &plan.tiles {
        std::hint::black_box(plan.render_tile(0, tile, &mut counters));
    }
    counters
}
