//! Adaptive sampling in whole renders: where samples go, determinism, and
//! agreement with uniform sampling.

use std::sync::{Arc, Mutex};

use super::{index, world};
use crate::accel::AccelKind;
use crate::render::adaptive;
use crate::render::{
    AdaptiveSampling, Budget, Encoding, Film, JobOptions, JobState, LensOverride, RenderJob,
    RenderPlan, RenderSettings, Sampling, render,
};
use crate::stats::Counters;

/// A sphere against a flat background and over a floor, lit by one light
/// (soft shadows give it a penumbra).
const SCENE: &str = "\
bclr 0.2 0.3 0.5
v from 0 -5 2 at 0 0 0.5 up 0 0 1 angle 45 hither 0.01 resolution 32 24
l 3 -3 5 1 1 1
f 0.8 0.8 0.8 1 1 1 1 0.2 20 0 1
p 4 -4 -4 0 4 -4 0 4 4 0 -4 4 0
f 0.9 0.2 0.1 0.7 1 1 1 0.3 30 0 1
s 0 0 0.7 0.7
";

fn adaptive(threshold: f32, min_spp: u32, max_spp: u32) -> RenderSettings {
    RenderSettings {
        width: 32,
        height: 24,
        antialiasing: true,
        soft_shadows: true,
        light_size: 0.8,
        depth_of_field: true,
        lens_override: LensOverride {
            aperture: Some(3.0),
            focal: Some(1.2),
        },
        sampling: Sampling::Adaptive(AdaptiveSampling {
            noise_threshold: threshold,
            min_spp,
            max_spp,
            budget: None,
        }),
        ..RenderSettings::default()
    }
}

fn render_film(settings: RenderSettings, threads: usize) -> Film {
    let w = world(SCENE);
    let idx = index(&w, settings.accel);
    render(w, idx, settings, Some(threads)).unwrap().0
}

/// Every pixel's sample count, row-major.
fn counts(film: &Film) -> Vec<u32> {
    (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| film.samples(x, y)))
        .collect()
}

#[test]
fn flat_pixels_stop_at_the_minimum_while_edges_refine() {
    let film = render_film(
        RenderSettings {
            depth_of_field: false,
            soft_shadows: false,
            ..adaptive(0.01, 8, 64)
        },
        2,
    );
    // The top corners see only the background.
    assert_eq!(film.samples(0, 0), 8);
    assert_eq!(film.samples(31, 0), 8);
    let counts = counts(&film);
    let refined = counts.iter().filter(|&&n| n > 8).count();
    assert!(refined > 0, "no pixel refined: {counts:?}");
    assert!(
        refined < counts.len() / 2,
        "most pixels refined: {counts:?}"
    );
    assert!(counts.iter().all(|&n| (8..=64).contains(&n)));
}

#[test]
fn the_image_is_the_same_whatever_the_thread_count() {
    // Twelve tiles, rendered in whatever order the threads take them.
    let settings = RenderSettings {
        width: 128,
        height: 96,
        ..adaptive(0.02, 4, 36)
    };
    let one = render_film(settings.clone(), 1);
    // Scheduling races differ from run to run: give them several chances.
    for threads in [2, 3, 4, 8, 3, 2] {
        assert!(
            render_film(settings.clone(), threads) == one,
            "{threads} threads"
        );
    }
}

/// How many of two decisions' pixels differ.
fn differing(a: &[bool], b: &[bool]) -> usize {
    a.iter().zip(b).filter(|(a, b)| a != b).count()
}

/// The adaptive passes run by hand, one tile after another on this thread.
fn sequential(plan: &RenderPlan) -> Film {
    let a = *plan.settings.adaptive().expect("adaptive settings");
    let mut film = Film::with_error_estimate(plan.settings.width, plan.settings.height);
    let mut counters = Counters::default();
    let mut refinement = adaptive::Refinement::default();
    loop {
        let planned: Vec<_> = plan
            .tiles
            .iter()
            .map(|tile| adaptive::plan(&film, tile, &a))
            .collect();
        if planned.iter().flatten().all(|samples| samples.is_empty()) {
            return film;
        }
        for (tile, samples_of) in plan.tiles.iter().zip(planned) {
            let samples = plan.render_samples(tile, &samples_of, false, &mut counters);
            let counts: Vec<u32> = samples_of.iter().map(|s| s.len() as u32).collect();
            film.add_samples(tile, &counts, &samples.values, &samples.tests);
        }
        let active = refinement.decide(&film, &a);
        // Re-measured in the rows a pass changed, the decision must be
        // the one every row measured afresh gives.
        if let Some(mean) = refinement.mean_per_sample() {
            let afresh = adaptive::Refinement::relative_to(mean).decide(&film, &a);
            assert!(
                active == afresh,
                "{} pixels differ",
                differing(&active, &afresh)
            );
        }
        film.set_active(active);
    }
}

