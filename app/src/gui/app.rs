//! The workbench window: panels around the live image, with every action
//! recorded as a [`Command`] and run once at the end of the frame.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, channel};
use std::time::{Duration, Instant};

use egui::{Color32, RichText, Ui};
use tracer::camera::CameraPose;
use tracer::render::JobState;

use crate::bundled;
use crate::load::SceneSource;
use crate::output::{save_exr, save_png};

use super::bench_window::BenchWindow;
use super::commands::Command;
use super::compare::{self, Compare, CompareView};
use super::engine::{Activity, Engine};
use super::frame_meter::{CpuTimes, FrameMeter, ProgressPace};
use super::inspector::Inspector;
use super::live_image::LiveImage;
use super::overlay::StructureOverlay;
use super::screenshot::{self, ScreenshotOutcome, ScreenshotPlan};
use super::state::AccelChoice;
use super::state::{Controls, Persisted};
use super::studies::{Applied, StudiesWindow};
use super::view_select::{self, ViewChoice};
use super::viewport::{self, Gesture, ViewState, Zoom};
use super::{accel_banner, controls, scene_picker, stats_panel};

/// How long after the last wheel dolly the camera counts as moving.
const MOVE_SETTLE: Duration = Duration::from_millis(250);
/// How long a notice stays on screen.
const NOTICE_TIME: Duration = Duration::from_secs(5);
/// Longest wait for the first render before the scene list's counts start.
const CATALOG_DELAY: Duration = Duration::from_secs(3);

/// What a save writes: the shown render (PNG) or the linear film (EXR).
enum SaveImage {
    Shown(tracer::render::Snapshot),
    Linear(image::Rgb32FImage),
}

/// Results of background dialogs and saves, delivered to the UI thread.
enum Reply {
    Open(PathBuf),
    Notice(String),
    Error(String),
    /// The line to print once the screenshot is saved, or why it was not.
    Screenshot(Result<String, String>),
}

/// The application state: persisted settings plus runtime handles.
pub struct WorkbenchApp {
    state: Persisted,
    engine: Engine,
    view: ViewState,
    /// The camera after the user moved it; `None` is the scene's own.
    camera: Option<CameraPose>,
    /// The render on screen.
    image: LiveImage,
    /// The B side while comparing.
    compare: Option<Compare>,
    bench: BenchWindow,
    studies: StudiesWindow,
    /// For wake-ups from render threads of jobs started later.
    repaint_ctx: egui::Context,
    dragging_camera: bool,
    moving_until: Option<Instant>,
    /// Opening a scene adopts its settings; restoring the last session
    /// keeps the persisted ones.
    adopt_next_scene: bool,
    error: Option<String>,
    notice: Option<(String, Instant)>,
    help_open: bool,
    disk_scenes: Vec<PathBuf>,
    catalog: scene_picker::Catalog,
    hovered_pixel: Option<(u32, u32)>,
    frame_meter: FrameMeter,
    /// How often render progress may redraw the window (see [`FrameMeter`]).
    progress_pace: ProgressPace,
    /// The title last given to the window, to send it only when it changes
    /// (every viewport command asks for one more frame).
    title: String,
    replies: (Sender<Reply>, Receiver<Reply>),
    opened_at: Instant,
    screenshot: Option<(ScreenshotPlan, ScreenshotOutcome)>,
    screenshot_requested: bool,
    /// Which per-pixel view the images show.
    views: ViewChoice,
    /// The pinned pixel's ray tree.
    inspector: Inspector,
    /// The acceleration structure drawn over the image.
    overlay: StructureOverlay,
}

impl WorkbenchApp {
    /// Creates the app, restoring the persisted state when `storage` has
    /// one, and starts loading `initial` (or the last scene, or the bundled
    /// default).
    pub fn new(
        ctx: &egui::Context,
        storage: Option<&dyn eframe::Storage>,
        initial: Option<SceneSource>,
    ) -> Self {
        let state: Persisted = storage
            .and_then(|s| eframe::get_value(s, eframe::APP_KEY))
            .unwrap_or_default();
        let (wake_ctx, wake_now_ctx) = (ctx.clone(), ctx.clone());
        let progress_pace = ProgressPace::default();
        let pace = progress_pace.clone();
        let mut app = Self {
            engine: Engine::with_wakes(
                Arc::new(move || wake_ctx.request_repaint_after(pace.get())),
                Arc::new(move || wake_now_ctx.request_repaint()),
            ),
            progress_pace,
            view: ViewState::default(),
            camera: None,
            image: LiveImage::new("render"),
            compare: None,
            bench: BenchWindow::default(),
            studies: StudiesWindow::default(),
            repaint_ctx: ctx.clone(),
            dragging_camera: false,
            moving_until: None,
            adopt_next_scene: true,
            error: None,
            notice: None,
            help_open: false,
            disk_scenes: scene_picker::scene_files(Path::new("scenes")),
            // Started by `start_catalog_when_due`.
            catalog: scene_picker::Catalog::default(),
            hovered_pixel: None,
            frame_meter: FrameMeter::default(),
            title: String::new(),
            replies: channel(),
            opened_at: Instant::now(),
            screenshot: None,
            screenshot_requested: false,
            views: ViewChoice::default(),
            inspector: Inspector::default(),
            overlay: StructureOverlay::default(),
            state,
        };
        let restoring = initial.is_none() && app.state.last_scene.is_some();
        let last_scene = match app.state.last_scene.clone() {
            Some(SceneSource::File(path)) if restoring && !path.exists() => {
                app.notify(format!(
                    "{} is gone: the last scene of the previous session was moved or deleted",
                    path.display()
                ));
                None
            }
            last => last,
        };
        let restoring = restoring && last_scene.is_some();
        let source = initial.or(last_scene).or_else(default_scene);
        if let Some(source) = source {
            app.adopt_next_scene = !restoring;
            app.engine.load(source);
        }
        app
    }

