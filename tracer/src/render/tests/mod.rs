//! Behaviour of the progressive renderer and of stochastic sampling.

mod aa;
mod adaptive;
mod estimate;
mod lens;
mod shadows;
mod slices;

use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::{Arc, Mutex, mpsc};
use std::time::Duration;

use glam::Vec3A;

use super::driver::Host;
use super::{
    Encoding, Film, JobOptions, JobState, LensOverride, RenderJob, RenderPlan, RenderSettings,
    render,
};
use crate::accel::{AccelKind, SceneIndex};
use crate::scene::{Limits, parse_scene};
use crate::stats::Counters;
use crate::waiting::{PATIENCE, wait_until};
use crate::world::World;

pub(super) fn world(text: &str) -> Arc<World> {
    let scene = parse_scene(text, None, &Limits::default()).expect("test scene parses");
    Arc::new(World::build(&scene))
}

pub(super) fn index(world: &World, kind: AccelKind) -> Arc<SceneIndex> {
    Arc::new(SceneIndex::build(&world.shapes, kind, 2.0))
}

/// Spheres of every material over a floor, two lights: exercises shadows,
/// reflection and refraction.
const SCENE: &str = "\
bclr 0.2 0.3 0.5
v from 0 -5 2 at 0 0 0.5 up 0 0 1 angle 45 hither 0.01 resolution 40 30
l 3 -3 5 1 1 1
l -4 -2 3 0.5 0.5 0.5
f 0.8 0.8 0.8 1 1 1 1 0.2 20 0 1
p 4 -4 -4 0 4 -4 0 4 4 0 -4 4 0
f 0.9 0.2 0.1 0.7 1 1 1 0.3 30 0 1
s -1 0 0.7 0.7
f 1 1 1 0.1 1 1 1 0.1 100 0.9 1.5
s 1 -0.5 0.6 0.6
";

fn settings(width: u32, height: u32) -> RenderSettings {
    RenderSettings {
        width,
        height,
        antialiasing: true,
        samples: 3,
        soft_shadows: true,
        light_size: 0.8,
        depth_of_field: true,
        lens_override: LensOverride {
            aperture: Some(6.0),
            focal: Some(1.2),
        },
        ..RenderSettings::default()
    }
}

/// The plan executed by hand, one tile after another on this thread.
fn sequential(plan: &RenderPlan) -> Film {
    let mut film = Film::new(plan.settings.width, plan.settings.height);
    let mut counters = Counters::default();
    for pass in 0..plan.passes_target() {
        for tile in &plan.tiles {
            film.add_tile(tile, &plan.render_tile(pass, tile, &mut counters));
        }
    }
    film
}

#[test]
fn progressive_passes_equal_a_sequential_render_bit_for_bit() {
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let s = settings(70, 45);
    let plan = RenderPlan::new(w.clone(), idx.clone(), s.clone()).unwrap();
    assert_eq!(plan.passes_target(), 9);
    let expected = sequential(&plan);
    for threads in [1, 2] {
        let (film, stats) = render(w.clone(), idx.clone(), s.clone(), Some(threads)).unwrap();
        assert_eq!(film, expected, "{threads} thread(s)");
        assert_eq!(stats.passes_done, 9);
        assert_eq!(stats.counters.eye_rays, 70 * 45 * 9);
        // 3 x 2 tiles a pass, each counted once, by a thread of the pool.
        assert_eq!(stats.tiles_by_thread.iter().sum::<u64>(), 6 * 9);
        assert!(
            stats.tiles_by_thread.len() <= threads,
            "{threads} thread(s)"
        );
    }
}

#[test]
fn a_job_hosted_on_the_global_pool_renders_the_same_image() {
    let w = world(SCENE);
    // Built by the job on the global pool, as a web page's job is.
    let s = settings(70, 45);
    let frame = RenderPlan::new(w.clone(), index(&w, AccelKind::Bvh), s.clone()).unwrap();
    let job = RenderJob::start(
        w,
        None,
        s,
        JobOptions {
            host: Host::Global,
            ..JobOptions::default()
        },
    )
    .unwrap();
    let (film, stats, state) = job.wait();
    assert_eq!(state, JobState::Done);
    assert_eq!(stats.passes_done, 9);
    assert_eq!(film, sequential(&frame));
}

