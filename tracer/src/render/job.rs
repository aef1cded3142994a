//! A progressive render running in the background: passes over tiles on a
//! thread pool, cancellable at any moment, observable at any time.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rayon::prelude::*;

use crate::accel::SceneIndex;
use crate::camera::CameraError;
use crate::stats::{AdaptiveStats, Counters, RenderStats};
use crate::world::World;

use glam::Vec3A;

use super::adaptive;
use super::film::encode_values;
use super::settings::SettingsError;
use super::view::{View, ViewFilm, ViewHeatmap, ViewSample, view_rgba8};
use super::{Budget, Encoding, Film, PlannedSamples, RenderPlan, RenderSettings};

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
    /// The acceleration structure is being built.
    Building,
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

impl Snapshot {
    /// The image without alpha, ready to save.
    pub fn to_image(&self) -> Option<image::RgbImage> {
        super::film::rgba_to_rgb_image(self.width, self.height, &self.rgba)
    }
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
    pub on_pass: Option<PassListener>,
    /// Let an interactive viewer's threads run first whenever they wake
    /// (batch scheduling on Linux, the lowest priority elsewhere), while
    /// render threads keep the share of the cores a headless render gets.
    pub yield_to_viewer: bool,
    /// Render only in the time other work leaves (Linux's idle scheduling,
    /// the lowest priority elsewhere): a second view beside the main render
    /// (the window's observer) that must not slow it.
    pub idle_priority: bool,
    /// Also measure the views (cost and what each pixel saw) into a
    /// [`ViewFilm`]; off, the render pays nothing for them.
    pub views: bool,
    /// Start paused (as [`RenderJob::set_paused`] right away, but before the
    /// job builds or renders anything).
    pub paused: bool,
    /// Pause the job once this many tiles are in (tiles already under way
    /// finish too): a first pass held half done whatever the machine's
    /// speed, for a viewer stepping through it and for tests.
    pub pause_after_tiles: Option<u64>,
    /// Also make the finished image's 8-bit RGB in this encoding, each
    /// tile's bytes by the render thread that lands its last pass, while
    /// they are in its cache ([`RenderJob::wait_with_image`]). For a caller
    /// that saves the image once it is done: resolving the whole film after
    /// the render is serial work on the command line's critical path.
    pub finished_image: Option<Encoding>,
    /// With [`JobOptions::finished_image`] and a target of one pass: the
    /// tiles' values go straight into the finished image and the film gets
    /// no sample (its pages are never touched, so the job's film, its
    /// snapshots and [`Finished::film`] stay empty). For a caller that only
    /// saves the image: adding into the film under the job's lock, and
    /// first writing its 5 MB at 512 x 512, made a `workbench render`
    /// measurably slower (`docs/PERFORMANCE.md`). Ignored when the job refines, renders several passes or
    /// observes them.
    pub image_only: bool,
}

/// See [`JobOptions::on_pass`].
pub type PassListener = Box<dyn Fn(u32, &Film) + Send + Sync>;

struct Progress {
    film: Film,
    views: Option<ViewFilm>,
    /// [`JobOptions::finished_image`]'s encoding and bytes, row-major RGB.
    finished: Option<(Encoding, Vec<u8>)>,
    stats: RenderStats,
    state: JobState,
}

/// What a job leaves when it stops ([`RenderJob::wait_with_image`]).
pub struct Finished {
    pub film: Film,
    /// The views, when the job measured them ([`JobOptions::views`]).
    pub views: Option<ViewFilm>,
    /// The finished image, when asked for ([`JobOptions::finished_image`])
    /// and the job rendered every pass of its target.
    pub image: Option<image::RgbImage>,
    pub stats: RenderStats,
    pub state: JobState,
}

struct Shared {
    cancel: AtomicBool,
    paused: Mutex<bool>,
    resumed: Condvar,
    progress: Mutex<Progress>,
    index: Mutex<Option<Arc<SceneIndex>>>,
    version: AtomicU64,
    on_progress: Option<Box<dyn Fn() + Send + Sync>>,
    on_pass: Option<PassListener>,
    views: bool,
    /// The finished image's encoding when [`JobOptions::image_only`]
    /// applies.
    image_only: Option<Encoding>,
    pause_after_tiles: Option<u64>,
    tiles_done: AtomicU64,
}

/// Locks a mutex, ignoring poisoning: render panics are caught and
/// reported as [`JobState::Failed`], and the data stays usable.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