#[test]
fn progressive_passes_equal_a_sequential_render() {
    let settings = adaptive(0.02, 4, 49);
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let plan = RenderPlan::new(w.clone(), idx.clone(), settings.clone()).unwrap();
    let job = RenderJob::start(
        w,
        Some(idx),
        settings,
        JobOptions {
            threads: Some(3),
            ..JobOptions::default()
        },
    )
    .unwrap();
    let (film, stats, state) = job.wait();
    assert_eq!(state, JobState::Done);
    let expected = sequential(&plan);
    assert_eq!(counts(&film), counts(&expected), "sample counts");
    for y in 0..film.height() {
        for x in 0..film.width() {
            assert_eq!(film.pixel(x, y), expected.pixel(x, y), "({x}, {y})");
            assert_eq!(film.is_active(x, y), expected.is_active(x, y), "({x}, {y})");
        }
    }
    assert!(film == expected);
    let summary = stats.adaptive.expect("adaptive statistics");
    assert_eq!(summary.active_pixels, 0);
    assert_eq!(
        summary.samples,
        counts(&film).iter().map(|&n| n as u64).sum::<u64>()
    );
    assert_eq!(summary.max_spp, *counts(&film).iter().max().unwrap());
    assert!(summary.error > 0.0 && summary.error < 0.02, "{summary:?}");
    assert_eq!(stats.passes_done, stats.passes_target);
}

/// Sharp edges on a larger film: late passes refine a few rows, and the
/// decisions, which re-measure only the rows a pass changed and their
/// neighbours, must be those every row measured afresh gives (checked
/// pass by pass in [`sequential`]).
#[test]
fn decisions_over_the_changed_rows_equal_decisions_over_the_film() {
    let settings = RenderSettings {
        width: 128,
        height: 96,
        soft_shadows: false,
        depth_of_field: false,
        ..adaptive(0.01, 4, 64)
    };
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let film = sequential(&RenderPlan::new(w, idx, settings).unwrap());
    let most = counts(&film).into_iter().max().unwrap_or(0);
    let rows_refined_last = (0..film.height())
        .filter(|&y| (0..film.width()).any(|x| film.samples(x, y) == most))
        .count();
    assert!(
        most > 8 && (1..film.height() as usize / 4).contains(&rows_refined_last),
        "{rows_refined_last} rows reached {most} samples: the last passes must refine a few rows"
    );
}

#[test]
fn pixels_below_the_threshold_get_no_more_samples() {
    let settings = adaptive(0.03, 2, 36);
    let a = *settings.adaptive().unwrap();
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let passes: Arc<Mutex<Vec<Film>>> = Arc::default();
    let record = passes.clone();
    let job = RenderJob::start(
        w,
        Some(idx),
        settings,
        JobOptions {
            threads: Some(2),
            on_pass: Some(Box::new(move |_, film, _| {
                record.lock().unwrap().push(film.clone())
            })),
            ..JobOptions::default()
        },
    )
    .unwrap();
    job.wait();
    let passes = passes.lock().unwrap();
    assert!(passes.len() > 3, "{} passes", passes.len());
    let mut stopped = 0;
    // Costs are relative to the mean when every pixel has the minimum.
    let mean = passes
        .iter()
        .find(|film| {
            (0..film.height()).all(|y| (0..film.width()).all(|x| film.samples(x, y) >= a.min_spp))
        })
        .and_then(|film| {
            let mut refinement = adaptive::Refinement::default();
            refinement.decide(film, &a);
            refinement.mean_per_sample()
        })
        .expect("a pass with the minimum everywhere");
    for pair in passes.windows(2) {
        let (before, after) = (&pair[0], &pair[1]);
        let mut measured = adaptive::Refinement::relative_to(mean);
        measured.decide(before, &a);
        let errors = measured.pooled_errors();
        for y in 0..before.height() {
            for x in 0..before.width() {
                let n = before.samples(x, y);
                let i = (y * before.width() + x) as usize;
                if before.is_active(x, y) {
                    // Below the minimum nothing is measured.
                    assert!(
                        n < a.min_spp
                            || adaptive::is_active(n, errors[i], measured.relative_cost(i), &a)
                            || crate::render::estimate::variance_estimate(
                                n,
                                before.spread(x, y).unwrap()
                            ) >= adaptive::threshold_at(n, measured.relative_cost(i), &a),
                        "pixel ({x}, {y}) active though converged"
                    );
                    assert_eq!(after.samples(x, y), adaptive::next_count(n, &a));
                } else {
                    stopped += 1;
                    assert_eq!(after.samples(x, y), n, "pixel ({x}, {y}) sampled again");
                    assert_eq!(after.pixel(x, y), before.pixel(x, y));
                }
            }
        }
    }
    assert!(stopped > 0, "no pixel ever stopped");
}

