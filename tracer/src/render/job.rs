//! A progressive render running in the background: passes over tiles on a
//! thread pool, cancellable at any moment, observable at any time.

use std::future::Future;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::pin::Pin;
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::task::{Context, Poll};

use crate::accel::SceneIndex;
use crate::camera::CameraError;
use crate::stats::RenderStats;
use crate::world::World;

use super::adaptive::Adaptive;
use super::control::{Control, ProgressListener, lock, lock_spinning};
use super::driver::{Clock, FailureSlot, Host, Hosted, JobPool, Priority, SystemClock, WorkingFor};
use super::outputs::{Outputs, Recording};
use super::passes::{LoopContext, PassListener};
use super::settings::SettingsError;
use super::strategy::{SamplingStrategy, Uniform};
use super::view::{View, ViewFilm, ViewHeatmap, view_rgba8};
use super::{Encoding, Film, RenderPlan, RenderSettings, driver, passes, slices};

/// Why a render could not start.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The settings break a rule of [`RenderSettings::validate`](super::RenderSettings::validate).
    #[error("invalid settings: {0}")]
    Settings(#[from] SettingsError),
    /// The camera cannot form an image.
    #[error("invalid camera: {0}")]
    Camera(#[from] CameraError),
    /// The operating system refused the worker threads.
    #[error("could not start render threads: {0}")]
    Threads(String),
    #[error("{0}")]
    /// The render failed while running (a worker panicked); the message says why.
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
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Row-major RGBA8; pixels without a sample yet are transparent.
    pub rgba: Vec<u8>,
    /// The statistics so far.
    pub stats: RenderStats,
    /// Building, rendering, done, cancelled or failed.
    pub state: JobState,
    /// The job is paused: the image will not change until it resumes.
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
    pub on_progress: Option<ProgressListener>,
    /// Called after each completed pass, before the next begins (see
    /// [`PassListener`]): to record convergence.
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
    /// The pool the job renders on, made once for many jobs; `None`: a
    /// pool of its own, of `threads` threads at the priority above.
    /// Unused with [`Host::Global`], which renders on rayon's global pool,
    /// and [`Host::Slices`], on the calling thread.
    pub pool: Option<Arc<rayon::ThreadPool>>,
    /// The clock its passes and time budget read; `None`: the system's.
    pub clock: Option<Arc<dyn Clock>>,
    /// Where the job's loop runs.
    pub host: Host,
    /// Shown live to a viewer (a window's side): the job waits between
    /// tiles while the viewers are hidden
    /// ([`set_viewers_hidden`](super::driver::set_viewers_hidden)), as a
    /// web page's hidden tab. A job that measures is not viewed, so
    /// hiding never stretches its times.
    pub viewed: bool,
}

impl JobOptions {
    /// The priority its own pool's threads take.
    fn priority(&self) -> Priority {
        if self.idle_priority {
            Priority::Idle
        } else if self.yield_to_viewer {
            Priority::YieldToViewer
        } else {
            Priority::Normal
        }
    }

    /// What the job records for `settings`: the finished image alone only
    /// when it is one pass that nobody observes.
    fn recording(&self, settings: &RenderSettings) -> Recording {
        Recording {
            views: self.views,
            finished_image: self.finished_image,
            image_only: self.finished_image.is_some()
                && self.image_only
                && settings.samples_per_pixel() == 1
                && !settings.keep_refining
                && self.on_pass.is_none(),
        }
    }
}

/// What a job leaves when it stops ([`RenderJob::wait_with_image`]).
pub struct Finished {
    /// The accumulated samples, at full precision.
    pub film: Film,
    /// The views, when the job measured them ([`JobOptions::views`]).
    pub views: Option<ViewFilm>,
    /// The finished image, when asked for ([`JobOptions::finished_image`])
    /// and the job rendered every pass of its target.
    pub image: Option<image::RgbImage>,
    /// The statistics of the whole render.
    pub stats: RenderStats,
    /// How the job ended: done, cancelled or failed.
    pub state: JobState,
}

struct Shared {
    control: Control,
    outputs: Mutex<Outputs>,
    /// Where the job stands; a failure written to `failure` overrides it.
    state: Mutex<JobState>,
    /// Signalled when the job stops, for a job hosted on its pool.
    stopped: Condvar,
    failure: FailureSlot,
    index: Mutex<Option<Arc<SceneIndex>>>,
    recording: Recording,
    on_pass: Option<PassListener>,
    clock: Arc<dyn Clock>,
}

impl Shared {
    fn set_state(&self, state: JobState) {
        *lock(&self.state) = state;
        self.stopped.notify_all();
        self.control.notify();
    }

    /// The job's state as a viewer sees it, without waiting.
    fn state(&self) -> JobState {
        match self.failure.get() {
            Some(message) => JobState::Failed(message.clone()),
            None => lock_spinning(&self.state).clone(),
        }
    }

    fn is_stopped(&self) -> bool {
        !matches!(self.state(), JobState::Rendering | JobState::Building)
    }
}

/// A background render. Dropping it cancels it (and, hosted on a thread,
/// waits for that thread).
///
/// Its viewer calls (snapshots, statistics, state, pause) never wait for
/// a render thread and never start parallel work on the caller's thread:
/// a web page calls them from its main thread, where waiting is refused.
pub struct RenderJob {
    shared: Arc<Shared>,
    /// Where its loop went; `None` once waited for.
    hosted: Option<Hosted>,
}

impl RenderJob {
    /// Starts rendering `world` with `settings`, sampled as they say
    /// (uniform N x N or adaptive). `index` is reused when it was built
    /// with the settings' acceleration (so several renders can share one);
    /// otherwise the job builds its own first. Bad settings or cameras are
    /// refused here, before any thread starts.
    pub fn start(
        world: Arc<World>,
        index: Option<Arc<SceneIndex>>,
        settings: RenderSettings,
        options: JobOptions,
    ) -> Result<RenderJob, RenderError> {
        let strategy = strategy_for(&settings);
        Self::start_with(world, index, settings, strategy, options)
    }

    /// [`RenderJob::start`] with a sampling strategy of the caller's:
    /// the settings still give the camera, the tiles and each sample's
    /// random numbers.
    pub fn start_with(
        world: Arc<World>,
        index: Option<Arc<SceneIndex>>,
        settings: RenderSettings,
        strategy: Box<dyn SamplingStrategy>,
        options: JobOptions,
    ) -> Result<RenderJob, RenderError> {
        settings.validate()?;
        settings.render_camera(&world.view)?;
        let pool = match (options.host, &options.pool) {
            // Slices render their tiles on the calling thread; what little
            // else is parallel (the structure's build) asks the global pool,
            // which without threads is rayon's fallback onto that thread.
            (Host::Global | Host::Slices, _) => JobPool::Global,
            (_, Some(pool)) => JobPool::Own(pool.clone()),
            (_, None) => JobPool::Own(driver::render_pool(options.threads, options.priority())?),
        };
        let index = index.filter(|i| i.matches(settings.accel, settings.grid_multiplier));
        let recording = options.recording(&settings);
        let mut outputs = Outputs::new(&settings, &*strategy, recording);
        outputs.stats.build_time = index.as_ref().map(|i| i.build_time()).unwrap_or_default();
        let state = match index {
            Some(_) => JobState::Rendering,
            None => JobState::Building,
        };
        let shared = Arc::new(Shared {
            control: Control::new(
                options.paused,
                options.pause_after_tiles,
                options.on_progress,
                options.viewed,
            ),
            outputs: Mutex::new(outputs),
            state: Mutex::new(state),
            stopped: Condvar::new(),
            failure: FailureSlot::default(),
            index: Mutex::new(index.clone()),
            recording,
            on_pass: options.on_pass,
            clock: options
                .clock
                .unwrap_or_else(|| Arc::new(SystemClock::default())),
        });
        let job = Job {
            shared: shared.clone(),
            world,
            index,
            settings,
            strategy,
            pool: pool.clone(),
            sliced: options.host == Host::Slices,
        };
        let hosted = driver::host(options.host, &pool, job.run())?;
        Ok(RenderJob {
            shared,
            hosted: Some(hosted),
        })
    }

    /// The acceleration structure this job traces against, once built.
    pub fn index(&self) -> Option<Arc<SceneIndex>> {
        lock_spinning(&self.shared.index).clone()
    }

    /// A number that grows whenever the job makes progress (a tile, a pass,
    /// a state change): a viewer refreshes its image when it changes.
    pub fn version(&self) -> u64 {
        self.shared.control.version()
    }

    /// Asks the job to stop; render threads finish the tile they are on.
    pub fn cancel(&self) {
        self.shared.control.cancel();
    }

    /// Pauses or resumes the render between tiles.
    pub fn set_paused(&self, paused: bool) {
        self.shared.control.set_paused(paused);
    }

    /// Whether the job is paused now.
    pub fn is_paused(&self) -> bool {
        self.shared.control.is_paused()
    }

    /// True once the job has stopped (done, cancelled or failed).
    pub fn is_finished(&self) -> bool {
        self.shared.is_stopped()
    }

    /// Where the job stands now; never blocks on the workers.
    pub fn state(&self) -> JobState {
        self.shared.state()
    }

    /// The statistics so far.
    pub fn stats(&self) -> RenderStats {
        self.outputs().stats.clone()
    }

    fn outputs(&self) -> std::sync::MutexGuard<'_, Outputs> {
        lock_spinning(&self.shared.outputs)
    }

    /// The current image, resolved with `encoding`, and its statistics.
    pub fn snapshot(&self, encoding: Encoding) -> Snapshot {
        let (paused, state) = (self.is_paused(), self.state());
        let outputs = self.outputs();
        Snapshot {
            width: outputs.film.width(),
            height: outputs.film.height(),
            rgba: outputs.film.to_rgba8(encoding),
            stats: outputs.stats.clone(),
            state,
            paused,
        }
    }

    /// The pixels an adaptive render still refines, row-major, as decided
    /// after the last pass (every pixel before the first ends, none once
    /// done); `None` for uniform sampling.
    pub fn active_pixels(&self) -> Option<Vec<bool>> {
        self.outputs().film.active_pixels().map(<[bool]>::to_vec)
    }

    /// The film as it stands, as linear floats (see
    /// [`Film::to_linear_image`]), for saving HDR output mid-render.
    pub fn linear_image(&self) -> image::Rgb32FImage {
        self.outputs().film.to_linear_image()
    }

    /// The image under `view` as it stands (the shaded image for
    /// [`View::Shaded`] or a job without views), with its statistics.
    pub fn view_snapshot(&self, view: View, heat: &ViewHeatmap, encoding: Encoding) -> Snapshot {
        let (paused, state) = (self.is_paused(), self.state());
        let outputs = self.outputs();
        Snapshot {
            width: outputs.film.width(),
            height: outputs.film.height(),
            rgba: view_rgba8(&outputs.film, outputs.views.as_ref(), view, heat, encoding),
            stats: outputs.stats.clone(),
            state,
            paused,
        }
    }

    /// The values of scalar view `view` so far (see [`ViewFilm::values`]);
    /// `None` unless the job measures views.
    pub fn view_values(&self, view: View) -> Option<Vec<Option<f32>>> {
        self.outputs().views.as_ref().map(|v| v.values(view))
    }

    /// The value of scalar view `view` at pixel `(x, y)` so far; `None`
    /// without a value (or views).
    pub fn view_value(&self, view: View, x: u32, y: u32) -> Option<f32> {
        self.outputs().views.as_ref()?.value(view, x, y)
    }

    /// The views measured so far (a copy); `None` unless the job was
    /// started with [`JobOptions::views`].
    pub fn view_film(&self) -> Option<ViewFilm> {
        self.outputs().views.clone()
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

    /// Waits for the job to stop and returns all it made. Not for a web
    /// page's main thread, which may not wait.
    pub fn wait_with_image(mut self) -> Finished {
        match self.hosted.take() {
            // The worker catches render panics itself; a join error could
            // only come from the bookkeeping around it.
            Some(Hosted::Thread(worker)) => drop(worker.join()),
            Some(Hosted::Slices(id)) => slices::finish(id),
            Some(Hosted::Task) | None => {
                let mut state = lock(&self.shared.state);
                while matches!(*state, JobState::Rendering | JobState::Building) {
                    state = self
                        .shared
                        .stopped
                        .wait(state)
                        .unwrap_or_else(PoisonError::into_inner);
                }
            }
        }
        let state = self.shared.state();
        let mut outputs = lock(&self.shared.outputs);
        let stats = outputs.stats.clone();
        let complete = state == JobState::Done && stats.passes_done >= stats.passes_target;
        let (width, height) = (outputs.film.width(), outputs.film.height());
        let image = outputs
            .finished
            .take()
            .filter(|_| complete)
            .and_then(|(_, bytes)| image::RgbImage::from_raw(width, height, bytes));
        Finished {
            film: std::mem::replace(&mut outputs.film, Film::new(0, 0)),
            views: outputs.views.take(),
            image,
            stats,
            state,
        }
    }
}

impl Drop for RenderJob {
    fn drop(&mut self) {
        self.cancel();
        match self.hosted.take() {
            Some(Hosted::Thread(worker)) => drop(worker.join()),
            Some(Hosted::Slices(id)) => slices::forget(id),
            Some(Hosted::Task) | None => {}
        }
    }
}

/// What a job's loop owns while it runs.
struct Job {
    shared: Arc<Shared>,
    world: Arc<World>,
    index: Option<Arc<SceneIndex>>,
    settings: RenderSettings,
    strategy: Box<dyn SamplingStrategy>,
    pool: JobPool,
    /// Hosted in time slices ([`Host::Slices`]).
    sliced: bool,
}

impl Job {
    /// The job's loop, to be run where its host says: builds what is
    /// missing, runs the passes and says how the job ended. Each step of
    /// it reports a panic to the job ([`Reported`]).
    fn run(self) -> impl Future<Output = ()> + Send + 'static {
        Reported {
            shared: self.shared.clone(),
            work: Box::pin(self.render()),
        }
    }

    async fn render(mut self) -> Result<(), String> {
        // A job paused from its start builds nothing either.
        let control = &self.shared.control;
        let proceed = match self.sliced {
            true => passes::proceed_in_slices(control).await,
            false => control.proceed(),
        };
        if !proceed {
            return Ok(());
        }
        let index = self.index()?;
        let shared = &*self.shared;
        let plan = RenderPlan::new(self.world.clone(), index, self.settings.clone())
            .map_err(|e| format!("invalid camera: {e}"))?;
        let cx = LoopContext {
            control: &shared.control,
            outputs: &shared.outputs,
            recording: shared.recording,
            clock: &*shared.clock,
            failure: &shared.failure,
            on_pass: shared.on_pass.as_ref(),
            sliced: self.sliced,
        };
        let strategy = &mut *self.strategy;
        match self.sliced {
            true => passes::run(&plan, strategy, &cx).await,
            false => self
                .pool
                .install(|| slices::block_on(passes::run(&plan, strategy, &cx))),
        }
    }

    /// The job's index: the one it was given, or one built now, while
    /// the pool's other thread writes the outputs' pages.
    fn index(&mut self) -> Result<Arc<SceneIndex>, String> {
        let shared = &*self.shared;
        let prefault = || lock(&shared.outputs).prefault(shared.recording);
        if let Some(index) = self.index.take() {
            prefault();
            return Ok(index);
        }
        let (world, settings) = (&self.world, &self.settings);
        let (built, ()) = self.pool.join(
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
        lock(&shared.outputs).stats.build_time = built.build_time();
        *lock(&shared.state) = JobState::Rendering;
        shared.control.notify();
        Ok(built)
    }
}

/// A job's loop whose every step reports to the job: a panic is read
/// from the failure slot its hook wrote (caught here too where panics
/// unwind, so the thread ends cleanly), and the end sets the job's state.
struct Reported {
    shared: Arc<Shared>,
    work: Pin<Box<dyn Future<Output = Result<(), String>> + Send>>,
}

impl Future for Reported {
    type Output = ();

    fn poll(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<()> {
        let shared = self.shared.clone();
        let _working = WorkingFor::job(&shared.failure);
        let outcome = catch_unwind(AssertUnwindSafe(|| self.work.as_mut().poll(cx)));
        let state = match outcome {
            Ok(Poll::Pending) => return Poll::Pending,
            Ok(Poll::Ready(Ok(()))) if shared.control.cancelled() => JobState::Cancelled,
            Ok(Poll::Ready(Ok(()))) => JobState::Done,
            Ok(Poll::Ready(Err(message))) => JobState::Failed(message),
            Err(panic) => JobState::Failed(
                shared
                    .failure
                    .get()
                    .cloned()
                    .unwrap_or_else(|| driver::panic_message(&*panic)),
            ),
        };
        shared.set_state(state);
        Poll::Ready(())
    }
}

/// The strategy `settings` ask for: adaptive sampling when it is in force,
/// else uniform N x N.
fn strategy_for(settings: &RenderSettings) -> Box<dyn SamplingStrategy> {
    match settings.adaptive() {
        Some(adaptive) => Box::new(Adaptive::new(*adaptive)),
        None => Box::new(Uniform::new(settings)),
    }
}