impl Shared {
    fn progress(&self) -> MutexGuard<'_, Progress> {
        lock(&self.progress)
    }

    fn notify(&self) {
        self.version.fetch_add(1, Ordering::Relaxed);
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
        let mut paused = lock(&self.paused);
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
    worker: Option<JoinHandle<()>>,
}

impl RenderJob {
    /// Starts rendering `world` with `settings`. `index` is reused when it
    /// was built with the settings' acceleration (so several renders can
    /// share one); otherwise the job builds its own on its thread first.
    /// Bad settings or cameras are refused here, before any thread starts.
    pub fn start(
        world: Arc<World>,
        index: Option<Arc<SceneIndex>>,
        settings: RenderSettings,
        options: JobOptions,
    ) -> Result<RenderJob, RenderError> {
        settings.validate()?;
        crate::camera::Camera::for_render(&world.view, &settings)?;
        let (yield_to_viewer, idle) = (options.yield_to_viewer, options.idle_priority);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(options.threads.unwrap_or(0))
            .thread_name(|i| format!("render-{i}"))
            .start_handler(move |_| {
                if idle {
                    run_when_idle();
                } else if yield_to_viewer {
                    yield_to_interactive_threads();
                }
            })
            .build()
            .map_err(|e| RenderError::Threads(e.to_string()))?;
        let index = index.filter(|i| i.matches(settings.accel, settings.grid_multiplier));
        let image_only = options.finished_image.filter(|_| {
            options.image_only
                && settings.samples_per_pixel() == 1
                && !settings.keep_refining
                && options.on_pass.is_none()
        });
        let shared = Arc::new(Shared {
            cancel: AtomicBool::new(false),
            paused: Mutex::new(options.paused),
            resumed: Condvar::new(),
            progress: Mutex::new(Progress {
                film: if settings.adaptive().is_some() {
                    Film::with_error_estimate(settings.width, settings.height)
                } else {
                    Film::new(settings.width, settings.height)
                },
                views: options
                    .views
                    .then(|| ViewFilm::new(settings.width, settings.height)),
                finished: options.finished_image.map(|encoding| {
                    let bytes = settings.width as usize * settings.height as usize * 3;
                    (encoding, vec![0; bytes])
                }),
                stats: RenderStats {
                    width: settings.width,
                    height: settings.height,
                    passes_target: match settings.adaptive() {
                        Some(a) => adaptive::passes(a),
                        None => settings.samples_per_pixel(),
                    },
                    build_time: index.as_ref().map(|i| i.build_time()).unwrap_or_default(),
                    // Every pixel active, nothing known yet: a viewer lays
                    // its rows out once, from the start.
                    adaptive: settings.adaptive().map(|_| {
                        let pixels = u64::from(settings.width) * u64::from(settings.height);
                        AdaptiveStats {
                            pixels,
                            active_pixels: pixels,
                            error: f32::INFINITY,
                            ..AdaptiveStats::default()
                        }
                    }),
                    ..RenderStats::default()
                },
                state: if index.is_some() {
                    JobState::Rendering
                } else {
                    JobState::Building
                },
            }),
            index: Mutex::new(index.clone()),
            version: AtomicU64::new(0),
            on_progress: options.on_progress,
            on_pass: options.on_pass,
            views: options.views,
            image_only,
            pause_after_tiles: options.pause_after_tiles,
            tiles_done: AtomicU64::new(0),
        });
        let worker_shared = shared.clone();
        let worker = std::thread::Builder::new()
            .name("render-job".into())
            .spawn(move || {
                let shared = worker_shared;
                let outcome = catch_unwind(AssertUnwindSafe(|| {
                    // A job paused from its start builds nothing either.
                    shared.wait_while_paused();
                    if shared.cancelled() {
                        return Ok(());
                    }
                    // The film's pages are written while the structure
                    // builds, on the pool's other core (see `Film::prefault`).
                    let prefault = || {
                        let mut p = shared.progress();
                        if shared.image_only.is_none() {
                            p.film.prefault();
                        }
                        if let Some((_, bytes)) = &mut p.finished {
                            bytes.fill(0);
                        }
                    };
                    let index = match index {
                        Some(index) => {
                            prefault();
                            index
                        }
                        None => {
                            let (built, ()) = pool.join(
                                || {
                                    Arc::new(SceneIndex::build(
                                        &world.shapes,
                                        settings.accel,
                                        settings.grid_multiplier,
                                    ))
                                },
                                prefault,
                            );
                            *lock(&shared.index) = Some(built.clone());
                            let mut p = shared.progress();
                            p.stats.build_time = built.build_time();
                            p.state = JobState::Rendering;
                            drop(p);
                            shared.notify();
                            built
                        }
                    };
                    let frame = RenderPlan::new(world, index, settings)
                        .map_err(|e| format!("invalid camera: {e}"))?;
                    pool.install(|| run_passes(&frame, &shared));
                    Ok::<(), String>(())
                }));
                let state = match outcome {
                    Ok(Ok(())) if shared.cancelled() => JobState::Cancelled,
                    Ok(Ok(())) => JobState::Done,
                    Ok(Err(message)) => JobState::Failed(message),
                    Err(panic) => JobState::Failed(panic_message(&panic)),
                };
                shared.progress().state = state;
                shared.notify();
            })
            .map_err(|e| RenderError::Threads(e.to_string()))?;
        Ok(RenderJob {
            shared,
            worker: Some(worker),
        })
    }