/// The pixel's samples: with the lens and soft shadows off, as those
/// points follow adaptive sampling's own sequence (stratified in every
/// prefix where a pixel may stop), not uniform sampling's independent
/// lens points and one multi-jittered light pattern.
#[test]
fn threshold_zero_takes_the_samples_of_uniform_sampling_at_the_maximum() {
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let settings = RenderSettings {
        soft_shadows: false,
        depth_of_field: false,
        ..adaptive(0.0, 1, 16)
    };
    let adaptive = render(w.clone(), idx.clone(), settings.clone(), Some(2))
        .unwrap()
        .0;
    let uniform = RenderSettings {
        sampling: Sampling::Uniform,
        samples: 4,
        ..settings
    };
    let uniform = render(w, idx, uniform, Some(2)).unwrap().0;
    assert!(counts(&adaptive).iter().all(|&n| n == 16));
    // The same samples, summed in another order.
    for y in 0..uniform.height() {
        for x in 0..uniform.width() {
            let (a, u) = (adaptive.pixel(x, y).unwrap(), uniform.pixel(x, y).unwrap());
            assert!((a - u).abs().max_element() < 1e-5, "({x}, {y}): {a} vs {u}");
        }
    }
}

/// What a viewer draws over the image: every pixel active before the
/// first pass, some between passes while edges refine, none once done;
/// nothing for uniform sampling.
#[test]
fn a_jobs_active_pixels_go_from_all_to_none() {
    let settings = adaptive(0.01, 4, 64);
    let pixels = (settings.width * settings.height) as usize;
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let between: Arc<Mutex<Vec<Vec<bool>>>> = Arc::default();
    let record = between.clone();
    let job = RenderJob::start(
        w.clone(),
        Some(idx.clone()),
        settings.clone(),
        JobOptions {
            threads: Some(2),
            paused: true,
            on_pass: Some(Box::new(move |_, film, _| {
                let mask = film.active_pixels().expect("an adaptive film").to_vec();
                record.lock().unwrap().push(mask);
            })),
            ..JobOptions::default()
        },
    )
    .unwrap();
    assert_eq!(job.active_pixels(), Some(vec![true; pixels]));
    job.set_paused(false);
    crate::waiting::wait_until("the adaptive job", || job.is_finished());
    assert_eq!(job.active_pixels(), Some(vec![false; pixels]));
    let between = between.lock().unwrap();
    assert!(
        between
            .iter()
            .any(|mask| mask.contains(&true) && mask.contains(&false)),
        "no pass left some pixels refining and others done"
    );
    let uniform = RenderSettings {
        sampling: Sampling::Uniform,
        ..settings
    };
    let job = RenderJob::start(w, Some(idx), uniform, JobOptions::default()).unwrap();
    assert_eq!(job.active_pixels(), None);
}

/// The finished image the render threads make tile by tile is the
/// adaptive film resolved at the end: any pass may be a tile's last (a
/// neighbour's noise may bring it back), so each makes its bytes.
#[test]
fn an_adaptive_jobs_finished_image_is_its_resolved_film() {
    let job = RenderJob::start(
        world(SCENE),
        None,
        adaptive(0.02, 4, 16),
        JobOptions {
            threads: Some(2),
            finished_image: Some(Encoding::Srgb),
            ..JobOptions::default()
        },
    )
    .unwrap();
    let done = job.wait_with_image();
    assert_eq!(done.state, JobState::Done);
    let image = done.image.expect("a finished image");
    assert!(image == done.film.to_image(Encoding::Srgb));
}