    /// Takes a screenshot as `plan` says, reports it in `outcome` and closes
    /// the window.
    pub fn with_screenshot(mut self, plan: ScreenshotPlan, outcome: ScreenshotOutcome) -> Self {
        self.screenshot = Some((plan, outcome));
        self
    }

    /// The persisted state (for tests and saving).
    pub fn state(&self) -> &Persisted {
        &self.state
    }

    /// Mutable persisted state, as the side panel edits it.
    pub fn state_mut(&mut self) -> &mut Persisted {
        &mut self.state
    }

    /// The engine, for tests that check what the renderer was asked.
    /// The structure overlay.
    pub fn overlay(&self) -> &StructureOverlay {
        &self.overlay
    }

    /// The ray-tree inspector.
    pub fn inspector(&self) -> &Inspector {
        &self.inspector
    }

    /// Pins `pixel` in the inspector, as a click on it does.
    pub fn inspect(&mut self, pixel: (u32, u32)) {
        self.inspector.pin(pixel);
    }

    /// The per-pixel view the images show.
    pub fn views(&self) -> &ViewChoice {
        &self.views
    }

    pub fn engine(&self) -> &Engine {
        &self.engine
    }

    /// The B side, while comparing.
    pub fn comparison(&self) -> Option<&Compare> {
        self.compare.as_ref()
    }

    /// The benchmark matrix window.
    pub fn benchmark(&self) -> &BenchWindow {
        &self.bench
    }

    /// The Studies window.
    pub fn studies(&self) -> &StudiesWindow {
        &self.studies
    }

    /// The error shown in the window, if any.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// The render on screen, once there is one.
    pub fn shown(&self) -> Option<&tracer::render::Snapshot> {
        self.image.shown()
    }

    /// Samples per pixel of the image on screen, once there is one.
    pub fn shown_passes(&self) -> Option<u32> {
        self.image.shown().map(|s| s.stats.passes_done)
    }

    /// Starts counting the bundled scenes for the scene list once the
    /// first render no longer needs the machine (or there is no scene), or
    /// [`CATALOG_DELAY`] after opening at the latest: parsing them took
    /// 30-100 ms of CPU during balls_medium's 0.4 s first render on two
    /// cores, its thread's lowest priority notwithstanding. The counts
    /// redraw the window at the progress pace.
    fn start_catalog_when_due(&mut self, ctx: &egui::Context) {
        if self.catalog.is_started() {
            return;
        }
        // A scene just loaded renders later in this frame.
        let busy = match self.engine.activity() {
            Activity::Loading { .. } | Activity::Job(JobState::Building | JobState::Rendering) => {
                true
            }
            Activity::Idle => self.engine.scene().is_some(),
            Activity::Job(_) => false,
        };
        if busy && self.opened_at.elapsed() < CATALOG_DELAY {
            return;
        }
        let (ctx, pace) = (ctx.clone(), self.progress_pace.clone());
        self.catalog
            .start(move || ctx.request_repaint_after(pace.get()));
    }

    /// Whether the scene list's counting has started.
    pub fn is_catalog_started(&self) -> bool {
        self.catalog.is_started()
    }

    /// Whether the scene list has the object count of every bundled scene.
    pub fn is_catalog_complete(&self) -> bool {
        self.catalog.is_complete()
    }

    /// Whether the screen shows the renderer's latest image (uploads are
    /// throttled, so it may lag a little behind).
    pub fn is_display_current(&self) -> bool {
        self.image.is_current(&self.engine)
    }

    /// Starts loading a scene as the user would open it.
    pub fn open(&mut self, source: SceneSource) {
        self.adopt_next_scene = true;
        self.engine.load(source);
    }

    /// Writes the displayed render, at its full resolution, to `path`.
    pub fn save_png_to(&self, path: &Path) -> anyhow::Result<()> {
        let snapshot = self
            .image
            .shown()
            .ok_or_else(|| anyhow::anyhow!("there is no image to save yet"))?;
        let image = snapshot
            .to_image()
            .ok_or_else(|| anyhow::anyhow!("the image buffer has the wrong size"))?;
        save_png(&image, path)
    }

    /// Writes the linear film of the render on screen to `path` (OpenEXR).
    pub fn save_exr_to(&self, path: &Path) -> anyhow::Result<()> {
        let film = self
            .engine
            .linear_image()
            .ok_or_else(|| anyhow::anyhow!("there is no image to save yet"))?;
        save_exr(&film, path)
    }

