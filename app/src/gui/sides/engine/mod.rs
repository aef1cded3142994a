//! The window's bridge to the tracer: it owns the scene being shown and the
//! render job, restarts only what a settings change requires, and loads
//! scenes off the UI thread. Settings go in; images and statistics come out.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use tracer::accel::SceneIndex;
use tracer::render::driver::Priority;
use tracer::render::{JobOptions, JobState, RenderJob, RenderSettings};
use tracer::world::ShapeChange;

use crate::load::{Loaded, SceneSource};

use crate::gui::platform::cpu_clock::count_render_thread_cpu;
use crate::gui::platform::target;

use loader::SceneLoad;

/// Wakes the UI from a render thread.
pub type Wake = Arc<dyn Fn() + Send + Sync>;

/// Identifies what an engine shows: (jobs started, the job's own version).
pub type Version = (u64, u64);

/// What the engine is doing, for the overlay line.
#[derive(Debug, Clone, PartialEq)]
pub enum Activity {
    /// No scene yet.
    Idle,
    /// A scene is being read and prepared; `fraction` of a mesh file read
    /// so far, when the file is large enough to report it.
    Loading { name: String, fraction: Option<f32> },
    /// The render job's state.
    Job(JobState),
}

/// Owns the current scene and its render job.
pub struct Engine {
    scene: Option<Loaded>,
    job: Option<RenderJob>,
    /// Settings of the current job, to decide what a change restarts.
    settings: Option<RenderSettings>,
    /// The last acceleration structure built, reused while its kind and
    /// multiplier stay the same.
    index: Option<Arc<SceneIndex>>,
    /// Cancelled jobs still finishing their last tiles; dropped once done
    /// so the UI thread never waits for them.
    retired: Vec<RenderJob>,
    loading: Option<SceneLoad>,
    /// Called by render threads to wake the UI, at its own pace.
    wake: Wake,
    /// Called once the last pass is in, to show it at once.
    wake_now: Wake,
    /// The current job rendered its last pass (set by a render thread).
    complete: Arc<AtomicBool>,
    paused: bool,
    /// Jobs pause themselves once this many tiles are in.
    pause_after_tiles: Option<u64>,
    /// Jobs render only in the time the other engines leave.
    idle_priority: bool,
    /// The render threads every job of this engine runs on, made with its
    /// first job at the engine's priority, instead of a pool per job.
    pool: Option<Arc<rayon::ThreadPool>>,
    /// Whether the current job's failure was handed out already.
    failure_taken: bool,
    /// Jobs started so far: part of [`Engine::version`], as every job
    /// counts its own versions from zero.
    jobs_started: u64,
    /// Jobs measure the views (a view other than the shaded image is on).
    views: bool,
    /// `views` changed since the current job started.
    views_changed: bool,
    /// New settings wait for the current job's structure to be built (see
    /// [`Engine::render`]): its first report then wakes the window at once.
    restart_waiting: Arc<AtomicBool>,
}

impl Engine {
    /// An engine that calls `wake` whenever there is something new to show.
    #[cfg(test)]
    pub(crate) fn new(wake: Wake) -> Self {
        Self::with_wakes(wake.clone(), wake)
    }

    /// An engine that calls `wake` when a render progresses (the UI paces
    /// its redraws) and `wake_now` when its last pass is in, which the UI
    /// should show at once.
    pub(crate) fn with_wakes(wake: Wake, wake_now: Wake) -> Self {
        Self {
            scene: None,
            job: None,
            settings: None,
            index: None,
            retired: Vec::new(),
            loading: None,
            wake,
            wake_now,
            complete: Arc::new(AtomicBool::new(false)),
            paused: false,
            pause_after_tiles: None,
            idle_priority: false,
            pool: None,
            failure_taken: false,
            jobs_started: 0,
            views: false,
            views_changed: false,
            restart_waiting: Arc::new(AtomicBool::new(false)),
        }
    }

    /// Starts reading `source` on a background thread; the current scene
    /// keeps rendering until the new one is ready.
    pub(crate) fn load(&mut self, source: SceneSource) {
        self.loading = Some(SceneLoad::start(source, self.wake.clone()));
    }

    /// Takes a finished load, if any: `Some(Ok(scene))`, now the current
    /// scene, or `Some(Err(message))` when it failed.
    pub(crate) fn poll_load(&mut self) -> Option<Result<&Loaded, String>> {
        let result = self.loading.as_ref()?.poll()?;
        self.loading = None;
        match result {
            Ok(scene) => {
                self.show(scene);
                self.scene.as_ref().map(Ok)
            }
            Err(message) => Some(Err(message)),
        }
    }