#[test]
fn every_structure_renders_the_same_image() {
    let w = world(SCENE);
    let s = RenderSettings {
        soft_shadows: false,
        depth_of_field: false,
        ..settings(40, 30)
    };
    let films: Vec<Film> = [AccelKind::None, AccelKind::Grid, AccelKind::Bvh]
        .into_iter()
        .map(|k| {
            render(w.clone(), index(&w, k), s.clone(), Some(2))
                .unwrap()
                .0
        })
        .collect();
    assert_eq!(films[0], films[1]);
    assert_eq!(films[0], films[2]);
}

/// A shadow ray blocked by the shape that blocked the previous one towards
/// the same light costs one test and no traversal; any other ray costs
/// that test on top of a traversal, and after an unblocked ray the next
/// one goes straight to the structure; the answer is always the
/// structure's.
#[test]
fn the_shadow_cache_tests_the_last_occluder_first() {
    let world = world(
        "v from 0 -5 2 at 0 0 0 up 0 0 1 angle 45 hither 0.01 resolution 8 8\n\
         l 0 0 10\n\
         f 1 1 1 1 0 0 0 0 1 0 1\n\
         s 0 0 2 1\n\
         s 9 9 2 1\n",
    );
    let settings = settings(8, 8);
    for kind in [AccelKind::None, AccelKind::Grid, AccelKind::Bvh] {
        let index = index(&world, kind);
        let tracer = super::Tracer::new(&world, &index, &settings);
        let shadow = |x: f32, counters: &mut Counters| {
            let ray = crate::geometry::Ray::new(Vec3A::new(x, 0.0, 0.0), Vec3A::Z);
            let expected = index.any_hit(&world.shapes, &ray, 0.0, 10.0, &mut Counters::default());
            let blocked = tracer.shadowed(0, &ray, 10.0, counters);
            assert_eq!(blocked, expected, "{kind:?} at x = {x}");
            blocked
        };
        let mut first = Counters::default();
        assert!(shadow(0.0, &mut first));
        assert_eq!(first.shadow_cache_hits, 0);
        let mut again = Counters::default();
        assert!(shadow(0.1, &mut again), "{kind:?}");
        assert_eq!(again.shadow_cache_hits, 1);
        assert_eq!((again.intersection_tests, again.nodes_visited), (1, 0));
        let mut lit = Counters::default();
        assert!(!shadow(5.0, &mut lit));
        assert_eq!(lit.shadow_cache_hits, 0);
        let mut lit_again = Counters::default();
        assert!(!shadow(5.0, &mut lit_again));
        assert_eq!(
            lit.intersection_tests,
            lit_again.intersection_tests + 1,
            "{kind:?}: the cached shape is tested once, then forgotten"
        );
    }
}

#[test]
fn seeds_change_the_noise_but_not_the_picture() {
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let a = render(w.clone(), idx.clone(), settings(40, 30), None)
        .unwrap()
        .0;
    let b = render(
        w.clone(),
        idx,
        RenderSettings {
            seed: 99,
            ..settings(40, 30)
        },
        None,
    )
    .unwrap()
    .0;
    assert_ne!(a, b);
    let mean = |f: &Film| {
        let mut sum = Vec3A::ZERO;
        for y in 0..f.height() {
            for x in 0..f.width() {
                sum += f.pixel(x, y).unwrap();
            }
        }
        sum / (f.width() * f.height()) as f32
    };
    assert!((mean(&a) - mean(&b)).abs().max_element() < 0.02);
}

/// A white square filling the left part of a one-pixel image, lit only by
/// ambient light: the pixel's value is the covered fraction.
fn edge_scene(edge: f32) -> String {
    // The camera looks down -z from z = 1 at the origin with a 90 degree
    // field: with one pixel row the view plane is 2 units high, so the
    // pixel spans x in [-1, 1].
    format!(
        "bclr 0 0 0\n\
         v from 0 0 1 at 0 0 0 up 0 1 0 angle 90 hither 0 resolution 1 1\n\
         f 1 1 1 1 0 0 0 0 1 0 1\n\
         p 4 -5 -5 0 {edge} -5 0 {edge} 5 0 -5 5 0\n"
    )
}