    /// Side B shows the image at `path` (PNG, JPEG or EXR), as "Compare
    /// with image..." does with the file picked; an unreadable file is
    /// reported in the window.
    pub fn compare_with_image(&mut self, path: &Path) {
        if let Some(compare) = &mut self.compare {
            compare.open_reference(path, self.state.controls.encoding());
        }
    }

    /// Files opened recently, newest first.
    pub fn recent_files(&self) -> &[PathBuf] {
        &self.state.recent
    }

    fn is_camera_moving(&self) -> bool {
        self.dragging_camera || self.moving_until.is_some_and(|t| Instant::now() < t)
    }

    /// Takes finished loads, dialogs, saves and screenshots.
    fn receive(&mut self, ctx: &egui::Context) {
        if let Some(result) = self.engine.poll_load() {
            match result {
                Ok(loaded) => {
                    let scene = loaded.scene.clone();
                    let source = loaded.source.clone();
                    let warnings = loaded.world.warnings.clone();
                    if self.adopt_next_scene {
                        self.state.controls.adopt_scene(&scene);
                    }
                    self.adopt_next_scene = true;
                    self.camera = None;
                    self.view = ViewState::default();
                    self.error = None;
                    self.image.forget();
                    if let (Some(compare), Some(loaded)) = (&mut self.compare, self.engine.scene())
                    {
                        compare.show_scene(loaded);
                    }
                    if let SceneSource::File(path) = &source {
                        self.state.remember(path.clone());
                    }
                    self.state.last_scene = Some(source);
                    if !warnings.is_empty() {
                        self.notify(warnings.join("; "));
                    }
                }
                Err(message) => self.error = Some(message),
            }
        }
        while let Ok(reply) = self.replies.1.try_recv() {
            match reply {
                Reply::Open(path) => self.open(SceneSource::File(path)),
                Reply::Notice(text) => self.notify(text),
                Reply::Error(text) => self.error = Some(text),
                Reply::Screenshot(result) => {
                    if let Some((_, outcome)) = &self.screenshot
                        && let Ok(mut slot) = outcome.lock()
                    {
                        *slot = Some(result);
                    }
                    ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                }
            }
        }
    }

    fn notify(&mut self, text: String) {
        self.notice = Some((text, Instant::now()));
    }

    /// Opens scene files dropped on the window.
    fn take_dropped_files(&mut self, ctx: &egui::Context) {
        let dropped = ctx.input(|i| i.raw.dropped_files.clone());
        for file in dropped {
            let path = file.path();
            if scene_picker::is_scene_file(path) {
                self.open(SceneSource::File(path.to_path_buf()));
                return;
            }
            self.notify(format!(
                "{} is not a scene or mesh file (.p3f, .nff, .obj, .ply)",
                path.display()
            ));
        }
    }

    /// The controls the side panel and the toggles edit: B's while
    /// comparing with B selected, else A's.
    fn active_controls(&mut self) -> &mut Controls {
        match &mut self.compare {
            Some(compare) if compare.editing_b => &mut compare.controls,
            _ => &mut self.state.controls,
        }
    }

    fn run_command(&mut self, command: Command) {
        let controls = self.active_controls();
        match command {
            Command::ToggleAntialiasing => controls.antialiasing ^= true,
            Command::ToggleSoftShadows => controls.soft_shadows ^= true,
            Command::ToggleDepthOfField => controls.depth_of_field ^= true,
            Command::ToggleGrid => controls.toggle_grid(),
            Command::ToggleKeepRefining => controls.keep_refining ^= true,
            Command::TogglePause => self.engine.set_paused(!self.engine.is_paused()),
            Command::Restart => self.restart(),
            Command::ResetCamera => self.camera = None,
            Command::ZoomFit => self.view = ViewState::default(),
            Command::ZoomActualSize => {
                self.view = ViewState {
                    zoom: Zoom::Scale(1.0),
                    ..ViewState::default()
                }
            }
            Command::ToggleStats => self.state.show_stats ^= true,
            Command::CycleView => self.views.cycle(),
            Command::ToggleHelp => self.help_open ^= true,
            Command::ToggleCompare => self.toggle_compare(),
            Command::ToggleBenchmark => self.bench.open ^= true,
            Command::ToggleStudies => self.studies.open ^= true,
            Command::SwapSides => self.swap_sides(),
            Command::CopyAToB => match &mut self.compare {
                Some(compare) => compare.controls = self.state.controls.clone(),
                None => self.notify("copy A to B: turn compare mode on first (B)".into()),
            },
            Command::Reload => match self.state.last_scene.clone() {
                Some(source) => {
                    self.adopt_next_scene = false;
                    self.engine.load(source);
                }
                None => self.notify("no scene to reload".into()),
            },
            Command::Open => self.open_dialog(),
            Command::Save => self.save_dialog(false),
            Command::SaveExr => self.save_dialog(true),
        }
    }