    /// Makes `scene` the current scene (loaded elsewhere, e.g. by the
    /// other side of a comparison); nothing renders until asked.
    pub(crate) fn show(&mut self, scene: Loaded) {
        self.retire_job();
        self.index = None;
        self.settings = None;
        self.scene = Some(scene);
    }

    /// Makes `scene`, an edit of the current one, the current scene, and
    /// renders again, with the structure over the old shapes where it can
    /// serve: as it is when the edit left the shapes as they were (a
    /// material, a light, the camera), refitted around the shapes `shapes`
    /// says moved in place ([`SceneIndex::refit`]: no Building phase; on
    /// this thread, as a refit costs a fraction of a build), and built anew by
    /// the next job when the refit refuses or the shapes were renumbered.
    pub(crate) fn edit_scene(&mut self, scene: Loaded, shapes: ShapeChange) {
        let index = self.index();
        let index = match shapes {
            ShapeChange::None => index,
            ShapeChange::InPlace(moved) => index
                .and_then(|index| index.refit(&scene.world.shapes, moved))
                .map(Arc::new),
            ShapeChange::Renumbered => None,
        };
        self.show(scene);
        self.index = index;
    }

    /// The scene was saved as `path`: it is that file's now, with nothing
    /// rendered anew. Its skybox name stays relative to the folder it came
    /// from, which is where the next save finds it.
    pub(crate) fn saved_as(&mut self, path: &std::path::Path) {
        if let Some(loaded) = &mut self.scene {
            loaded.source = SceneSource::File(path.to_path_buf());
        }
    }

    pub fn scene(&self) -> Option<&Loaded> {
        self.scene.as_ref()
    }

    pub fn is_loading(&self) -> bool {
        self.loading.is_some()
    }

    /// Renders the current scene with `settings`, restarting the job only
    /// when they differ from the running job's, and not before the running
    /// job has built the acceleration structure they need too: restarting
    /// during the build would start a second build beside it (a camera drag
    /// right after opening a 262k-triangle mesh started one per frame, and
    /// the memory grew by gigabytes). Call again once the build reports;
    /// the window does on every frame.
    pub(crate) fn render(&mut self, settings: &RenderSettings) -> Result<(), String> {
        if self.settings.as_ref() == Some(settings) && self.job.is_some() && !self.views_changed {
            self.restart_waiting.store(false, Ordering::Relaxed);
            return Ok(());
        }
        if self.is_building_for(settings) {
            self.restart_waiting.store(true, Ordering::Relaxed);
            return Ok(());
        }
        self.restart(settings)
    }

    /// Whether the current job is still building the structure `settings`
    /// would use.
    fn is_building_for(&self, settings: &RenderSettings) -> bool {
        let (Some(job), Some(current)) = (&self.job, &self.settings) else {
            return false;
        };
        let structure = |s: &RenderSettings| s.accel.structure_key(s.grid_multiplier);
        job.state() == JobState::Building && structure(current) == structure(settings)
    }

    /// Starts a new job with `settings` whatever runs now.
    pub(crate) fn restart(&mut self, settings: &RenderSettings) -> Result<(), String> {
        let Some(world) = self.scene.as_ref().map(|s| s.world.clone()) else {
            return Ok(());
        };
        if let Some(job) = &self.job
            && let Some(index) = job.index()
        {
            self.index = Some(index);
        }
        self.retire_job();
        let (wake, wake_now) = (self.wake.clone(), self.wake_now.clone());
        let complete = Arc::new(AtomicBool::new(false));
        let (last_pass_in, done) = (complete.clone(), complete.clone());
        self.restart_waiting.store(false, Ordering::Relaxed);
        let waiting = self.restart_waiting.clone();
        let pool = self.render_pool()?;
        let job = RenderJob::start(
            world,
            self.index.clone(),
            settings.clone(),
            JobOptions {
                pool,
                on_progress: Some(Box::new(move || {
                    count_render_thread_cpu();
                    if done.load(Ordering::Relaxed) || waiting.load(Ordering::Relaxed) {
                        wake_now();
                    } else {
                        wake();
                    }
                })),
                on_pass: Some(Box::new(move |_, _, last| {
                    if last {
                        last_pass_in.store(true, Ordering::Relaxed);
                    }
                })),
                views: self.views,
                paused: self.paused,
                pause_after_tiles: self.pause_after_tiles,
                viewed: true,
                ..JobOptions::default()
            },
        )
        .map_err(|e| e.to_string())?;
        self.views_changed = false;
        self.job = Some(job);
        self.complete = complete;
        self.failure_taken = false;
        self.jobs_started += 1;
        self.settings = Some(settings.clone());
        Ok(())
    }

