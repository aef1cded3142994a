//! Jobs hosted in time slices (`Host::Slices`): what a page without
//! workers renders with.

use std::time::Duration;

use super::{SCENE, index, sequential, settings, world};
use crate::accel::AccelKind;
use crate::render::driver::{Host, set_viewers_hidden};
use crate::render::strategy::{PassEnd, SamplingStrategy, TileSamples, Uniform};
use crate::render::{
    Encoding, Film, JobOptions, JobState, RenderJob, RenderPlan, Tile, run_slices, slices_pending,
};
use crate::stats::RenderStats;

/// Pixels with a sample so far.
fn covered(job: &RenderJob) -> usize {
    let snapshot = job.snapshot(Encoding::Srgb);
    snapshot.rgba.chunks(4).filter(|p| p[3] > 0).count()
}

fn sliced(options: JobOptions) -> (RenderJob, Film) {
    let w = world(SCENE);
    let idx = index(&w, AccelKind::Bvh);
    let s = settings(70, 45);
    let expected = sequential(&RenderPlan::new(w.clone(), idx.clone(), s.clone()).unwrap());
    let options = JobOptions {
        host: Host::Slices,
        ..options
    };
    (
        RenderJob::start(w, Some(idx), s, options).unwrap(),
        expected,
    )
}

#[test]
fn a_spent_slice_renders_one_tile_and_the_slices_add_up_to_the_image() {
    let (job, expected) = sliced(JobOptions::default());
    assert!(slices_pending());
    assert_eq!(covered(&job), 0, "nothing runs before the first slice");
    let mut slices = 0;
    while run_slices(Duration::ZERO) {
        slices += 1;
        if slices == 1 {
            assert_eq!(covered(&job), 32 * 32, "the first tile alone");
        }
    }
    // 70 x 45 is 3 x 2 tiles of 32, over 9 passes.
    assert_eq!(slices, 6 * 9);
    assert!(!slices_pending(), "the loop ended");
    let (film, stats, state) = job.wait();
    assert_eq!(state, JobState::Done);
    assert_eq!(stats.passes_done, 9);
    assert_eq!(stats.tiles_by_thread, [6 * 9], "all on this thread");
    assert_eq!(film, expected);
}

#[test]
fn waiting_for_a_job_in_slices_runs_it_to_the_end_on_the_waiting_thread() {
    let (job, expected) = sliced(JobOptions::default());
    assert!(run_slices(Duration::ZERO));
    let (film, stats, state) = job.wait();
    assert_eq!(state, JobState::Done);
    assert_eq!(stats.passes_done, 9);
    assert_eq!(film, expected);
    assert!(!slices_pending());
}

#[test]
fn a_paused_job_in_slices_waits_for_the_next_slice_and_a_wait_cancels_it() {
    let (job, _) = sliced(JobOptions {
        paused: true,
        ..JobOptions::default()
    });
    assert!(!run_slices(Duration::ZERO), "nothing to do at once");
    assert_eq!(covered(&job), 0);
    assert!(slices_pending(), "it waits to be resumed");
    job.set_paused(false);
    assert!(run_slices(Duration::ZERO));
    assert_eq!(covered(&job), 32 * 32);
    job.set_paused(true);
    assert!(!run_slices(Duration::ZERO));
    assert_eq!(covered(&job), 32 * 32);
    // Nothing could resume it while this thread waits.
    let (_, stats, state) = job.wait();
    assert_eq!(state, JobState::Cancelled);
    assert_eq!(stats.passes_done, 0);
}

#[test]
fn a_dropped_job_leaves_no_slices() {
    let (job, _) = sliced(JobOptions::default());
    assert!(run_slices(Duration::ZERO));
    drop(job);
    assert!(!slices_pending());
    assert!(!run_slices(Duration::ZERO));
}

/// Uniform sampling that panics on its second tile.
struct Failing(Uniform);

impl SamplingStrategy for Failing {
    fn film(&self, width: u32, height: u32) -> Film {
        self.0.film(width, height)
    }

    fn passes_target(&self) -> u32 {
        self.0.passes_target()
    }

    fn tile_samples(&self, pass: u32, tile: &Tile, film: &Film) -> Option<TileSamples> {
        assert!(tile.x == 0 || pass > 0, "a bug in the strategy");
        self.0.tile_samples(pass, tile, film)
    }

    fn may_be_last(&self, pass: u32) -> bool {
        self.0.may_be_last(pass)
    }

    fn end_pass(
        &mut self,
        pass: u32,
        film: &mut Film,
        stats: &mut RenderStats,
        spent: bool,
    ) -> PassEnd {
        self.0.end_pass(pass, film, stats, spent)
    }
}

#[test]
fn a_panic_in_a_slice_fails_the_job_with_its_message() {
    let w = world(SCENE);
    let s = settings(70, 45);
    let strategy = Box::new(Failing(Uniform::new(&s)));
    let options = JobOptions {
        host: Host::Slices,
        ..JobOptions::default()
    };
    let job = RenderJob::start_with(
        w.clone(),
        Some(index(&w, AccelKind::Bvh)),
        s,
        strategy,
        options,
    )
    .unwrap();
    assert!(run_slices(Duration::ZERO), "the first tile");
    assert!(!run_slices(Duration::ZERO), "the second panicked");
    assert!(!slices_pending());
    let state = job.state();
    let JobState::Failed(message) = state else {
        panic!("not failed: {state:?}");
    };
    assert!(message.contains("a bug in the strategy"), "{message}");
}

/// Shows the viewers again when dropped, even when the test fails: no
/// other test in this process runs a viewed job.
struct Hidden;

impl Hidden {
    fn viewers() -> Self {
        set_viewers_hidden(true);
        Self
    }
}

impl Drop for Hidden {
    fn drop(&mut self) {
        set_viewers_hidden(false);
    }
}

#[test]
fn hidden_viewers_hold_viewed_jobs_only() {
    let (viewed, _) = sliced(JobOptions {
        viewed: true,
        ..JobOptions::default()
    });
    let (measuring, _) = sliced(JobOptions::default());
    let hidden = Hidden::viewers();
    // Each loop takes one tile of a spent slice, if it may.
    assert!(run_slices(Duration::ZERO));
    assert_eq!(covered(&viewed), 0, "held while hidden");
    assert_eq!(covered(&measuring), 32 * 32, "a measurement goes on");
    drop(hidden);
    run_slices(Duration::ZERO);
    assert_eq!(covered(&viewed), 32 * 32, "shown again");
}