    /// The benchmark matrix window, started on the current scene, camera
    /// and size.
    fn benchmark_window(&mut self, ctx: &egui::Context) {
        self.bench.receive(ctx);
        if !self.bench.open {
            return;
        }
        let name = self
            .engine
            .scene()
            .map_or_else(|| "no scene".into(), |s| s.source.label());
        let mut start = false;
        self.bench.show(ctx, &name, &mut start);
        if start && let Some(scene) = self.engine.scene() {
            let base = self
                .state
                .controls
                .render_settings(&scene.scene, self.camera, false);
            let wake = ctx.clone();
            self.bench
                .start(scene.world.clone(), &base, move || wake.request_repaint());
        }
    }

    /// The Studies window, started on the current scene, camera and size;
    /// a point the user picks is shown in the main view.
    fn studies_window(&mut self, ctx: &egui::Context) {
        self.studies.receive(ctx);
        if !self.studies.open {
            return;
        }
        let base = self.engine.scene().map_or_else(Default::default, |s| {
            self.state
                .controls
                .render_settings(&s.scene, self.camera, false)
        });
        let mut start = false;
        let applied = self.studies.show(ctx, &base, &mut start);
        if start {
            let wake = ctx.clone();
            let scene = self.engine.scene();
            let name = scene.map_or_else(String::new, |s| s.source.label());
            self.studies.start(
                scene.map(|s| s.world.clone()),
                &base,
                &self.state.controls,
                &name,
                move || wake.request_repaint(),
            );
        }
        if let Some(applied) = applied {
            self.apply_study_point(&applied);
        }
    }

    /// A study's point in the main view: its settings, or for the level
    /// study its generated scene.
    fn apply_study_point(&mut self, applied: &Applied) {
        match applied.scene_file() {
            Ok(Some(path)) => self.open(SceneSource::File(path)),
            Ok(None) => {
                let width = self.engine.scene().map_or(1, |s| s.scene.view.width);
                applied.apply_to(&mut self.state.controls, width);
            }
            Err(e) => self.error = Some(format!("{e:#}")),
        }
    }

    fn toggle_compare(&mut self) {
        if self.compare.take().is_none() {
            let (ctx, now_ctx) = (self.repaint_ctx.clone(), self.repaint_ctx.clone());
            let pace = self.progress_pace.clone();
            self.compare = Some(Compare::new(
                Arc::new(move || ctx.request_repaint_after(pace.get())),
                Arc::new(move || now_ctx.request_repaint()),
                &self.state.controls,
                self.engine.scene(),
            ));
        }
    }

    /// Exchanges A and B, renders and all, so nothing re-renders.
    fn swap_sides(&mut self) {
        let Some(compare) = &mut self.compare else {
            self.notify("swap: turn compare mode on first (B)".into());
            return;
        };
        std::mem::swap(&mut self.engine, &mut compare.engine);
        std::mem::swap(&mut self.image, &mut compare.image);
        std::mem::swap(&mut self.state.controls, &mut compare.controls);
    }

    fn restart(&mut self) {
        if let Some(scene) = self.engine.scene() {
            let settings = self.state.controls.render_settings(
                &scene.scene,
                self.camera,
                self.is_camera_moving(),
            );
            if let Err(e) = self.engine.restart(&settings) {
                self.error = Some(e);
            }
            let moving = self.is_camera_moving();
            if let Some(compare) = &mut self.compare
                && let Some(settings) = compare.settings(self.camera, moving)
                && let Err(e) = compare.engine.restart(&settings)
            {
                self.error = Some(e);
            }
        }
    }

    /// The native open dialog, on its own thread so the UI keeps drawing.
    fn open_dialog(&mut self) {
        let reply = self.replies.0.clone();
        let spawned = std::thread::Builder::new()
            .name("open-dialog".into())
            .spawn(move || {
                let picked = rfd::FileDialog::new()
                    .add_filter("Scenes and meshes", &["p3f", "nff", "obj", "ply"])
                    .set_directory("scenes")
                    .pick_file();
                let _ = reply.send(match picked {
                    Some(path) => Reply::Open(path),
                    None => Reply::Notice(
                        "nothing opened (cancelled, or no file dialog on this desktop: \
                         drop a file on the window instead)"
                            .into(),
                    ),
                });
            });
        if spawned.is_err() {
            self.notify("cannot open a file dialog".into());
        }
    }

    /// The native save dialog and the write, off the UI thread: the shown
    /// render as PNG, or the linear film as OpenEXR (`exr`).
    fn save_dialog(&mut self, exr: bool) {
        let image = if exr {
            self.engine.linear_image().map(SaveImage::Linear)
        } else {
            self.image.shown().cloned().map(SaveImage::Shown)
        };
        let Some(image) = image else {
            self.notify("there is no image to save yet".into());
            return;
        };
        if self.is_camera_moving() {
            self.notify("the camera is moving: save once the render settles".into());
            return;
        }
        let name = self
            .state
            .last_scene
            .as_ref()
            .map_or_else(|| "render".into(), |s| s.label());
        let stem = Path::new(&name)
            .file_stem()
            .map_or_else(|| "render".into(), |s| s.to_string_lossy().into_owned());
        let (filter, extension) = if exr {
            ("OpenEXR image", "exr")
        } else {
            ("PNG image", "png")
        };
        let reply = self.replies.0.clone();
        let spawned = std::thread::Builder::new()
            .name("save-dialog".into())
            .spawn(move || {
                let Some(path) = rfd::FileDialog::new()
                    .add_filter(filter, &[extension])
                    .set_file_name(format!("{stem}.{extension}"))
                    .save_file()
                else {
                    let _ = reply.send(Reply::Notice(
                        "not saved (cancelled, or no file dialog on this desktop)".into(),
                    ));
                    return;
                };
                let result = match image {
                    SaveImage::Linear(film) => save_exr(&film, &path),
                    SaveImage::Shown(snapshot) => snapshot
                        .to_image()
                        .ok_or_else(|| anyhow::anyhow!("the image buffer has the wrong size"))
                        .and_then(|img| save_png(&img, &path)),
                };
                let _ = reply.send(match result {
                    Ok(()) => Reply::Notice(format!("saved {}", path.display())),
                    Err(e) => Reply::Error(format!("{e:#}")),
                });
            });
        if spawned.is_err() {
            self.notify("cannot open a file dialog".into());
        }
    }

