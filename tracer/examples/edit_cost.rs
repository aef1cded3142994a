//! What an edit costs, from the scene document to a world and structure
//! ready to render ([`Edit::apply`], [`World::update_shapes`], and for an
//! edit that moves geometry either a new BVH or the old one refitted
//! around the moved shapes, [`SceneIndex::refit`]), against building both
//! from the edited scene. The three are alternated round by round, so a
//! machine that drifts slows them alike; medians are printed.
//!
//! With `--frames N`, the tree's quality after a refit: N alternated
//! renders of one frame (the frame `workbench bench` times: one sample per
//! pixel, hard shadows, on the calling thread) over the refitted tree and
//! over the rebuilt one, medians and the work per frame.
//!
//! `cargo run --release -p tracer --example edit_cost -- SCENE 'EDIT' [ROUNDS] [--frames N]`

use std::sync::Arc;
use std::time::{Duration, Instant};

use tracer::accel::{AccelKind, SceneIndex};
use tracer::render::{RenderPlan, RenderSettings};
use tracer::scene::edit::{Edit, Effect};
use tracer::scene::{Limits, parse_scene_file};
use tracer::stats::Counters;
use tracer::world::{ShapeChange, World};

fn median(times: &mut [Duration]) -> f64 {
    times.sort_unstable();
    times[times.len() / 2].as_secs_f64() * 1e3
}

/// The structure over `world` after the edit: `index` refitted when the
/// change allows it and the refit is not refused, else a new one; and
/// whether it was refitted.
fn follow(index: &Arc<SceneIndex>, world: &World, change: &ShapeChange) -> (Arc<SceneIndex>, bool) {
    match change {
        ShapeChange::None => (index.clone(), false),
        ShapeChange::InPlace(moved) => match index.refit(&world.shapes, moved.clone()) {
            Some(refit) => (Arc::new(refit), true),
            None => (
                Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0)),
                false,
            ),
        },
        ShapeChange::Renumbered => (
            Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0)),
            false,
        ),
    }
}

/// One frame over `index`: its time and work.
fn frame_time(plan: &RenderPlan) -> (Duration, Counters) {
    let mut counters = Counters::default();
    let start = Instant::now();
    for tile in &plan.tiles {
        std::hint::black_box(plan.render_tile(0, tile, &mut counters));
    }
    (start.elapsed(), counters)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let frames = match args.iter().position(|a| a == "--frames") {
        Some(at) => {
            let n = args.get(at + 1).ok_or("--frames N")?.parse()?;
            args.drain(at..at + 2);
            n
        }
        None => 0usize,
    };
    let [path, text, rest @ ..] = &args[..] else {
        return Err("usage: edit_cost SCENE 'EDIT' [ROUNDS] [--frames N]".into());
    };
    let rounds: usize = rest.first().map_or(Ok(11), |r| r.parse())?;
    let scene = parse_scene_file(path.as_ref(), &Limits::default())?;
    let world = World::build(&scene);
    let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
    let edit = Edit::parse_in(text, &scene)?;
    let mut edited = scene.clone();
    edit.apply(&mut edited)?;
    let (mut rebuilt, mut refitted, mut fresh) = (Vec::new(), Vec::new(), Vec::new());
    let mut structure = Vec::new();
    let mut refits = 0;
    let mut last = None;
    for _ in 0..rounds {
        let start = Instant::now();
        let mut rebuilt_scene = scene.clone();
        edit.apply(&mut rebuilt_scene)?;
        let mut rebuilt_world = world.clone();
        rebuilt_world.update_shapes(&rebuilt_scene, &edit);
        let rebuilt_index = match edit.kind() {
            Effect::Geometry => Arc::new(SceneIndex::build(
                &rebuilt_world.shapes,
                AccelKind::Bvh,
                2.0,
            )),
            _ => index.clone(),
        };
        rebuilt.push(start.elapsed());

        let start = Instant::now();
        let mut refit_scene = scene.clone();
        edit.apply(&mut refit_scene)?;
        let mut refit_world = world.clone();
        let change = refit_world.update_shapes(&refit_scene, &edit);
        let follow_start = Instant::now();
        let (refit_index, refit) = follow(&index, &refit_world, &change);
        structure.push(follow_start.elapsed());
        refitted.push(start.elapsed());
        refits += usize::from(refit);

        let start = Instant::now();
        let built_world = World::build(&edited);
        let built = SceneIndex::build(&built_world.shapes, AccelKind::Bvh, 2.0);
        fresh.push(start.elapsed());
        std::hint::black_box((built_world, built, rebuilt_scene, refit_scene));
        last = Some([(rebuilt_world, rebuilt_index), (refit_world, refit_index)]);
    }
    let (rebuilt, refitted, fresh) = (
        median(&mut rebuilt),
        median(&mut refitted),
        median(&mut fresh),
    );
    println!(
        "{path}: '{text}' ({:?}, {} shapes), {rounds} alternated rounds, medians: \
         edit + update + new BVH {rebuilt:.3} ms, edit + update + refit {refitted:.3} ms \
         (the refit {:.3} ms; refitted {refits} of {rounds}), build world + BVH {fresh:.3} ms; \
         refit / new BVH {:.3}, refit / build {:.3}",
        edit.kind(),
        world.shapes.len(),
        median(&mut structure),
        refitted / rebuilt,
        refitted / fresh,
    );
    let Some(last) = last.filter(|_| frames > 0) else {
        return Ok(());
    };
    let settings = RenderSettings {
        antialiasing: false,
        depth_of_field: false,
        soft_shadows: false,
        accel: AccelKind::Bvh,
        ..RenderSettings::from_scene(&edited)
    };
    let [rebuilt, refitted] = last.map(|(world, index)| {
        RenderPlan::new(Arc::new(world), index, settings.clone()).expect("the scene's camera")
    });
    let (mut rebuilt_times, mut refit_times) = (Vec::new(), Vec::new());
    let mut work = [Counters::default(), Counters::default()];
    for _ in 0..frames {
        let (time, counters) = frame_time(&rebuilt);
        rebuilt_times.push(time);
        work[0] = counters;
        let (time, counters) = frame_time(&refitted);
        refit_times.push(time);
        work[1] = counters;
    }
    let (rebuilt_time, refit_time) = (median(&mut rebuilt_times), median(&mut refit_times));
    let per_ray = |c: &Counters| {
        let rays = c.total_rays().max(1) as f64;
        (
            c.nodes_visited as f64 / rays,
            c.intersection_tests as f64 / rays,
        )
    };
    let [(rebuilt_nodes, rebuilt_tests), (refit_nodes, refit_tests)] = work.each_ref().map(per_ray);
    println!(
        "one frame, {frames} alternated renders, medians: over the new BVH {rebuilt_time:.1} ms \
         ({rebuilt_nodes:.2} nodes, {rebuilt_tests:.2} tests a ray), over the refitted one \
         {refit_time:.1} ms ({refit_nodes:.2} nodes, {refit_tests:.2} tests a ray); \
         refitted / new {:.3}",
        refit_time / rebuilt_time
    );
    Ok(())
}
