//! What an edit costs, from the scene document to a world and structure
//! ready to render ([`Edit::apply`], [`World::update`], and a new BVH only
//! when the edit moves geometry), against building both from the edited
//! scene. The two are alternated round by round, so a machine that drifts
//! slows both alike; medians are printed.
//!
//! `cargo run --release -p tracer --example edit_cost -- SCENE 'EDIT' [ROUNDS]`

use std::sync::Arc;
use std::time::{Duration, Instant};

use tracer::accel::{AccelKind, SceneIndex};
use tracer::scene::edit::{Edit, Effect};
use tracer::scene::{Limits, parse_scene_file};
use tracer::world::World;

fn median(times: &mut [Duration]) -> f64 {
    times.sort_unstable();
    times[times.len() / 2].as_secs_f64() * 1e3
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [path, text, rest @ ..] = &args[..] else {
        return Err("usage: edit_cost SCENE 'EDIT' [ROUNDS]".into());
    };
    let rounds: usize = rest.first().map_or(Ok(11), |r| r.parse())?;
    let scene = parse_scene_file(path.as_ref(), &Limits::default())?;
    let world = World::build(&scene);
    let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
    let edit = Edit::parse_in(text, &scene)?;
    let (mut updated, mut rebuilt) = (Vec::new(), Vec::new());
    for _ in 0..rounds {
        let mut edited = scene.clone();
        let start = Instant::now();
        edit.apply(&mut edited)?;
        let mut world = world.clone();
        world.update(&edited, &edit);
        let index = match edit.kind() {
            Effect::Geometry => Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0)),
            _ => index.clone(),
        };
        updated.push(start.elapsed());
        std::hint::black_box((world, index));

        let start = Instant::now();
        let world = World::build(&edited);
        let index = SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0);
        rebuilt.push(start.elapsed());
        std::hint::black_box((world, index));
    }
    let (updated, rebuilt) = (median(&mut updated), median(&mut rebuilt));
    println!(
        "{path}: '{text}' ({:?}, {} shapes), {rounds} alternated rounds, medians: \
         edit + update {updated:.3} ms, build world + BVH {rebuilt:.3} ms, ratio {:.3}",
        edit.kind(),
        world.shapes.len(),
        updated / rebuilt
    );
    Ok(())
}