    /// Applies camera gestures from the viewport.
    fn apply_gestures(&mut self, gestures: &[Gesture]) {
        let Some(scene) = self.engine.scene() else {
            return;
        };
        let mut pose = self
            .camera
            .unwrap_or_else(|| CameraPose::of(&scene.scene.view));
        for gesture in gestures {
            pose = match *gesture {
                Gesture::Orbit { yaw, pitch } => pose.orbit(yaw, pitch),
                Gesture::Pan { dx, dy } => pose.pan(dx, dy),
                Gesture::Dolly(factor) => {
                    self.moving_until = Some(Instant::now() + MOVE_SETTLE);
                    pose.dolly(factor)
                }
            };
        }
        if !gestures.is_empty() {
            self.camera = Some(pose);
        }
    }

    /// Keeps the engine rendering what the controls say.
    fn sync_render(&mut self, ctx: &egui::Context) {
        let moving = self.is_camera_moving();
        let Some(scene) = self.engine.scene() else {
            return;
        };
        let settings = self
            .state
            .controls
            .render_settings(&scene.scene, self.camera, moving);
        self.engine.set_views(self.views.measures());
        if let Err(e) = self.engine.render(&settings) {
            self.error = Some(e);
        }
        if let Some(compare) = &mut self.compare {
            compare.engine.set_views(self.views.measures());
            if let Err(e) = compare.sync(self.camera, moving) {
                self.error = Some(e);
            }
        }
        if let Some(failure) = self.engine.take_failure() {
            self.error = Some(format!(
                "the render failed: {failure}. The image so far stays; change a setting or \
                 press R to render again"
            ));
        }
        if let Some(until) = self.moving_until {
            let now = Instant::now();
            if now < until {
                ctx.request_repaint_after(until - now);
            } else {
                self.moving_until = None;
            }
        }
    }

    /// Uploads the render to the GPU when it changed, at the progress pace.
    fn refresh_texture(&mut self, ctx: &egui::Context) {
        let encoding = self.state.controls.encoding();
        let b = self.compare.as_ref().map(|c| &c.engine);
        let shown = self.views.fit(ctx, &self.engine, b);
        self.image.set_view(shown);
        self.image
            .refresh(ctx, &self.engine, encoding, self.progress_pace.get());
        if let Some(compare) = &mut self.compare {
            compare.image.set_view(shown);
            let view = shown.map(|(view, _)| view);
            compare.refresh(
                ctx,
                (&self.engine, &self.image),
                self.progress_pace.get(),
                view,
            );
        }
    }

    fn status_line(&self) -> String {
        let mut parts = Vec::new();
        if let Some(s) = self.image.shown() {
            parts.push(format!(
                "{} x {} · {} / {} spp · {:.2} s",
                s.width,
                s.height,
                s.stats.passes_done,
                s.stats.passes_target,
                s.stats.render_time.as_secs_f64()
            ));
        }
        let state = match self.engine.activity() {
            Activity::Idle => "no scene".to_string(),
            Activity::Loading {
                name,
                fraction: None,
            } => format!("loading {name}…"),
            Activity::Loading {
                name,
                fraction: Some(f),
            } => format!("loading {name}… {:.0}%", f * 100.0),
            Activity::Job(_) if self.is_camera_moving() => "preview (camera moving)".into(),
            Activity::Job(JobState::Building) => "building acceleration structure…".into(),
            Activity::Job(JobState::Rendering) if self.engine.is_paused() => "paused".into(),
            Activity::Job(JobState::Rendering) => "rendering".into(),
            Activity::Job(JobState::Done) => "done".into(),
            Activity::Job(JobState::Cancelled) => "cancelled".into(),
            Activity::Job(JobState::Failed(e)) => format!("failed: {e}"),
        };
        parts.push(state);
        if self.engine.scene().is_some_and(|s| s.source.is_bare_mesh()) {
            parts.push(tracer::mesh_io::FRAMING_NOTE.into());
        }
        parts.join(" · ")
    }

