//! A progressive render running in the background: passes over tiles on a
//! thread pool, cancellable at any moment, observable at any time.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::accel::SceneIndex;
use crate::camera::CameraError;
use crate::stats::{Counters, RenderStats};
use crate::world::World;

use super::settings::SettingsError;
use super::{Encoding, Film, Frame, RenderSettings};

/// Why a render could not start.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("invalid settings: {0}")]
    Settings(#[from] SettingsError),
    #[error("invalid camera: {0}")]
    Camera(#[from] CameraError),
    #[error("could not start render threads: {0}")]
    Threads(String),
    #[error("{0}")]
    Panicked(String),
}

/// Where a job stands.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum JobState {
    /// Passes are running (possibly paused between tiles).
    Rendering,
    /// The target was reached (never, when refining past it).
    Done,
    /// Stopped by [`RenderJob::cancel`].
    Cancelled,
    /// A bug made a render thread panic; the message says what happened.
    Failed(String),
}

/// Everything a viewer needs at one moment.
#[derive(Debug, Clone)]
pub struct Snapshot {
    pub width: u32,
    pub height: u32,
    /// Row-major RGBA8; pixels without a sample yet are transparent.
    pub rgba: Vec<u8>,
    pub stats: RenderStats,
    pub state: JobState,
    pub paused: bool,
}

/// Options that change how a job runs but not the image it makes.
#[derive(Default)]
pub struct JobOptions {
    /// Worker threads; `None` uses every core.
    pub threads: Option<usize>,
    /// Called after every tile and pass, from a render thread, so a viewer
    /// can wake up (e.g. `egui::Context::request_repaint`).
    pub on_progress: Option<Box<dyn Fn() + Send + Sync>>,
    /// Called with the pass number (from 1) and the film as it stands after
    /// each completed pass, before the next begins: to record convergence.
    pub on_pass: Option<PassObserver>,
}

/// See [`JobOptions::on_pass`].
pub type PassObserver = Box<dyn Fn(u32, &Film) + Send + Sync>;

struct Progress {
    film: Film,
    stats: RenderStats,
    state: JobState,
}

struct Shared {
    cancel: AtomicBool,
    paused: Mutex<bool>,
    resumed: Condvar,
    progress: Mutex<Progress>,
    on_progress: Option<Box<dyn Fn() + Send + Sync>>,
    on_pass: Option<PassObserver>,
}

impl Shared {
    fn progress(&self) -> MutexGuard<'_, Progress> {
        // A panic while holding the lock is caught and reported as
        // `JobState::Failed`; the data stays usable.
        self.progress.lock().unwrap_or_else(PoisonError::into_inner)
    }

    fn notify(&self) {
        if let Some(f) = &self.on_progress {
            f();
        }
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// Blocks a render thread while the job is paused (until resumed or
    /// cancelled).
    fn wait_while_paused(&self) {
        let mut paused = self.paused.lock().unwrap_or_else(PoisonError::into_inner);
        while *paused && !self.cancelled() {
            paused = self
                .resumed
                .wait(paused)
                .unwrap_or_else(PoisonError::into_inner);
        }
    }
}

/// A background render. Dropping it cancels it and waits for its threads.
pub struct RenderJob {
    shared: Arc<Shared>,
    index: Arc<SceneIndex>,
    worker: Option<JoinHandle<()>>,
}

impl RenderJob {
    /// Starts rendering `world` with `settings`, using `index` (built with
    /// the settings' acceleration) so that several renders can share it.
    pub fn start(
        world: Arc<World>,
        index: Arc<SceneIndex>,
        settings: RenderSettings,
        options: JobOptions,
    ) -> Result<RenderJob, RenderError> {
        settings.validate()?;
        let frame = Frame::new(world, index.clone(), settings)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(options.threads.unwrap_or(0))
            .thread_name(|i| format!("render-{i}"))
            .build()
            .map_err(|e| RenderError::Threads(e.to_string()))?;
        let shared = Arc::new(Shared {
            cancel: AtomicBool::new(false),
            paused: Mutex::new(false),
            resumed: Condvar::new(),
            progress: Mutex::new(Progress {
                film: Film::new(frame.settings.width, frame.settings.height),
                stats: RenderStats {
                    width: frame.settings.width,
                    height: frame.settings.height,
                    passes_target: frame.passes_target(),
                    build_time: frame.index.build_time(),
                    ..RenderStats::default()
                },
                state: JobState::Rendering,
            }),
            on_progress: options.on_progress,
            on_pass: options.on_pass,
        });
        let worker_shared = shared.clone();
        let worker = std::thread::Builder::new()
            .name("render-job".into())
            .spawn(move || {
                let outcome = catch_unwind(AssertUnwindSafe(|| {
                    pool.install(|| run_passes(&frame, &worker_shared))
                }));
                let state = match outcome {
                    Ok(()) if worker_shared.cancelled() => JobState::Cancelled,
                    Ok(()) => JobState::Done,
                    Err(panic) => JobState::Failed(panic_message(&panic)),
                };
                worker_shared.progress().state = state;
                worker_shared.notify();
            })
            .map_err(|e| RenderError::Threads(e.to_string()))?;
        Ok(RenderJob {
            shared,
            index,
            worker: Some(worker),
        })
    }

