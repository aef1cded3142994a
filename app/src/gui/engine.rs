//! The window's bridge to the tracer: it owns the scene being shown and the
//! render job, restarts only what a settings change requires, and loads
//! scenes off the UI thread. Settings go in; images and statistics come out.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::time::{Duration, Instant};

use tracer::accel::{AccelInfo, SceneIndex};
use tracer::render::{
    Encoding, JobOptions, JobState, RenderJob, RenderSettings, Snapshot, View, ViewHeatmap,
};
use tracer::scene::Scene;
use tracer::world::World;

use crate::load::{SceneSource, load_source_with_progress};

use super::frame_meter::count_render_thread_cpu;

/// Wakes the UI from a render thread.
pub type Wake = Arc<dyn Fn() + Send + Sync>;

/// Identifies what an engine shows: (jobs started, the job's own version).
pub type Version = (u64, u64);

/// A scene ready to render, with where it came from.
#[derive(Clone)]
pub struct LoadedScene {
    pub source: SceneSource,
    pub scene: Scene,
    pub world: Arc<World>,
    /// How long parsing and preparing took.
    pub load_time: Duration,
}

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

/// A scene being loaded on its thread.
struct Loading {
    label: String,
    result: Receiver<Result<LoadedScene, String>>,
    /// Thousandths of a mesh file read so far, or [`NO_FRACTION`].
    per_mille: Arc<AtomicU32>,
}

/// A load that has reported no progress (a scene file, a small mesh).
const NO_FRACTION: u32 = u32::MAX;

/// Owns the current scene and its render job.
pub struct Engine {
    scene: Option<LoadedScene>,
    job: Option<RenderJob>,
    /// Settings of the current job, to decide what a change restarts.
    settings: Option<RenderSettings>,
    /// The last acceleration structure built, reused while its kind and
    /// multiplier stay the same.
    index: Option<Arc<SceneIndex>>,
    /// Cancelled jobs still finishing their last tiles; dropped once done
    /// so the UI thread never waits for them.
    retired: Vec<RenderJob>,
    loading: Option<Loading>,
    /// Called by render threads to wake the UI, at its own pace.
    wake: Wake,
    /// Called once the last pass is in, to show it at once.
    wake_now: Wake,
    /// The current job rendered its last pass (set by a render thread).
    complete: Arc<AtomicBool>,
    /// Render threads' priority: low so the window stays responsive.
    low_priority: bool,
    threads: Option<usize>,
    paused: bool,
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
    pub fn new(wake: Wake) -> Self {
        Self::with_wakes(wake.clone(), wake)
    }