    fn pixel_readout(&self) -> Option<String> {
        let (x, y) = self.hovered_pixel?;
        let s = self.image.shown()?;
        let i = (y as usize * s.width as usize + x as usize) * 4;
        let p = s.rgba.get(i..i + 4)?;
        let view = self.views.view;
        Some(if p[3] == 0 {
            format!("({x}, {y}) not rendered yet")
        } else if let Some(value) = view_select::readout(&self.engine, view, x, y) {
            format!("({x}, {y}) {value}")
        } else {
            format!("({x}, {y}) rgb {} {} {}", p[0], p[1], p[2])
        })
    }

    fn help_window(&mut self, ctx: &egui::Context) {
        let mut open = self.help_open;
        egui::Window::new("Keyboard shortcuts and mouse")
            .open(&mut open)
            .collapsible(false)
            .resizable(false)
            .show(ctx, |ui| {
                egui::Grid::new("help")
                    .num_columns(3)
                    .striped(true)
                    .show(ui, |ui| {
                        for command in Command::ALL {
                            ui.monospace(command.shortcut_text(ctx));
                            ui.label(command.label());
                            ui.label(command.description());
                            ui.end_row();
                        }
                        for (gesture, what) in [
                            ("Left drag", "Orbit the camera around its target"),
                            ("Shift + left drag, middle drag", "Pan the camera"),
                            ("Ctrl + wheel", "Dolly the camera in and out"),
                            ("Wheel", "Zoom the image around the cursor"),
                            ("Right drag", "Pan the image"),
                        ] {
                            ui.monospace(gesture);
                            ui.label("");
                            ui.label(what);
                            ui.end_row();
                        }
                    });
            });
        self.help_open = open;
    }

    fn central(&mut self, ui: &mut Ui) {
        if let Some(error) = self.error.clone() {
            egui::Frame::new()
                .fill(Color32::from_rgb(90, 20, 20))
                .inner_margin(6.0)
                .show(ui, |ui| {
                    // Long messages (paths, parser context) wrap inside the
                    // panel instead of widening it.
                    ui.set_width(ui.available_width());
                    ui.horizontal(|ui| {
                        ui.label(RichText::new("Error").strong().color(Color32::WHITE));
                        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                            if ui.small_button("Dismiss").clicked() {
                                self.error = None;
                            }
                        });
                    });
                    ui.add(egui::Label::new(RichText::new(&error).color(Color32::WHITE)).wrap());
                });
        }
        self.brute_force_banners(ui);
        let (size, full) = match self.image.shown() {
            Some(s) => (
                [s.width as usize, s.height as usize],
                self.full_size().unwrap_or([s.width, s.height]),
            ),
            None => ([0, 0], self.full_size().unwrap_or([1, 1])),
        };
        if let Some(compare) = &mut self.compare {
            compare_header(
                ui,
                compare,
                &self.state.controls,
                self.engine.scene(),
                self.camera,
            );
        }
        let bottom = 22.0;
        let mut area = ui.available_rect_before_wrap();
        area.max.y -= bottom;
        let flip_held = ui.input(|i| i.key_down(FLIP_KEY));
        let response = ui
            .scope_builder(egui::UiBuilder::new().max_rect(area), |ui| {
                let Some(compare) = &mut self.compare else {
                    return viewport::show(
                        ui,
                        &mut self.view,
                        &self.image.layers(),
                        None,
                        size,
                        full,
                    );
                };
                let b_layers = compare.b_layers(ui.ctx(), (size[0] as u32, size[1] as u32));
                let b = viewport::Layers {
                    textures: b_layers.iter().collect(),
                    opaque: compare.b_is_opaque(),
                };
                match compare.view {
                    CompareView::SideBySide => {
                        let half =
                            egui::vec2(ui.available_width() / 2.0 - 2.0, ui.available_height());
                        ui.horizontal(|ui| {
                            let left = ui
                                .allocate_ui(half, |ui| {
                                    viewport::show(
                                        ui,
                                        &mut self.view,
                                        &self.image.layers(),
                                        None,
                                        size,
                                        full,
                                    )
                                })
                                .inner;
                            let right = ui
                                .allocate_ui(half, |ui| {
                                    viewport::show(ui, &mut self.view, &b, None, size, full)
                                })
                                .inner;
                            left.merge(right)
                        })
                        .inner
                    }
                    CompareView::Split => {
                        let split = b.textures.last().map(|&texture| viewport::SplitWith {
                            texture,
                            at: &mut compare.split,
                        });
                        let a = self.image.layers();
                        viewport::show(ui, &mut self.view, &a, split, size, full)
                    }
                    CompareView::Flip => {
                        let layers = if flip_held { b } else { self.image.layers() };
                        viewport::show(ui, &mut self.view, &layers, None, size, full)
                    }
                    CompareView::Difference => {
                        // A heat map of every pixel: opaque.
                        let textures: Vec<_> = compare.difference().into_iter().collect();
                        let difference = viewport::Layers {
                            opaque: !textures.is_empty(),
                            textures,
                        };
                        viewport::show(ui, &mut self.view, &difference, None, size, full)
                    }
                }
            })
            .inner;
        self.dragging_camera = response.dragging_camera;
        self.hovered_pixel = response.hovered_pixel;
        if let Some(rect) = response.image_rect {
            let visits = self.inspector.eye_visits();
            self.overlay.paint(ui, &self.engine, rect, visits);
            self.inspector.paths_drawn = self.inspector.paint_paths(ui, &self.engine, rect);
        }
        if let Some(pixel) = self.hovered_pixel
            && ui.input(|i| i.pointer.primary_clicked())
        {
            self.inspector.pin(pixel);
        }
        self.apply_gestures(&response.gestures);
        ui.horizontal(|ui| {
            ui.label(self.status_line());
            if let Some(readout) = self.pixel_readout() {
                ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                    ui.monospace(readout);
                });
            }
        });
    }

    /// The slow-render banner of each side that runs brute force over a
    /// large scene; its button switches that side to the BVH.
    fn brute_force_banners(&mut self, ui: &mut Ui) {
        if let (Some(scene), Some(settings)) = (self.engine.scene(), self.engine.settings())
            && accel_banner::show(ui, "", settings, &scene.world.counts)
        {
            self.state.controls.set_accel(AccelChoice::Bvh);
        }
        if let Some(compare) = &mut self.compare
            && compare.reference().is_none()
            && let (Some(scene), Some(settings)) =
                (compare.engine.scene(), compare.engine.settings())
            && accel_banner::show(ui, "B: ", settings, &scene.world.counts)
        {
            compare.controls.set_accel(AccelChoice::Bvh);
        }
    }

    /// The full-resolution size of the current settings.
    fn full_size(&self) -> Option<[u32; 2]> {
        let scene = self.engine.scene()?;
        let s = self
            .state
            .controls
            .render_settings(&scene.scene, self.camera, false);
        Some([s.width, s.height])
    }

    /// Asks for the screenshot of `--screenshot` once it is due.
    fn take_screenshot_when_due(&mut self, ctx: &egui::Context) {
        let Some((plan, _)) = &self.screenshot else {
            return;
        };
        if self.screenshot_requested {
            return;
        }
        let due = match plan.after {
            Some(delay) => {
                let elapsed = self.opened_at.elapsed();
                if elapsed < delay {
                    ctx.request_repaint_after(delay - elapsed);
                }
                elapsed >= delay
            }
            None => {
                !self.engine.is_loading()
                    && (self.error.is_some()
                        || (self.engine.activity() == Activity::Job(JobState::Done)
                            && self.is_display_current()))
            }
        };
        if !due {
            return;
        }
        self.screenshot_requested = true;
        let path = plan.path.clone();
        let shown = self.image.shown().map(screenshot::describe);
        let reply = self.replies.0.clone();
        let wake = ctx.clone();
        ctx.request_screenshot(move |image| {
            let result = screenshot::save(&image, &path)
                .map(|()| match shown {
                    Some(shown) => format!("saved screenshot {} of {shown}", path.display()),
                    None => format!("saved screenshot {}", path.display()),
                })
                .map_err(|e| format!("{e:#}"));
            let _ = reply.send(Reply::Screenshot(result));
            wake.request_repaint();
        });
    }
}

