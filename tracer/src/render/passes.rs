//! The render loop: passes over the plan's tiles, each tile's samples as
//! the strategy asks, recorded into the outputs, until the strategy says
//! done or the job is cancelled. One loop for every strategy; where it
//! runs, and on which threads, is the driver's: all of a pass's tiles at
//! once on a pool, or one after another in a page's time slices, the loop
//! giving way between tiles (`slices`).

use std::sync::Mutex;
use std::time::Duration;

use rayon::prelude::*;

use super::control::{Control, lock};
use super::driver::{Clock, FailureSlot, WorkingFor};
use super::outputs::{Outputs, Recording, TileBatch};
use super::slices::{self, give_way};
use super::strategy::{PassEnd, SamplingStrategy};
use super::{Budget, Film, RenderPlan, Tile};

/// Called with the pass number (from 1), the film as it stands after each
/// completed pass, before the next begins, and whether that pass was the
/// render's last: to record convergence.
pub type PassListener = Box<dyn Fn(u32, &Film, bool) + Send + Sync>;

/// Everything a loop reads and writes besides its plan and strategy: the
/// job's shared state.
pub(super) struct LoopContext<'a> {
    pub control: &'a Control,
    pub outputs: &'a Mutex<Outputs>,
    pub recording: Recording,
    pub clock: &'a dyn Clock,
    pub failure: &'a FailureSlot,
    pub on_pass: Option<&'a PassListener>,
    /// The loop runs in time slices ([`super::driver::Host::Slices`]):
    /// tiles one after another, giving way when the slice is spent.
    pub sliced: bool,
}

/// The time a render may take ([`Budget::Time`]), as its passes spend it.
struct Deadline {
    limit: Option<Duration>,
    /// The earlier passes' time, and when this pass started.
    before: Duration,
    pass_start: Duration,
}

impl Deadline {
    fn spent(&self, clock: &dyn Clock) -> bool {
        self.limit.is_some_and(|limit| self.elapsed(clock) >= limit)
    }

    fn elapsed(&self, clock: &dyn Clock) -> Duration {
        self.before + clock.now().saturating_sub(self.pass_start)
    }
}

/// Runs passes until `strategy` says done or the job is cancelled. Never
/// gives way unless [`LoopContext::sliced`]. Fails when a pass sampled no
/// pixel and the strategy still asks for another: it decides from the
/// film alone, which that pass left as it was, so every later pass would
/// sample nothing too, and the render would never end.
pub(super) async fn run(
    plan: &RenderPlan,
    strategy: &mut dyn SamplingStrategy,
    cx: &LoopContext<'_>,
) -> Result<(), String> {
    let limit = match plan.settings.adaptive().and_then(|a| a.budget) {
        Some(Budget::Time(limit)) => Some(limit),
        _ => None,
    };
    let mut deadline = Deadline {
        limit,
        before: Duration::ZERO,
        pass_start: Duration::ZERO,
    };
    // Passes are counted in a u32, so u32::MAX at most: keep refining at
    // a thousand passes a second would take 50 days to reach it.
    for pass in 0..u32::MAX {
        if cx.control.cancelled() {
            return Ok(());
        }
        deadline.pass_start = cx.clock.now();
        let rays_before = lock(cx.outputs).stats.counters.total_rays();
        let tiles_of = &*strategy;
        let render_tile = |tile: &Tile| {
            let _working = WorkingFor::job(cx.failure);
            // A time budget spent starts no tile, after the first pass.
            if !cx.control.proceed() || (pass > 0 && deadline.spent(cx.clock)) {
                return;
            }
            let samples = tiles_of.tile_samples(pass, tile, &lock(cx.outputs).film);
            let Some(samples) = samples else {
                return;
            };
            let batch = TileBatch::render(plan, tile, samples, cx.recording);
            let mut outputs = lock(cx.outputs);
            outputs.record(tile, batch, tiles_of.may_be_last(pass));
            outputs.stats.render_time = deadline.elapsed(cx.clock);
            outputs.stats.count_tile(rayon::current_thread_index());
            drop(outputs);
            cx.control.tile_done();
        };
        if cx.sliced {
            for tile in &plan.tiles {
                if !proceed_in_slices(cx.control).await {
                    return Ok(());
                }
                render_tile(tile);
                if slices::spent() {
                    give_way(true).await;
                }
            }
        } else {
            plan.tiles.par_iter().for_each(render_tile);
        }
        if cx.control.cancelled() || end_pass(pass, strategy, &mut deadline, rays_before, cx)? {
            return Ok(());
        }
    }
    Ok(())
}

/// [`Control::proceed`] for a loop in time slices, which may not block
/// its thread: while the job is held it gives way. False once the job is
/// cancelled, or held while waited for, which cancels it (nothing else
/// could resume it).
pub(super) async fn proceed_in_slices(control: &Control) -> bool {
    while control.held() && !control.cancelled() {
        if slices::waited_for() {
            control.cancel();
        } else {
            give_way(false).await;
        }
    }
    !control.cancelled()
}

/// Ends pass `pass`: the strategy decides, the pass's figures are
/// recorded and the pass listener told. True when the render is done; an
/// error when the pass sampled nothing and the strategy wants more.
fn end_pass(
    pass: u32,
    strategy: &mut dyn SamplingStrategy,
    deadline: &mut Deadline,
    rays_before: u64,
    cx: &LoopContext,
) -> Result<bool, String> {
    let done = {
        let mut outputs = lock(cx.outputs);
        let outputs = &mut *outputs;
        let spent = deadline.spent(cx.clock);
        let end = strategy.end_pass(pass, &mut outputs.film, &mut outputs.stats, spent);
        // A pass's time takes in the decision after it: the next pass
        // waits for it, and so does whoever waits for the image.
        let elapsed = cx.clock.now().saturating_sub(deadline.pass_start);
        deadline.before += elapsed;
        let stats = &mut outputs.stats;
        let traced = stats.counters.total_rays() - rays_before;
        if traced == 0 && end == PassEnd::More {
            return Err(format!(
                "pass {} sampled no pixel, yet the sampling strategy asked for another: \
                 the render would never end",
                pass + 1
            ));
        }
        stats.passes_done = pass + 1;
        stats.pass_times.push(elapsed);
        stats.pass_rays.push(traced);
        stats.render_time = deadline.before;
        if let Some(observe) = cx.on_pass {
            observe(pass + 1, &outputs.film, end == PassEnd::Done);
        }
        end == PassEnd::Done
    };
    cx.control.notify();
    Ok(done)
}
