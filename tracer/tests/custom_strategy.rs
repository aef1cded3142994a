//! A sampling strategy defined outside the renderer renders through its
//! unchanged loop: the loop asks the strategy, never the settings, which
//! samples a pass takes and when the render ends.

use std::ops::Range;
use std::sync::Arc;
use std::time::{Duration, Instant};

use tracer::accel::{AccelKind, SceneIndex};
use tracer::render::strategy::{PassEnd, SamplingStrategy, TileSamples};
use tracer::render::{Film, JobOptions, JobState, RenderJob, RenderSettings, Tile, render};
use tracer::scene::{Limits, parse_scene};
use tracer::stats::RenderStats;
use tracer::world::World;

const SCENE: &str = "\
bclr 0.2 0.3 0.5
v from 0 -5 2 at 0 0 0.5 up 0 0 1 angle 45 hither 0.01 resolution 40 30
l 3 -3 5 1 1 1
f 0.8 0.8 0.8 1 1 1 1 0.2 20 0 1
p 4 -4 -4 0 4 -4 0 4 4 0 -4 4 0
f 1 1 1 0.1 1 1 1 0.1 100 0.9 1.5
s 0 0 0.7 0.7
";

/// Samples the left half of the image only, one sample a pass in uniform
/// sampling's order, for `passes` passes; past them, when `stalls`, it
/// samples nothing and asks for more passes for ever.
struct LeftHalf {
    width: u32,
    passes: u32,
    stalls: bool,
}

impl SamplingStrategy for LeftHalf {
    fn film(&self, width: u32, height: u32) -> Film {
        Film::new(width, height)
    }

    fn passes_target(&self) -> u32 {
        self.passes
    }

    fn tile_samples(&self, pass: u32, tile: &Tile, _: &Film) -> Option<TileSamples> {
        let left = self.width / 2;
        let ranges: Vec<Range<u32>> = (tile.y..tile.y + tile.height)
            .flat_map(|_| tile.x..tile.x + tile.width)
            .map(|x| {
                if x < left && pass < self.passes {
                    pass..pass + 1
                } else {
                    pass..pass
                }
            })
            .collect();
        Some(TileSamples::Each(ranges))
    }

    fn may_be_last(&self, pass: u32) -> bool {
        pass + 1 == self.passes
    }

    fn end_pass(&mut self, pass: u32, _: &mut Film, _: &mut RenderStats, _: bool) -> PassEnd {
        if pass + 1 == self.passes && !self.stalls {
            PassEnd::Done
        } else {
            PassEnd::More
        }
    }
}

/// The test scene's world, its BVH, and uniform 2 x 2's settings.
fn scene() -> (Arc<World>, Arc<SceneIndex>, RenderSettings) {
    let scene = parse_scene(SCENE, None, &Limits::default()).unwrap();
    let world = Arc::new(World::build(&scene));
    let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
    let settings = RenderSettings {
        antialiasing: true,
        samples: 2,
        ..RenderSettings::from_scene(&scene)
    };
    (world, index, settings)
}

/// Starts a job of [`LeftHalf`] on two threads.
fn start(
    (world, index, settings): &(Arc<World>, Arc<SceneIndex>, RenderSettings),
    passes: u32,
    stalls: bool,
) -> RenderJob {
    let strategy = LeftHalf {
        width: settings.width,
        passes,
        stalls,
    };
    let options = JobOptions {
        threads: Some(2),
        ..JobOptions::default()
    };
    RenderJob::start_with(
        world.clone(),
        Some(index.clone()),
        settings.clone(),
        Box::new(strategy),
        options,
    )
    .unwrap()
}

#[test]
fn a_strategy_of_the_callers_renders_through_the_loop() {
    let scene = scene();
    let job = start(&scene, 4, false);
    let (film, stats, state) = job.wait();
    assert_eq!(state, JobState::Done);
    assert_eq!((stats.passes_done, stats.passes_target), (4, 4));

    // The left half took uniform 2 x 2's very samples, the right none.
    let (world, index, settings) = scene;
    let (uniform, _) = render(world, index, settings, Some(2)).unwrap();
    let (width, height) = (film.width(), film.height());
    let mut checked = 0;
    for y in 0..height {
        for x in 0..width {
            if x < width / 2 {
                assert_eq!(film.samples(x, y), 4, "({x}, {y})");
                assert_eq!(film.pixel(x, y), uniform.pixel(x, y), "({x}, {y})");
            } else {
                assert_eq!(film.samples(x, y), 0, "({x}, {y})");
            }
            checked += 1;
        }
    }
    assert_eq!(checked, 40 * 30);
}

#[test]
fn a_strategy_that_samples_nothing_yet_asks_for_more_fails_the_render() {
    let scene = scene();
    let job = start(&scene, 2, true);
    // Without the loop's check the render would never end: give up (and
    // fail) after a minute instead of hanging the suite.
    let deadline = Instant::now() + Duration::from_secs(60);
    while !job.is_finished() && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(10));
    }
    let finished = job.is_finished();
    job.cancel();
    assert!(finished, "the render was still going after a minute");
    let (film, stats, state) = job.wait();
    assert_eq!(
        state,
        JobState::Failed(
            "pass 3 sampled no pixel, yet the sampling strategy asked for another: \
             the render would never end"
                .into()
        )
    );
    // The two passes that sampled were recorded, the empty third not.
    assert_eq!(stats.passes_done, 2);
    assert_eq!(stats.pass_rays.len(), 2);
    assert_eq!(film.samples(0, 0), 2);
}