#[test]
fn jittered_samples_converge_to_the_covered_fraction() {
    for (edge, fraction) in [(0.0f32, 0.5f32), (-0.5, 0.25), (0.8, 0.9)] {
        let w = world(&edge_scene(edge));
        let mut errors = Vec::new();
        for n in [2, 4, 8, 16] {
            let s = RenderSettings {
                width: 1,
                height: 1,
                ambient: 1.0,
                antialiasing: true,
                samples: n,
                ..RenderSettings::default()
            };
            let (film, _) = render(w.clone(), index(&w, AccelKind::Bvh), s, Some(1)).unwrap();
            errors.push((film.pixel(0, 0).unwrap().x - fraction).abs());
        }
        // A straight edge crosses one column of the N x N strata, and each
        // of its N cells is off by at most one sample's 1 / N^2.
        for (n, error) in [2, 4, 8, 16].into_iter().zip(&errors) {
            assert!(*error <= 1.0 / n as f32, "edge {edge}, N = {n}: {errors:?}");
        }
        assert!(errors[3] < 0.01, "edge {edge}: {errors:?}");
        assert!(errors[3] <= errors[0] + 1e-6, "edge {edge}: {errors:?}");
    }
}

/// A floor with a sphere over it, lit from above: the number of pixels on
/// the middle row that are neither fully lit nor fully in shadow, compared
/// with the same floor without the sphere.
fn penumbra_width(light_size: f32, soft: bool) -> usize {
    let floor = "bclr 0 0 0\n\
         v from 0 0 10 at 0 0 0 up 0 1 0 angle 20 hither 0 resolution 81 81\n\
         l 0 0 6 1 1 1\n\
         f 1 1 1 1 0 0 0 0 1 0 1\n\
         p 4 -9 -9 0 9 -9 0 9 9 0 -9 9 0\n";
    let sphere = "f 0 0 0 0 0 0 0 0 1 0 1\ns 0 0 3 0.4\n";
    let s = RenderSettings {
        width: 81,
        height: 81,
        ambient: 0.0,
        soft_shadows: soft,
        light_size,
        samples: 8,
        ..RenderSettings::default()
    };
    let row = |text: &str| {
        let w = world(text);
        let (film, _) = render(w.clone(), index(&w, AccelKind::Bvh), s.clone(), Some(2)).unwrap();
        (0..81)
            .map(|x| film.pixel(x, 40).unwrap().x)
            .collect::<Vec<f32>>()
    };
    let unshadowed = row(floor);
    let shadowed = row(&format!("{floor}{sphere}"));
    shadowed
        .iter()
        .zip(&unshadowed)
        .filter(|(v, full)| **v > 0.02 * **full && **v < 0.98 * **full)
        .count()
}

#[test]
fn soft_shadow_penumbra_widens_with_the_light_size() {
    let hard = penumbra_width(1.0, false);
    let small = penumbra_width(0.3, true);
    let large = penumbra_width(1.5, true);
    assert!(hard <= 2, "hard shadows have no penumbra: {hard}");
    assert!(small > hard, "{small} vs {hard}");
    assert!(large > small, "{large} vs {small}");
}

#[test]
fn cancellation_stops_a_long_render() {
    let w = world(SCENE);
    let s = RenderSettings {
        samples: 16,
        ..settings(1024, 1024)
    };
    let tiles_done = Arc::new(AtomicU32::new(0));
    let counter = tiles_done.clone();
    let job = RenderJob::start(
        w,
        Some(index(&world(SCENE), AccelKind::Bvh)),
        s,
        JobOptions {
            threads: Some(2),
            on_progress: Some(Box::new(move || {
                counter.fetch_add(1, Ordering::Relaxed);
            })),
            ..JobOptions::default()
        },
    )
    .unwrap();
    wait_until("the first tile", || tiles_done.load(Ordering::Relaxed) > 0);
    job.cancel();
    let at_cancel = job.stats().counters.eye_rays;
    let (_, stats, state) = job.wait();
    assert_eq!(state, JobState::Cancelled);
    assert_eq!(stats.passes_done, 0);
    // After cancel() returns, only the tiles already in flight (one per
    // thread) may finish: none of the remaining thousands of tiles.
    let pixels_per_tile = 32 * 32;
    let after = stats.counters.eye_rays - at_cancel;
    assert!(
        after <= 2 * pixels_per_tile,
        "{after} eye rays after cancel"
    );
}