    fn retire_job(&mut self) {
        if let Some(job) = self.job.take() {
            job.cancel();
            self.retired.push(job);
        }
    }

    /// Drops cancelled jobs that have finished; call once per frame.
    pub(crate) fn collect_retired(&mut self) {
        self.retired.retain(|job| !job.is_finished());
    }

    /// Holds the render between tiles (and before building a structure),
    /// or lets it go on; jobs started later start so.
    pub(crate) fn set_paused(&mut self, paused: bool) {
        self.paused = paused;
        if let Some(job) = &self.job {
            job.set_paused(paused);
        }
    }

    /// Whether renders are held (the job, or the next one, paused). A job
    /// pauses itself after [`Engine::pause_after_tiles`]: then too.
    pub fn is_paused(&self) -> bool {
        self.job.as_ref().map_or(self.paused, RenderJob::is_paused)
    }

    /// The next jobs render only in the time the other engines' renders
    /// leave (the observer's, beside the sides').
    pub(crate) fn set_idle_priority(&mut self, idle: bool) {
        if idle != self.idle_priority {
            self.pool = None;
        }
        self.idle_priority = idle;
    }

    /// The engine's render threads, made on first use: they let the
    /// window's threads run first, or run only when the cores are idle.
    /// None on the web page, whose jobs render on its workers' pool.
    fn render_pool(&mut self) -> Result<Option<Arc<rayon::ThreadPool>>, String> {
        if let Some(pool) = &self.pool {
            return Ok(Some(pool.clone()));
        }
        let priority = if self.idle_priority {
            Priority::Idle
        } else {
            Priority::YieldToViewer
        };
        let pool = target::render_pool(priority)?;
        self.pool.clone_from(&pool);
        Ok(pool)
    }

    /// The next jobs pause themselves once `tiles` tiles are in (`None`:
    /// they run on): a first pass held half done, whatever the machine.
    pub(crate) fn pause_after_tiles(&mut self, tiles: Option<u64>) {
        self.pause_after_tiles = tiles;
    }

    /// Whether the current job rendered its last pass: its image is final
    /// even while the job still reports itself rendering.
    pub(crate) fn is_complete(&self) -> bool {
        self.job.is_some() && self.complete.load(Ordering::Relaxed)
    }

    /// The current job's statistics as they stand, not as last shown: for
    /// a script asking a page whose frames stop while its tab is hidden.
    #[cfg(target_family = "wasm")]
    pub(crate) fn live_stats(&self) -> Option<tracer::stats::RenderStats> {
        self.job.as_ref().map(RenderJob::stats)
    }

    /// The acceleration structure of the current job, once built (or the
    /// last one built), to inspect rays against the same structure.
    pub fn index(&self) -> Option<Arc<SceneIndex>> {
        self.job
            .as_ref()
            .and_then(RenderJob::index)
            .or_else(|| self.index.clone())
    }

    /// Lends this engine the structure another engine built over the same
    /// scene (the observer renders A's scene): its next job skips the
    /// build when the structure fits its settings.
    pub(crate) fn share_index(&mut self, index: Arc<SceneIndex>) {
        if self.index.as_ref().is_none_or(|i| !Arc::ptr_eq(i, &index)) {
            self.index = Some(index);
        }
    }

    /// Whether jobs measure the views; a change renders again.
    pub(crate) fn set_views(&mut self, on: bool) {
        self.views_changed |= on != self.views;
        self.views = on;
    }

    pub fn activity(&self) -> Activity {
        if let Some(loading) = &self.loading {
            return Activity::Loading {
                name: loading.label.clone(),
                fraction: loading.fraction(),
            };
        }
        match &self.job {
            Some(job) => Activity::Job(job.state()),
            None => Activity::Idle,
        }
    }

    /// Why the current job failed (a panic in the tracer, an invalid
    /// camera), once per job, so the window reports it a single time.
    pub(crate) fn take_failure(&mut self) -> Option<String> {
        if self.failure_taken {
            return None;
        }
        match self.job.as_ref()?.state() {
            JobState::Failed(message) => {
                self.failure_taken = true;
                Some(message)
            }
            _ => None,
        }
    }

    /// The settings of the running job.
    pub fn settings(&self) -> Option<&RenderSettings> {
        self.settings.as_ref()
    }
}

mod loader;
mod outputs;
#[cfg(test)]
mod tests;