/// "A: grid off", "B: grid on, m = 4": what differs between the sides.
fn compare_labels(
    compare: &Compare,
    controls_a: &Controls,
    scene: Option<&super::engine::LoadedScene>,
    camera: Option<CameraPose>,
) -> Option<(String, String)> {
    let a = controls_a.render_settings(&scene?.scene, camera, false);
    if let Some(reference) = compare.reference() {
        return Some((
            format!("A: {}", crate::measure::describe::describe(&a)),
            reference.label(),
        ));
    }
    let b = compare.settings(camera, false)?;
    Some(compare::labels(&a, &b))
}

/// Hold it to see B in the compare mode's flip view.
const FLIP_KEY: egui::Key = egui::Key::X;

/// Above the images in compare mode: the view, what each side is, and the
/// difference view's gain and legend.
fn compare_header(
    ui: &mut Ui,
    compare: &mut Compare,
    controls_a: &Controls,
    scene: Option<&super::engine::LoadedScene>,
    camera: Option<CameraPose>,
) {
    ui.horizontal(|ui| {
        for view in CompareView::ALL {
            ui.selectable_value(&mut compare.view, view, view.label());
        }
        if compare.view == CompareView::Flip {
            ui.weak("hold X to see B");
        }
    });
    compare.reference_controls(ui, controls_a.encoding());
    if let Some((label_a, label_b)) = compare_labels(compare, controls_a, scene, camera) {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(label_a).strong());
            ui.label("·");
            ui.label(RichText::new(label_b).strong());
        });
    }
    if compare.view == CompareView::Difference {
        compare::difference_controls(ui, compare);
    }
}

/// The bundled showcase scene, or the first bundled scene.
fn default_scene() -> Option<SceneSource> {
    bundled::find(bundled::DEFAULT_SCENE)
        .or(bundled::SCENES.first())
        .map(|s| SceneSource::Bundled(s.name.to_string()))
}

/// `frame` without its fill: the window's clear paints the panels' colour
/// at almost no cost, where a filled panel is a rectangle of fragments that a
/// software rasterizer shades one by one in every frame.
fn unfilled(frame: egui::Frame) -> egui::Frame {
    frame.fill(Color32::TRANSPARENT)
}