#[test]
fn pause_holds_the_render_until_resumed() {
    // One render thread, held inside its first progress callback (after
    // its first tile) while the test pauses the job: no sleep decides
    // when the pause lands.
    let (tile_done, tiles) = mpsc::channel();
    let (open_gate, gate) = mpsc::channel::<()>();
    let gate = Mutex::new(gate);
    let w = world(SCENE);
    let job = RenderJob::start(
        w.clone(),
        Some(index(&w, AccelKind::Bvh)),
        settings(64, 64),
        JobOptions {
            threads: Some(1),
            on_progress: Some(Box::new(move || {
                let _ = tile_done.send(());
                // Returns at once when the gate is opened or dropped.
                let _ = gate.lock().unwrap().recv();
            })),
            ..JobOptions::default()
        },
    )
    .unwrap();
    tiles.recv_timeout(PATIENCE).expect("the first tile");
    job.set_paused(true);
    open_gate.send(()).unwrap();
    // Paused between tiles: no further tile may finish. A broken pause
    // fails at once; only a working one waits out the window.
    let next = tiles.recv_timeout(Duration::from_millis(300));
    assert_eq!(
        next,
        Err(mpsc::RecvTimeoutError::Timeout),
        "a tile finished while paused"
    );
    assert!(!job.is_finished());
    assert_eq!(job.stats().counters.eye_rays, 32 * 32);
    job.set_paused(false);
    drop(open_gate);
    tiles.recv_timeout(PATIENCE).expect("a tile after resuming");
    let (_, stats, state) = job.wait();
    assert_eq!(state, JobState::Done);
    assert_eq!(stats.passes_done, 9);
}

#[test]
fn invalid_settings_are_refused_before_rendering() {
    let w = world(SCENE);
    let s = RenderSettings {
        width: 0,
        ..RenderSettings::default()
    };
    assert!(
        RenderJob::start(
            w.clone(),
            Some(index(&w, AccelKind::Bvh)),
            s,
            JobOptions::default()
        )
        .is_err()
    );
}

#[test]
fn a_panic_inside_a_job_is_reported_and_what_was_rendered_stays() {
    let w = world(SCENE);
    let tiles = Arc::new(AtomicU32::new(0));
    let counter = tiles.clone();
    let job = RenderJob::start(
        w.clone(),
        Some(index(&w, AccelKind::Bvh)),
        settings(64, 64),
        JobOptions {
            threads: Some(2),
            // Progress callbacks run on the render threads: a panic there
            // stands for any bug in the tracer.
            on_progress: Some(Box::new(move || {
                if counter.fetch_add(1, Ordering::Relaxed) == 3 {
                    panic!("a bug in the tracer");
                }
            })),
            ..JobOptions::default()
        },
    )
    .unwrap();
    wait_until("the job to stop", || job.is_finished());
    let snapshot = job.snapshot(super::Encoding::Linear);
    assert_eq!(snapshot.rgba.len(), 64 * 64 * 4);
    let (_, stats, state) = job.wait();
    assert_eq!(
        state,
        JobState::Failed("render thread panicked: a bug in the tracer".into())
    );
    assert!(stats.counters.eye_rays > 0);
}

/// Renders `text` the way the `parse_render` fuzz target does (at most
/// 8 x 8, 2 x 2 samples, depth 3, soft shadows forced on, one thread) and
/// returns every film value that is not a finite number.
fn non_finite_pixels(text: &str) -> Vec<(u32, u32, Vec3A)> {
    let scene = parse_scene(text, None, &Limits::default()).expect("test scene parses");
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
    let (film, _) = render(world, index, settings, Some(1)).expect("the scene renders");
    let mut bad = Vec::new();
    for y in 0..film.height() {
        for x in 0..film.width() {
            let value = film.pixel(x, y).unwrap_or_default();
            if !value.is_finite() {
                bad.push((x, y, value));
            }
        }
    }
    bad
}