    /// The acceleration structure this job traces against.
    pub fn index(&self) -> &Arc<SceneIndex> {
        &self.index
    }

    /// Asks the job to stop; render threads finish the tile they are on.
    pub fn cancel(&self) {
        self.shared.cancel.store(true, Ordering::Relaxed);
        self.set_paused(false);
    }

    /// Pauses or resumes the render between tiles.
    pub fn set_paused(&self, paused: bool) {
        *self
            .shared
            .paused
            .lock()
            .unwrap_or_else(PoisonError::into_inner) = paused;
        self.shared.resumed.notify_all();
    }

    pub fn is_paused(&self) -> bool {
        *self
            .shared
            .paused
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }

    /// True once the job has stopped (done, cancelled or failed).
    pub fn is_finished(&self) -> bool {
        self.shared.progress().state != JobState::Rendering
    }

    pub fn state(&self) -> JobState {
        self.shared.progress().state.clone()
    }

    pub fn stats(&self) -> RenderStats {
        self.shared.progress().stats.clone()
    }

    /// The current image, resolved with `encoding`, and its statistics.
    pub fn snapshot(&self, encoding: Encoding) -> Snapshot {
        let paused = self.is_paused();
        let p = self.shared.progress();
        Snapshot {
            width: p.film.width(),
            height: p.film.height(),
            rgba: p.film.to_rgba8(encoding),
            stats: p.stats.clone(),
            state: p.state.clone(),
            paused,
        }
    }

    /// Waits for the job to stop and returns its film and statistics.
    pub fn wait(mut self) -> (Film, RenderStats, JobState) {
        if let Some(worker) = self.worker.take() {
            // The worker catches render panics itself; a join error could
            // only come from the bookkeeping around it.
            let _ = worker.join();
        }
        let mut p = self.shared.progress();
        let film = std::mem::replace(&mut p.film, Film::new(0, 0));
        (film, p.stats.clone(), p.state.clone())
    }
}

impl Drop for RenderJob {
    fn drop(&mut self) {
        if let Some(worker) = self.worker.take() {
            self.cancel();
            let _ = worker.join();
        }
    }
}

/// Runs passes until the target (or forever when refining) or cancellation.
fn run_passes(frame: &Frame, shared: &Shared) {
    let target = frame.passes_target();
    let mut rendered = Duration::ZERO;
    for pass in 0.. {
        if shared.cancelled() || (pass >= target && !frame.settings.keep_refining) {
            return;
        }
        let start = Instant::now();
        frame.tiles.par_iter().for_each(|tile| {
            shared.wait_while_paused();
            if shared.cancelled() {
                return;
            }
            let mut counters = Counters::default();
            let values = frame.render_tile(pass, tile, &mut counters);
            {
                let mut p = shared.progress();
                p.film.add_tile(tile, &values);
                p.stats.counters += counters;
                p.stats.render_time = rendered + start.elapsed();
            }
            shared.notify();
        });
        if shared.cancelled() {
            return;
        }
        let elapsed = start.elapsed();
        rendered += elapsed;
        {
            let mut p = shared.progress();
            p.stats.passes_done = pass + 1;
            p.stats.pass_times.push(elapsed);
            p.stats.render_time = rendered;
            if let Some(observe) = &shared.on_pass {
                observe(pass + 1, &p.film);
            }
        }
        shared.notify();
    }
}

fn panic_message(panic: &Box<dyn std::any::Any + Send>) -> String {
    if let Some(s) = panic.downcast_ref::<&str>() {
        format!("render thread panicked: {s}")
    } else if let Some(s) = panic.downcast_ref::<String>() {
        format!("render thread panicked: {s}")
    } else {
        "render thread panicked".to_string()
    }
}