    /// An engine that calls `wake` when a render progresses (the UI paces
    /// its redraws) and `wake_now` when its last pass is in, which the UI
    /// should show at once.
    pub fn with_wakes(wake: Wake, wake_now: Wake) -> Self {
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
            low_priority: true,
            threads: None,
            paused: false,
            failure_taken: false,
            jobs_started: 0,
            views: false,
            views_changed: false,
            restart_waiting: Arc::new(AtomicBool::new(false)),
        }
    }

    /// Starts reading `source` on a background thread; the current scene
    /// keeps rendering until the new one is ready.
    pub fn load(&mut self, source: SceneSource) {
        let (tx, rx) = channel();
        let label = source.label();
        let wake = self.wake.clone();
        let per_mille = Arc::new(AtomicU32::new(NO_FRACTION));
        let progress = per_mille.clone();
        let spawned = std::thread::Builder::new()
            .name("scene-loader".into())
            .spawn(move || {
                let start = Instant::now();
                let mut on_progress = |p: tracer::mesh_io::LoadProgress| {
                    let fraction = p.bytes_read as f64 / p.total_bytes.max(1) as f64;
                    progress.store((fraction.min(1.0) * 1000.0) as u32, Ordering::Relaxed);
                    wake();
                };
                let result = load_source_with_progress(&source, &mut on_progress)
                    .map(|(scene, world)| LoadedScene {
                        source,
                        scene,
                        world: Arc::new(world),
                        load_time: start.elapsed(),
                    })
                    .map_err(|e| format!("{e:#}"));
                let _ = tx.send(result);
                wake();
            });
        let result = match spawned {
            Ok(_) => rx,
            Err(e) => {
                let (tx, rx) = channel();
                let _ = tx.send(Err(format!("cannot start the scene loader: {e}")));
                rx
            }
        };
        self.loading = Some(Loading {
            label,
            result,
            per_mille,
        });
    }

    /// Takes a finished load, if any: `Some(Ok(scene))` to be shown with
    /// [`Engine::show`], `Some(Err(message))` when it failed.
    pub fn poll_load(&mut self) -> Option<Result<&LoadedScene, String>> {
        let rx = &self.loading.as_ref()?.result;
        match rx.try_recv() {
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                self.loading = None;
                Some(Err("the scene loader stopped unexpectedly".into()))
            }
            Ok(result) => {
                self.loading = None;
                match result {
                    Ok(scene) => {
                        self.show(scene);
                        self.scene.as_ref().map(Ok)
                    }
                    Err(message) => Some(Err(message)),
                }
            }
        }
    }

    /// Makes `scene` the current scene (loaded elsewhere, e.g. by the
    /// other side of a comparison); nothing renders until asked.
    pub fn show(&mut self, scene: LoadedScene) {
        self.retire_job();
        self.index = None;
        self.settings = None;
        self.scene = Some(scene);
    }

    pub fn scene(&self) -> Option<&LoadedScene> {
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
    pub fn render(&mut self, settings: &RenderSettings) -> Result<(), String> {
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
    pub fn restart(&mut self, settings: &RenderSettings) -> Result<(), String> {
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
        let last_pass = (!settings.keep_refining).then(|| settings.samples_per_pixel());
        let job = RenderJob::start(
            world,
            self.index.clone(),
            settings.clone(),
            JobOptions {
                threads: self.threads,
                on_progress: Some(Box::new(move || {
                    count_render_thread_cpu();
                    if done.load(Ordering::Relaxed) || waiting.load(Ordering::Relaxed) {
                        wake_now();
                    } else {
                        wake();
                    }
                })),
                on_pass: Some(Box::new(move |pass, _| {
                    if Some(pass) == last_pass {
                        last_pass_in.store(true, Ordering::Relaxed);
                    }
                })),
                low_priority: self.low_priority,
                views: self.views,
            },
        )
        .map_err(|e| e.to_string())?;
        self.views_changed = false;
        job.set_paused(self.paused);
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
    pub fn collect_retired(&mut self) {
        self.retired.retain(|job| !job.is_finished());
    }

    pub fn set_paused(&mut self, paused: bool) {
        self.paused = paused;
        if let Some(job) = &self.job {
            job.set_paused(paused);
        }
    }

    pub fn is_paused(&self) -> bool {
        self.paused
    }

    /// Sets the worker threads for the next job (`None`: every core).
    pub fn set_threads(&mut self, threads: Option<usize>) {
        self.threads = threads;
    }

    /// Whether render threads run at low priority (next job on).
    pub fn set_low_priority(&mut self, low: bool) {
        self.low_priority = low;
    }

    /// Whether the current job rendered its last pass: its image is final
    /// even while the job still reports itself rendering.
    pub fn is_complete(&self) -> bool {
        self.job.is_some() && self.complete.load(Ordering::Relaxed)
    }

    /// A number that changes whenever the image or statistics change,
    /// including when a new job replaces one that reached the same count.
    pub fn version(&self) -> Version {
        (
            self.jobs_started,
            self.job.as_ref().map_or(0, |j| j.version()),
        )
    }

    /// The current image and statistics.
    pub fn snapshot(&self, encoding: Encoding) -> Option<Snapshot> {
        self.job.as_ref().map(|j| j.snapshot(encoding))
    }

    /// The current job's film as linear floats, for "Save as EXR".
    pub fn linear_image(&self) -> Option<image::Rgb32FImage> {
        self.job.as_ref().map(RenderJob::linear_image)
    }

    /// The acceleration structure of the current job, once built (or the
    /// last one built), to inspect rays against the same structure.
    pub fn index(&self) -> Option<Arc<SceneIndex>> {
        self.job
            .as_ref()
            .and_then(RenderJob::index)
            .or_else(|| self.index.clone())
    }

    /// Whether jobs measure the views; a change renders again.
    pub fn set_views(&mut self, on: bool) {
        self.views_changed |= on != self.views;
        self.views = on;
    }

    /// The current image under `view` (the shaded image while the job
    /// does not measure views).
    pub fn view_snapshot(
        &self,
        view: View,
        heat: &ViewHeatmap,
        encoding: Encoding,
    ) -> Option<Snapshot> {
        self.job
            .as_ref()
            .map(|j| j.view_snapshot(view, heat, encoding))
    }

    /// The value of a scalar view at one pixel, if the job measures views.
    pub fn view_value(&self, view: View, x: u32, y: u32) -> Option<f32> {
        self.job.as_ref()?.view_value(view, x, y)
    }

    /// The current values of a scalar view, if the job measures views.
    pub fn view_values(&self, view: View) -> Option<Vec<Option<f32>>> {
        self.job.as_ref().and_then(|j| j.view_values(view))
    }

    /// What was built for the current job, once built.
    pub fn accel_info(&self) -> Option<AccelInfo> {
        self.job
            .as_ref()
            .and_then(|j| j.index())
            .map(|i| i.info().clone())
    }

    pub fn activity(&self) -> Activity {
        if let Some(loading) = &self.loading {
            let per_mille = loading.per_mille.load(Ordering::Relaxed);
            return Activity::Loading {
                name: loading.label.clone(),
                fraction: (per_mille != NO_FRACTION).then(|| per_mille as f32 / 1000.0),
            };
        }
        match &self.job {
            Some(job) => Activity::Job(job.state()),
            None => Activity::Idle,
        }
    }

    /// Why the current job failed (a panic in the tracer, an invalid
    /// camera), once per job, so the window reports it a single time.
    pub fn take_failure(&mut self) -> Option<String> {
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

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicU32, Ordering};

    use tracer::accel::AccelKind;

    use super::*;

    fn wait_until(engine: &mut Engine, done: impl Fn(&mut Engine) -> bool) {
        let start = Instant::now();
        while !done(engine) {
            assert!(start.elapsed() < Duration::from_secs(120), "gave up");
            std::thread::sleep(Duration::from_millis(2));
        }
    }

    #[test]
    fn a_panicking_render_is_reported_once_and_the_next_render_works() {
        // The wake-up callback runs on the render threads; its third call
        // panics, standing for a bug in the tracer.
        let calls = Arc::new(AtomicU32::new(0));
        let counter = calls.clone();
        let mut engine = Engine::new(Arc::new(move || {
            if counter.fetch_add(1, Ordering::Relaxed) == 2 {
                panic!("a bug in the tracer");
            }
        }));
        engine.load(SceneSource::Bundled("balls_low".into()));
        wait_until(&mut engine, |e| e.poll_load().is_some());
        let settings = RenderSettings {
            width: 64,
            height: 64,
            ..RenderSettings::from_scene(&engine.scene().unwrap().scene)
        };
        engine.render(&settings).unwrap();
        wait_until(&mut engine, |e| {
            matches!(e.activity(), Activity::Job(JobState::Failed(_)))
        });
        let failure = engine.take_failure().expect("the failure");
        assert!(failure.contains("a bug in the tracer"), "{failure}");
        assert_eq!(engine.take_failure(), None, "reported once");

        engine.restart(&settings).unwrap();
        wait_until(&mut engine, |e| {
            e.activity() == Activity::Job(JobState::Done)
        });
        assert_eq!(engine.take_failure(), None);
        let snapshot = engine.snapshot(Encoding::Linear).unwrap();
        assert_eq!(snapshot.stats.passes_done, snapshot.stats.passes_target);
    }

    #[test]
    fn a_large_mesh_reports_how_much_is_read_while_it_loads() {
        // About 10 MB of OBJ: progress comes every 4 MB.
        let dir = tracer::scratch::Scratch::new("engine-mesh");
        let path = dir.join("big.obj");
        let mut text = String::new();
        for i in 0..150_000 {
            let x = i as f32 * 1e-4;
            text += &format!(
                "v {x:.6} {:.6} 0.000000\nv {x:.6} 1.000000 0.500000\n",
                x * 0.5
            );
        }
        for i in 0..149_999 {
            text += &format!("f {} {} {}\n", 2 * i + 1, 2 * i + 2, 2 * i + 3);
        }
        std::fs::write(&path, text).unwrap();
        let mut engine = Engine::new(Arc::new(|| {}));
        engine.load(SceneSource::File(path));
        // The last fraction stays until the load is taken.
        wait_until(
            &mut engine,
            |e| matches!(e.activity(), Activity::Loading { fraction: Some(f), .. } if f > 0.0),
        );
        let Activity::Loading { name, fraction } = engine.activity() else {
            panic!("still loading until taken");
        };
        assert!(
            name.contains("big.obj") && fraction.unwrap() <= 1.0,
            "{name}"
        );
        wait_until(&mut engine, |e| e.poll_load().is_some());
        assert_eq!(engine.scene().unwrap().world.counts.triangles, 149_999);
    }

    /// An engine on the bundled scene `name`, counting its paced and its
    /// immediate wakes.
    fn counting_engine(name: &str) -> (Arc<AtomicU32>, Arc<AtomicU32>, Engine) {
        let paced = Arc::new(AtomicU32::new(0));
        let at_once = Arc::new(AtomicU32::new(0));
        let counting = |count: &Arc<AtomicU32>| -> Wake {
            let count = count.clone();
            Arc::new(move || {
                count.fetch_add(1, Ordering::Relaxed);
            })
        };
        let mut engine = Engine::with_wakes(counting(&paced), counting(&at_once));
        engine.load(SceneSource::Bundled(name.into()));
        wait_until(&mut engine, |e| e.poll_load().is_some());
        (paced, at_once, engine)
    }

    #[test]
    fn the_last_pass_wakes_the_window_at_once() {
        let (paced, at_once, mut engine) = counting_engine("balls_low");
        let settings = RenderSettings {
            width: 32,
            height: 32,
            antialiasing: true,
            samples: 2,
            ..RenderSettings::from_scene(&engine.scene().unwrap().scene)
        };
        engine.render(&settings).unwrap();
        wait_until(&mut engine, |e| {
            e.activity() == Activity::Job(JobState::Done)
        });
        assert!(engine.is_complete());
        assert!(paced.load(Ordering::Relaxed) > 0, "tiles wake at the pace");
        // The last pass's report and the job's end.
        assert!(at_once.load(Ordering::Relaxed) >= 1);

        // A render that keeps refining is never complete.
        let refining = RenderSettings {
            keep_refining: true,
            ..settings
        };
        engine.render(&refining).unwrap();
        assert!(!engine.is_complete(), "a new job starts incomplete");
        wait_until(&mut engine, |e| {
            e.snapshot(Encoding::Linear).unwrap().stats.passes_done > 5
        });
        assert!(!engine.is_complete());
    }

    #[test]
    fn new_settings_wait_for_the_structure_being_built_instead_of_building_another() {
        // 262k triangles: its BVH takes tens of milliseconds to build.
        let (_, at_once, mut engine) = counting_engine("mesh_large");
        // Refining for ever: the last pass never wakes the window at once.
        let settings = RenderSettings {
            width: 24,
            height: 24,
            keep_refining: true,
            ..RenderSettings::from_scene(&engine.scene().unwrap().scene)
        };
        let moved = RenderSettings {
            ambient: settings.ambient + 0.1,
            ..settings.clone()
        };
        engine.render(&settings).unwrap();
        assert_eq!(engine.activity(), Activity::Job(JobState::Building));
        engine.render(&moved).unwrap();
        assert_eq!(engine.version().0, 1, "no second job, no second build");
        assert_eq!(engine.activity(), Activity::Job(JobState::Building));
        // The window calls again every frame; the build's report wakes it.
        wait_until(&mut engine, |e| {
            e.render(&moved).unwrap();
            e.version().0 == 2
        });
        assert!(at_once.load(Ordering::Relaxed) > 0, "woken at once");
        assert_ne!(
            engine.activity(),
            Activity::Job(JobState::Building),
            "the new job has the structure already"
        );
        assert_eq!(engine.settings(), Some(&moved));
        // A change of structure does not wait.
        let grid = RenderSettings {
            accel: AccelKind::Grid,
            ..moved.clone()
        };
        engine.render(&grid).unwrap();
        assert_eq!(engine.version().0, 3);
    }
}