/// Compare mode's "equal samples": with a budget of 12 samples per pixel
/// and a threshold of 0 (every pixel refines to the maximum), the pass
/// from 8 to 16 samples refines only the half of the pixels with the
/// largest errors, and the render takes exactly its budget, the same on
/// any thread count.
#[test]
fn a_sample_budget_ends_the_render_at_its_total() {
    let pixels = 32 * 24;
    let total = 12 * pixels as u64;
    let settings = RenderSettings {
        sampling: Sampling::Adaptive(AdaptiveSampling {
            budget: Some(Budget::Samples(total)),
            ..*adaptive(0.0, 4, 64).adaptive().unwrap()
        }),
        ..adaptive(0.0, 4, 64)
    };
    let film = render_film(settings.clone(), 3);
    let counts = counts(&film);
    assert_eq!(counts.iter().map(|&n| u64::from(n)).sum::<u64>(), total);
    assert_eq!(counts.iter().filter(|&&n| n == 16).count(), pixels / 2);
    assert!(counts.iter().all(|&n| n == 8 || n == 16));
    assert!(film == render_film(settings, 1));
}

/// Compare mode's "equal time", through its mechanism rather than a
/// clock: a budget already spent stops the render after its first pass
/// (one sample in every pixel, no hole), its target met.
#[test]
fn a_spent_time_budget_ends_the_render_after_its_first_pass() {
    let settings = RenderSettings {
        sampling: Sampling::Adaptive(AdaptiveSampling {
            budget: Some(Budget::Time(std::time::Duration::ZERO)),
            ..*adaptive(0.01, 4, 64).adaptive().unwrap()
        }),
        ..adaptive(0.01, 4, 64)
    };
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let (film, stats) = render(w, idx, settings, Some(2)).unwrap();
    assert_eq!((stats.passes_done, stats.passes_target), (1, 1));
    assert!(counts(&film).iter().all(|&n| n == 1));
}

/// A clock that moves only when told: each tile recorded takes one second.
#[derive(Default)]
struct TileClock(std::sync::atomic::AtomicU64);

impl crate::render::driver::Clock for TileClock {
    fn now(&self) -> std::time::Duration {
        std::time::Duration::from_secs(self.0.load(std::sync::atomic::Ordering::SeqCst))
    }
}

/// A time budget is the job's clock's: with one thread and a clock that
/// ticks a second per tile (4 tiles a pass), a budget of 6 s lets the first
/// pass's 4 tiles and then 2 of the second pass's in, the time recorded is
/// the budget, and the pass that spent it is the last.
#[test]
fn a_time_budget_stops_the_tiles_once_the_job_clock_reaches_it() {
    let settings = RenderSettings {
        width: 64,
        height: 64,
        sampling: Sampling::Adaptive(AdaptiveSampling {
            budget: Some(Budget::Time(std::time::Duration::from_secs(6))),
            ..*adaptive(0.0, 4, 64).adaptive().unwrap()
        }),
        ..adaptive(0.0, 4, 64)
    };
    let clock = Arc::new(TileClock::default());
    let ticks = clock.clone();
    let w = world(SCENE);
    let job = RenderJob::start(
        w.clone(),
        Some(index(&w, AccelKind::Bvh)),
        settings,
        JobOptions {
            threads: Some(1),
            clock: Some(clock),
            on_progress: Some(Box::new(move || {
                ticks.0.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
            })),
            ..JobOptions::default()
        },
    )
    .unwrap();
    let (film, stats, state) = job.wait();
    assert_eq!(state, JobState::Done);
    assert_eq!((stats.passes_done, stats.passes_target), (2, 2));
    let counts = counts(&film);
    // The first pass gives every pixel 1 sample, the second 1 more to the
    // pixels of its first two tiles (the top 64 x 32 pixels).
    let twice = counts.iter().filter(|&&n| n == 2).count();
    assert_eq!(twice, 64 * 32, "{counts:?}");
    assert!(counts.iter().all(|&n| n == 1 || n == 2));
    assert!(counts[..64 * 32].iter().all(|&n| n == 2));
    assert_eq!(stats.render_time, std::time::Duration::from_secs(6));
}