/// Found by the `parse_render` fuzz target (minimised): a blue of 3e38 in
/// a material is a finite number the parser accepts, but diffuse times the
/// light from two lights overflowed to infinity in the shading, and the
/// film then held `inf` (an EXR would too; a PNG shows it as white).
#[test]
fn huge_but_finite_colours_give_a_finite_film() {
    let fuzzed = "\
#e1
l 1 -4 4 1 1 1
l -3 1 5 1 1 1
f 1 0.75 3e38 0.8 1 1 1 1
p 3
3 3 -0.5
-3 3 -0.5
-3 -3 -0.57
s 0.055556
 0.4203137 0.51 55556
";
    // The same overflow, each factor at most f32::MAX: a colour times Kd
    // (inf when the world is built), a light colour times a diffuse colour
    // (with a zero channel: inf * 0 is NaN), two lights adding up, a huge
    // and a negative highlight exponent, reflections multiplying the
    // radiance at every bounce, and a huge background in a huge mirror.
    let scenes = [
        fuzzed,
        "f 1e30 1e30 1e30 3e38 3e38 3e38 3e38 3e38 3e38 1 3e38\ns 0 0 0 1\n",
        "l 0 0 5 3e38 3e38 0\nf 3e38 3e38 3e38 1 0 0 0 0 1 0 1\ns 0 0 0 1\n",
        "l 0 0 5\nl 0 0 5\nf 1 1 3e38 1 0 1 0 1\ns 0 0 0 1\n",
        "l 0 0 5\nf 1 1 1 1 1 1 1 1 3e38 0 1\ns 0 0 0 1\n",
        "l 0 0 5\nf 1 1 1 1 1 1 1 1 -3e38 0 1\ns 0 0 0 1\n",
        "l 0 0 5 3e38 3e38 3e38\nf 1 1 1 1 3e38 3e38 3e38 1 1 0 1\n\
         s 0 0 0 1\ns 0 0 10 3\n",
        "b 3e38 3e38 3e38\nf 1 1 1 0 1 1 1 3e38 1 0 1\ns 0 0 0 1\n",
    ];
    let failures: Vec<(&str, usize)> = scenes
        .into_iter()
        .map(|scene| (scene, non_finite_pixels(scene).len()))
        .filter(|&(_, bad)| bad > 0)
        .collect();
    assert!(
        failures.is_empty(),
        "scenes with non-finite pixels (how many of 64): {failures:#?}"
    );
}

/// The finished image the render threads make tile by tile is the film
/// resolved at the end, byte for byte, in either encoding and over
/// several passes; a job stopped early leaves none.
#[test]
fn the_finished_image_is_the_resolved_film() {
    let world = world(SCENE);
    for (samples, encoding) in [(1, Encoding::Linear), (3, Encoding::Srgb)] {
        let settings = RenderSettings {
            antialiasing: samples > 1,
            samples,
            ..settings(40, 30)
        };
        let options = JobOptions {
            threads: Some(2),
            finished_image: Some(encoding),
            ..JobOptions::default()
        };
        let done = RenderJob::start(world.clone(), None, settings, options)
            .unwrap()
            .wait_with_image();
        assert_eq!(done.state, JobState::Done);
        let image = done.image.expect("a finished image");
        assert_eq!(image, done.film.to_image(encoding), "{samples} x {samples}");
    }
    // Left out of the film, one pass gives the same bytes; the film stays
    // without a sample. Over several passes the film is kept.
    for (samples, encoding) in [(1, Encoding::Srgb), (2, Encoding::Linear)] {
        let settings = RenderSettings {
            antialiasing: samples > 1,
            samples,
            ..settings(40, 30)
        };
        let finished = |image_only| {
            let options = JobOptions {
                threads: Some(2),
                finished_image: Some(encoding),
                image_only,
                ..JobOptions::default()
            };
            RenderJob::start(world.clone(), None, settings.clone(), options)
                .unwrap()
                .wait_with_image()
        };
        let (with_film, image_only) = (finished(false), finished(true));
        assert_eq!(image_only.state, JobState::Done);
        assert_eq!(image_only.image, with_film.image, "{samples} x {samples}");
        assert_eq!(image_only.stats.counters, with_film.stats.counters);
        assert_eq!(
            image_only.film.pixel(20, 15).is_none(),
            samples == 1,
            "{samples} x {samples}"
        );
    }
    let stopped = RenderJob::start(
        world.clone(),
        None,
        settings(40, 30),
        JobOptions {
            paused: true,
            finished_image: Some(Encoding::Linear),
            ..JobOptions::default()
        },
    )
    .unwrap();
    stopped.cancel();
    assert!(stopped.wait_with_image().image.is_none());
}