    /// The acceleration structure this job traces against, once built.
    pub fn index(&self) -> Option<Arc<SceneIndex>> {
        lock(&self.shared.index).clone()
    }

    /// A number that grows whenever the job makes progress (a tile, a pass,
    /// a state change): a viewer refreshes its image when it changes.
    pub fn version(&self) -> u64 {
        self.shared.version.load(Ordering::Relaxed)
    }

    /// Asks the job to stop; render threads finish the tile they are on.
    pub fn cancel(&self) {
        self.shared.cancel.store(true, Ordering::Relaxed);
        self.set_paused(false);
    }

    /// Pauses or resumes the render between tiles.
    pub fn set_paused(&self, paused: bool) {
        *lock(&self.shared.paused) = paused;
        self.shared.resumed.notify_all();
    }

    pub fn is_paused(&self) -> bool {
        *lock(&self.shared.paused)
    }

    /// True once the job has stopped (done, cancelled or failed).
    pub fn is_finished(&self) -> bool {
        !matches!(
            self.shared.progress().state,
            JobState::Rendering | JobState::Building
        )
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

    /// The pixels an adaptive render still refines, row-major, as decided
    /// after the last pass (every pixel before the first ends, none once
    /// done); `None` for uniform sampling.
    pub fn active_pixels(&self) -> Option<Vec<bool>> {
        self.shared
            .progress()
            .film
            .active_pixels()
            .map(<[bool]>::to_vec)
    }

    /// The film as it stands, as linear floats (see
    /// [`Film::to_linear_image`]), for saving HDR output mid-render.
    pub fn linear_image(&self) -> image::Rgb32FImage {
        self.shared.progress().film.to_linear_image()
    }

    /// The image under `view` as it stands (the shaded image for
    /// [`View::Shaded`] or a job without views), with its statistics.
    pub fn view_snapshot(&self, view: View, heat: &ViewHeatmap, encoding: Encoding) -> Snapshot {
        let paused = self.is_paused();
        let p = self.shared.progress();
        Snapshot {
            width: p.film.width(),
            height: p.film.height(),
            rgba: view_rgba8(&p.film, p.views.as_ref(), view, heat, encoding),
            stats: p.stats.clone(),
            state: p.state.clone(),
            paused,
        }
    }

    /// The values of scalar view `view` so far (see [`ViewFilm::values`]);
    /// `None` unless the job measures views.
    pub fn view_values(&self, view: View) -> Option<Vec<Option<f32>>> {
        self.shared
            .progress()
            .views
            .as_ref()
            .map(|v| v.values(view))
    }

    /// The value of scalar view `view` at pixel `(x, y)` so far; `None`
    /// without a value (or views).
    pub fn view_value(&self, view: View, x: u32, y: u32) -> Option<f32> {
        self.shared.progress().views.as_ref()?.value(view, x, y)
    }

    /// The views measured so far (a copy); `None` unless the job was
    /// started with [`JobOptions::views`].
    pub fn view_film(&self) -> Option<ViewFilm> {
        self.shared.progress().views.clone()
    }

    /// Waits for the job to stop and returns its film and statistics.
    pub fn wait(self) -> (Film, RenderStats, JobState) {
        let (film, _, stats, state) = self.wait_with_views();
        (film, stats, state)
    }

    /// [`RenderJob::wait`], with the views when the job measured them.
    pub fn wait_with_views(self) -> (Film, Option<ViewFilm>, RenderStats, JobState) {
        let done = self.wait_with_image();
        (done.film, done.views, done.stats, done.state)
    }

    /// Waits for the job to stop and returns all it made.
    pub fn wait_with_image(mut self) -> Finished {
        if let Some(worker) = self.worker.take() {
            // The worker catches render panics itself; a join error could
            // only come from the bookkeeping around it.
            let _ = worker.join();
        }
        let mut p = self.shared.progress();
        let complete = p.state == JobState::Done && p.stats.passes_done >= p.stats.passes_target;
        let (width, height) = (p.film.width(), p.film.height());
        let image = p
            .finished
            .take()
            .filter(|_| complete)
            .and_then(|(_, bytes)| image::RgbImage::from_raw(width, height, bytes));
        Finished {
            film: std::mem::replace(&mut p.film, Film::new(0, 0)),
            views: p.views.take(),
            image,
            stats: p.stats.clone(),
            state: p.state.clone(),
        }
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

/// Runs passes until the target (or forever when refining) or cancellation;
/// an adaptive render also ends once no pixel is active or its budget is
/// spent.
fn run_passes(frame: &RenderPlan, shared: &Shared) {
    let target = frame.passes_target();
    let adaptive = frame.settings.adaptive().copied();
    let refine = frame.settings.keep_refining && adaptive.is_none();
    let time_budget = match adaptive.and_then(|a| a.budget) {
        Some(Budget::Time(limit)) => Some(limit),
        _ => None,
    };
    // A sample budget's last pass is under way (or done).
    let mut samples_spent = false;
    let mut rendered = Duration::ZERO;
    let mut refinement = adaptive::Refinement::default();
    for pass in 0.. {
        // An adaptive render runs until no pixel is active: a pixel a
        // neighbour brings back is a pass behind the schedule.
        if shared.cancelled() || (pass >= target && !refine && adaptive.is_none()) {
            return;
        }
        let start = Instant::now();
        let rays_before = shared.progress().stats.counters.total_rays();
        frame.tiles.par_iter().for_each(|tile| {
            shared.wait_while_paused();
            if shared.cancelled() {
                return;
            }
            // A time budget spent starts no tile, after the first pass.
            if pass > 0 && time_budget.is_some_and(|limit| rendered + start.elapsed() >= limit) {
                return;
            }
            let mut counters = Counters::default();
            let rendered_tile = match &adaptive {
                Some(a) => {
                    let plan = adaptive::plan(&shared.progress().film, tile, a);
                    if plan.iter().all(|samples| samples.is_empty()) {
                        return;
                    }
                    let PlannedSamples {
                        values,
                        tests,
                        views,
                    } = frame.render_samples(tile, &plan, shared.views, &mut counters);
                    let counts = plan.iter().map(|samples| samples.len() as u32).collect();
                    TileSamples::Some {
                        counts,
                        values,
                        tests,
                        views,
                    }
                }
                None if shared.views => {
                    let (values, views) = frame.render_tile_with_views(pass, tile, &mut counters);
                    TileSamples::One(values, Some(views))
                }
                None => TileSamples::One(frame.render_tile(pass, tile, &mut counters), None),
            };
            // Left out of the film, a tile's bytes are made before taking
            // the lock: only their copy waits for the other threads.
            let tile_bytes = match (&rendered_tile, shared.image_only) {
                (TileSamples::One(values, _), Some(encoding)) => {
                    Some(encode_values(values, encoding))
                }
                _ => None,
            };
            {
                let mut p = shared.progress();
                let p = &mut *p;
                match (&tile_bytes, &mut p.finished) {
                    (Some(tile_bytes), Some((_, image))) => {
                        tile.copy_rgb_into(frame.settings.width, tile_bytes, image);
                    }
                    _ => {
                        let last = match (&rendered_tile, &adaptive) {
                            // Whether a neighbour's noise brings the tile
                            // back is decided after the pass: its bytes
                            // are made each time it takes samples.
                            (
                                TileSamples::Some {
                                    counts,
                                    values,
                                    tests,
                                    ..
                                },
                                Some(_),
                            ) => {
                                p.film.add_samples(tile, counts, values, tests);
                                true
                            }
                            (TileSamples::One(values, _), _) => {
                                p.film.add_tile(tile, values);
                                pass + 1 == target && !refine
                            }
                            (TileSamples::Some { .. }, None) => {
                                unreachable!("only adaptive passes plan samples")
                            }
                        };
                        if let (true, Some((encoding, bytes))) = (last, &mut p.finished) {
                            p.film.resolve_tile(tile, *encoding, bytes);
                        }
                    }
                }
                if let Some(film) = &mut p.views {
                    match &rendered_tile {
                        TileSamples::One(_, Some(views)) => film.add_tile(tile, views),
                        TileSamples::Some {
                            counts,
                            views: Some(views),
                            ..
                        } => film.add_samples(tile, counts, views),
                        _ => {}
                    }
                }
                p.stats.counters += counters;
                p.stats.render_time = rendered + start.elapsed();
            }
            let tiles = shared.tiles_done.fetch_add(1, Ordering::Relaxed) + 1;
            if shared.pause_after_tiles == Some(tiles) {
                *lock(&shared.paused) = true;
            }
            shared.notify();
        });
        if shared.cancelled() {
            return;
        }
        let converged = {
            let mut p = shared.progress();
            let out_of_budget = samples_spent
                || time_budget.is_some_and(|limit| rendered + start.elapsed() >= limit);
            let converged = adaptive.map(|a| {
                let mut active = refinement.decide(&p.film, &a);
                if let (Some(Budget::Samples(total)), false) = (a.budget, out_of_budget) {
                    (active, samples_spent) = adaptive::within_budget(&p.film, active, &a, total);
                }
                p.film.set_active(active);
                let summary = adaptive::summary(&p.film);
                p.stats.adaptive = Some(summary);
                // Ended by its budget, a render leaves its pixels still
                // above the threshold active: a viewer shows where the
                // budget ran out.
                summary.active_pixels == 0 || out_of_budget
            });
            // A pass's time takes in the decision after it: the next pass
            // waits for it, and so does whoever waits for the image.
            let elapsed = start.elapsed();
            rendered += elapsed;
            p.stats.passes_done = pass + 1;
            p.stats.pass_times.push(elapsed);
            let rays = p.stats.counters.total_rays() - rays_before;
            p.stats.pass_rays.push(rays);
            p.stats.render_time = rendered;
            match converged {
                // Done before the most passes it might have taken.
                Some(true) => p.stats.passes_target = pass + 1,
                // Behind the schedule: at least one more.
                Some(false) => p.stats.passes_target = p.stats.passes_target.max(pass + 2),
                None => {}
            }
            if let Some(observe) = &shared.on_pass {
                observe(pass + 1, &p.film);
            }
            converged == Some(true)
        };
        shared.notify();
        if converged {
            return;
        }
    }
}

/// What a render thread made of a tile in a pass.
enum TileSamples {
    /// One sample per pixel (uniform passes), and its view samples.
    One(Vec<Vec3A>, Option<Vec<ViewSample>>),
    /// Adaptive passes: `counts[i]` samples of pixel `i`, pixel after
    /// pixel in `values` (and `views`).
    Some {
        counts: Vec<u32>,
        values: Vec<Vec3A>,
        /// Each pixel's intersection tests.
        tests: Vec<u64>,
        views: Option<Vec<ViewSample>>,
    },
}

/// Marks the calling render thread as batch work. The lowest priority
/// (nice 19) made a viewer's render several times slower than a headless one
/// as soon as anything else ran on the machine (the software rasterizer
/// painting the window, other processes); `SCHED_BATCH` at the usual nice
/// value keeps the thread's share of the cores and only gives way to
/// threads that wake up, such as the UI's. Best effort: a viewer works
/// either way, only less smoothly if the OS refuses.
fn yield_to_interactive_threads() {
    #[cfg(target_os = "linux")]
    {
        use thread_priority::unix::{
            NormalThreadSchedulePolicy, ThreadSchedulePolicy, set_thread_priority_and_policy,
            thread_native_id,
        };
        use thread_priority::{ThreadPriority, ThreadPriorityValue};
        // The crate maps its 0..=99 scale onto nice 19..=-20: 47 is nice 0,
        // the value every thread starts with.
        if let Ok(usual) = ThreadPriorityValue::try_from(47u8) {
            let _ = set_thread_priority_and_policy(
                thread_native_id(),
                ThreadPriority::Crossplatform(usual),
                ThreadSchedulePolicy::Normal(NormalThreadSchedulePolicy::Batch),
            );
        }
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Min);
    }
}

/// The calling render thread runs only when the cores have nothing else
/// to do (see [`JobOptions::idle_priority`]).
fn run_when_idle() {
    #[cfg(target_os = "linux")]
    {
        use thread_priority::unix::{
            NormalThreadSchedulePolicy, ThreadSchedulePolicy, set_thread_priority_and_policy,
            thread_native_id,
        };
        // SCHED_IDLE takes no priority but the minimum (a crossplatform
        // value is refused as out of its 0..=0 range).
        let _ = set_thread_priority_and_policy(
            thread_native_id(),
            thread_priority::ThreadPriority::Min,
            ThreadSchedulePolicy::Normal(NormalThreadSchedulePolicy::Idle),
        );
    }
    #[cfg(not(target_os = "linux"))]
    {
        let _ = thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Min);
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