impl eframe::App for WorkbenchApp {
    fn ui(&mut self, ui: &mut Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.frame_meter
            .begin(Instant::now(), frame.info().cpu_usage, CpuTimes::now());
        self.engine.collect_retired();
        self.receive(&ctx);
        // Before anything is drawn, so the numbers and the image of a
        // frame describe the same render.
        self.refresh_texture(&ctx);
        self.start_catalog_when_due(&ctx);
        self.take_dropped_files(&ctx);
        let mut commands = Command::pressed(&ctx);

        let title = match self.engine.scene() {
            Some(s) => format!("Whitted Workbench — {}", s.source.label()),
            None => "Whitted Workbench".into(),
        };
        if title != self.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title = title;
        }

        egui::Panel::left("controls")
            .resizable(true)
            .default_size(270.0)
            .frame(unfilled(egui::Frame::side_top_panel(ui.style())))
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    let current = self.engine.scene().map(|s| s.source.clone());
                    if let Some(source) = scene_picker::show(
                        ui,
                        &self.catalog,
                        current.as_ref(),
                        &self.disk_scenes,
                        &self.state.recent,
                        &mut commands,
                    ) {
                        self.open(source);
                    }
                    if let Some(loaded) = self.engine.scene() {
                        ui.small(format!(
                            "{} objects, {} lights",
                            loaded.world.counts.objects(),
                            loaded.world.counts.lights
                        ));
                    }
                    ui.separator();
                    let paused = self.engine.is_paused();
                    controls::command_toggle(
                        ui,
                        self.compare.is_some(),
                        Command::ToggleCompare,
                        &mut commands,
                    );
                    if let Some(compare) = &mut self.compare {
                        ui.horizontal(|ui| {
                            ui.label("Editing");
                            ui.selectable_value(&mut compare.editing_b, false, "A");
                            ui.selectable_value(&mut compare.editing_b, true, "B");
                            controls::command_button(ui, Command::SwapSides, &mut commands);
                            controls::command_button(ui, Command::CopyAToB, &mut commands);
                        });
                    }
                    let controls = match &mut self.compare {
                        Some(compare) if compare.editing_b => &mut compare.controls,
                        _ => &mut self.state.controls,
                    };
                    controls::show(ui, controls, paused, &mut commands);
                    ui.separator();
                    self.views.ui(ui, self.compare.is_some());
                    self.overlay.ui(ui);
                    ui.separator();
                    controls::command_button(ui, Command::ToggleHelp, &mut commands);
                });
            });

        if self.state.show_stats {
            egui::Panel::right("statistics")
                .resizable(true)
                .default_size(280.0)
                .frame(unfilled(egui::Frame::side_top_panel(ui.style())))
                .show(ui, |ui| {
                    egui::ScrollArea::vertical().show(ui, |ui| {
                        if let Some(compare) = &self.compare {
                            ui.heading("Comparison");
                            let labels = compare_labels(
                                compare,
                                &self.state.controls,
                                self.engine.scene(),
                                self.camera,
                            )
                            .unwrap_or_default();
                            compare::show_numbers(ui, self.image.shown(), compare, &labels);
                            ui.separator();
                        }
                        match (self.image.shown(), self.engine.scene()) {
                            (Some(shown), Some(scene)) => {
                                let accel = self.engine.accel_info();
                                stats_panel::show(
                                    ui,
                                    &stats_panel::StatsView {
                                        stats: &shown.stats,
                                        counts: &scene.world.counts,
                                        accel: accel.as_ref(),
                                        load_time: scene.load_time,
                                        frame_meter: &self.frame_meter,
                                    },
                                );
                            }
                            _ => {
                                ui.heading("Statistics");
                                ui.label("Nothing rendered yet.");
                            }
                        }
                    });
                });
        }

        egui::CentralPanel::default()
            .frame(unfilled(egui::Frame::central_panel(ui.style())))
            .show(ui, |ui| self.central(ui));

        if let Some((text, since)) = &self.notice {
            if since.elapsed() < NOTICE_TIME {
                let text = text.clone();
                egui::Area::new(egui::Id::unique("notice"))
                    .anchor(egui::Align2::CENTER_TOP, [0.0, 12.0])
                    .show(&ctx, |ui| {
                        egui::Frame::popup(ui.style()).show(ui, |ui| ui.label(text));
                    });
                ctx.request_repaint_after(NOTICE_TIME - since.elapsed());
            } else {
                self.notice = None;
            }
        }
        self.help_window(&ctx);
        let b = self.compare.as_ref().map(|c| &c.engine);
        self.inspector.update(&self.engine, b);
        self.inspector.window(&ctx, self.compare.is_some());
        self.benchmark_window(&ctx);
        self.studies_window(&ctx);

        for command in commands {
            self.run_command(command);
        }
        self.sync_render(&ctx);
        self.take_screenshot_when_due(&ctx);
        self.frame_meter.end(Instant::now());
        self.progress_pace.set(self.frame_meter.progress_interval());
    }

    /// The panels' colour: the panels leave their fill to the clear.
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        visuals.panel_fill.to_normalized_gamma_f32()
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        eframe::set_value(storage, eframe::APP_KEY, &self.state);
    }
}
