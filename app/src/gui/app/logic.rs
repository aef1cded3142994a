//! A frame's work that draws nothing: taking what arrived before drawing
//! (a loaded scene, dialog replies, dropped files, the sides' new images),
//! and after the commands ran, planning each side's settings and keeping
//! the engines rendering them.

use tracer::render::{JobState, RenderSettings};

use crate::lessons::format::{SceneFiles, parse_lesson};
use crate::load::SceneSource;
use crate::load::is_lesson_file;
use tracer::scene::mesh_io::MeshFormat;

use super::WorkbenchApp;
use super::saving::Reply;
use crate::gui::panels::scene_list;
use crate::gui::platform::{paced_waker, waker};
use crate::gui::sides::Activity;

/// Frames per timed configuration of a report exported from the window:
/// the benchmark window's default, a full report in a few minutes.
const REPORT_RUNS: usize = 3;

impl WorkbenchApp {
    /// Takes finished loads, dialogs, saves and dropped files, uploads the
    /// sides' images and refreshes what the comparison measures of them.
    pub(super) fn take_arrivals(&mut self, ctx: &egui::Context) {
        for side in self.sides.each_mut() {
            side.engine.collect_retired();
        }
        self.take_loaded_scene();
        for reply in self.dialogs.take() {
            match reply {
                Reply::Open(path) => self.open_file(&path),
                Reply::Dropped { path, bytes } => {
                    let lesson = is_lesson_file(&path);
                    self.open_dropped_text(&path, bytes, lesson);
                }
                Reply::Fetched {
                    url,
                    id,
                    for_what,
                    bytes,
                } => self.open_fetched(&url, id, for_what, bytes),
                Reply::LessonFolder(dir) => {
                    self.open_lesson_folder(&dir);
                }
                Reply::Notice(text) => self.messages.notify(text),
                Reply::Error(text) => self.messages.error = Some(text),
                Reply::SceneSaved { side, path, state } => self.scene_saved(side, &path, state),
                Reply::Screenshot(result) => {
                    if let Some(request) = &self.screenshot
                        && let Ok(mut slot) = request.outcome.lock()
                    {
                        *slot = Some(result);
                    }
                    ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                }
            }
        }
        self.take_dropped_files(ctx);
        self.comparison.receive_picked();
        self.refresh_images(ctx);
        self.count_scenes_when_due(ctx);
        self.update_title(ctx);
    }

    /// A scene A finished loading: both sides show it, A's controls adopt
    /// its settings unless the last session is being restored.
    fn take_loaded_scene(&mut self) {
        let Some(result) = self.sides.a.engine.poll_load() else {
            return;
        };
        let loaded = match result {
            Ok(loaded) => loaded.clone(),
            Err(message) => {
                self.messages.error = Some(message);
                return;
            }
        };
        if self.sides.adopt_loaded_scene {
            self.sides.a.controls.adopt_scene(&loaded.scene);
        }
        self.sides.adopt_loaded_scene = true;
        self.sides.follow_scene(&loaded);
        self.comparison.forget_results();
        self.sides.a.image.forget();
        self.navigation.reset();
        self.messages.scene_loaded();
        if let SceneSource::File(path) = &loaded.source {
            self.session.remember(path.clone());
        }
        self.session.last_scene = Some(loaded.source.clone());
        self.finish_lesson_setup(&loaded.source);
        self.finish_link(&loaded.source);
        if !loaded.world.warnings.is_empty() {
            self.messages.notify(loaded.world.warnings.join("; "));
        }
    }

    /// Opens a file the user picked or dropped: a lesson in the Lessons
    /// window (its first step set up), anything else as a scene, so a
    /// teacher's lesson opens the way a scene does.
    fn open_file(&mut self, path: &std::path::Path) {
        if is_lesson_file(path) {
            self.open_lesson(path);
        } else {
            self.open(SceneSource::File(path.to_path_buf()));
        }
    }

    /// Opens scene files and lessons dropped on the window.
    fn take_dropped_files(&mut self, ctx: &egui::Context) {
        let dropped = ctx.input(|i| i.raw.dropped_files.clone());
        for file in dropped {
            let path = file.path();
            if scene_list::is_scene_file(path) || is_lesson_file(path) {
                if path.is_file() {
                    self.open_file(path);
                } else {
                    self.dialogs.read_dropped(file, ctx);
                }
                return;
            }
            self.messages.notify(format!(
                "{} is not a scene, mesh or lesson file (.p3f, .nff, .obj, .ply, .toml)",
                path.display()
            ));
        }
    }

    /// Opens a dropped file that is no file on disk (the web page's: its
    /// name `path` and its `bytes`, once read), or a file a link fetched
    /// (its URL), from its text: a `lesson` as a lesson file opens,
    /// otherwise a scene under its name. A bare mesh is read from disk
    /// only.
    pub(super) fn open_dropped_text(
        &mut self,
        path: &std::path::Path,
        bytes: Result<Vec<u8>, String>,
        lesson: bool,
    ) {
        let name = path.display().to_string();
        if MeshFormat::of(path).is_some() {
            let e = format!("{name}: a mesh opens from a file on disk, in the desktop workbench");
            return self.messages.lasting_error(e);
        }
        let text = match bytes.map(String::from_utf8) {
            Ok(Ok(text)) => text,
            Ok(Err(_)) => {
                let e = format!("{name} is not text: drop a .p3f, .nff or lesson .toml file");
                return self.messages.lasting_error(e);
            }
            Err(e) => {
                return self
                    .messages
                    .lasting_error(format!("cannot read {name}: {e}"));
            }
        };
        if lesson {
            let stem = path.file_stem().unwrap_or_default().to_string_lossy();
            let lesson = parse_lesson(&text, &stem, &name, SceneFiles::Nowhere);
            self.set_up_lesson(lesson);
        } else {
            self.open(SceneSource::Written { name, text });
        }
    }

    /// Uploads each side's image at the progress pace (as the chosen view,
    /// on one scale for both sides), then what the comparison measures.
    fn refresh_images(&mut self, ctx: &egui::Context) {
        let b = self.sides.b.as_ref().map(|b| &b.engine);
        let shown = self.tools.views.fit(ctx, &self.sides.a.engine, b);
        let interval = self.pacing.progress_pace.get();
        for side in self.sides.each_mut() {
            side.refresh(ctx, interval, shown);
        }
        if let Some(b) = &self.sides.b {
            let view = shown.map(|(view, _)| view);
            self.comparison.refresh(ctx, &self.sides.a, b, view);
        }
        self.observer.refresh(ctx, &self.sides.a, interval);
    }

    /// Starts counting the bundled scenes for the list once A's first
    /// render no longer needs the machine.
    fn count_scenes_when_due(&mut self, ctx: &egui::Context) {
        let a = &self.sides.a.engine;
        // A scene just loaded renders later in this frame.
        let busy = match a.activity() {
            Activity::Loading { .. } | Activity::Job(JobState::Building | JobState::Rendering) => {
                true
            }
            Activity::Idle => a.scene().is_some(),
            Activity::Job(_) => false,
        };
        let wake = paced_waker(ctx, &self.pacing.progress_pace);
        self.scene_list.count_when_due(busy, wake);
    }

    fn update_title(&mut self, ctx: &egui::Context) {
        let edited = if self.sides.each().any(|s| s.history.is_modified()) {
            " *"
        } else {
            ""
        };
        let title = match self.sides.a.engine.scene() {
            Some(s) => format!("Whitted Workbench — {}{edited}", s.source.label()),
            None => "Whitted Workbench".into(),
        };
        if title != self.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title = title;
        }
    }

    /// Plans each side's settings for this frame (after the commands ran)
    /// and keeps its engine rendering them; B renders nothing while it is
    /// an image.
    pub(super) fn keep_rendering(&mut self, ctx: &egui::Context) {
        let (camera, moving) = (self.navigation.camera, self.navigation.is_camera_moving());
        let views = self.tools.views.measures();
        let b_is_image = self.comparison.reference().is_some();
        // B at A's cost: A's budget once A is done (`Some(None)` before).
        let a = &self.sides.a.engine;
        let a_cost = self
            .comparison
            .b_matches
            .filter(|_| !b_is_image)
            .map(|matches| {
                (a.activity() == Activity::Job(JobState::Done))
                    .then(|| a.stats())
                    .flatten()
                    .map(|stats| matches.budget(&stats))
            });
        for side in self.sides.each_mut() {
            let is_b = side.id == crate::gui::sides::SideId::B;
            if is_b && a_cost.is_some() {
                side.make_adaptive();
            }
            side.plan(camera, moving);
            if is_b && b_is_image {
                continue;
            }
            if let (true, Some(cost)) = (is_b, a_cost) {
                // B waits for A: it renders alone, after A, at A's cost.
                let Some(budget) = cost else {
                    continue;
                };
                side.limit(budget);
            }
            if let Err(e) = side.render(views) {
                self.messages.error = Some(e);
            }
        }
        self.keep_observing(ctx);
        if let Some(failure) = self.sides.a.engine.take_failure() {
            self.messages.error = Some(format!(
                "the render failed: {failure}. The image so far stays; change a setting or \
                 press R to render again"
            ));
        }
        self.navigation.wake_when_settled(ctx);
        if let Some(request) = &mut self.screenshot {
            let error = self.messages.error.is_some();
            request.take_when_due(ctx, &self.sides.a, error, &self.dialogs);
        }
    }

    /// Keeps the observer rendering A's scene from its camera, its trees
    /// those of the pinned pixel (and pattern) on each side, its animation
    /// moving.
    fn keep_observing(&mut self, ctx: &egui::Context) {
        let sides: Vec<&crate::gui::sides::Side> = self
            .sides
            .each()
            .filter(|s| {
                s.id == crate::gui::sides::SideId::A || self.comparison.reference().is_none()
            })
            .collect();
        let inspector = &self.tools.inspector;
        self.observer
            .record(&sides, inspector.pinned, inspector.sample);
        if let Err(e) = self.observer.sync(&self.sides.a) {
            self.messages.error = Some(format!("the observer view: {e}"));
        }
        if self
            .observer
            .animation
            .advance(self.clock.now(), self.observer.phases())
        {
            ctx.request_repaint();
        }
    }

    /// The benchmark matrix window, started on the current scene, camera
    /// and size.
    pub(super) fn benchmark_window(&mut self, ctx: &egui::Context) {
        let bench = &mut self.tools.bench;
        bench.receive(ctx);
        if !bench.open {
            return;
        }
        let a = &self.sides.a;
        let name = a
            .engine
            .scene()
            .map_or_else(|| "no scene".into(), |s| s.source.label());
        let mut start = false;
        bench.show(ctx, &name, &mut start);
        if start && let (Some(scene), Some(base)) = (a.engine.scene(), a.settings()) {
            bench.start(scene.world.clone(), base, waker(ctx));
        }
    }

    /// Export report...: once a file is chosen, the lab report of side A's
    /// scene (with its edits), camera and settings, measured in the
    /// background; its progress and Cancel in a window.
    pub(super) fn report_window(&mut self, ctx: &egui::Context) {
        let report = &mut self.tools.report;
        report.receive();
        if let Some(path) = report.chosen() {
            match self.report_request() {
                Some(request) => {
                    self.tools.report.start(request, path, waker(ctx));
                }
                None => {
                    self.tools.report.message = Some("report not exported: no scene is open".into())
                }
            }
        }
        self.tools.report.show(ctx);
    }

    /// The lab report's request for side A as it is now: its scene with
    /// the edits made, its camera and settings (N the course's 4).
    pub(crate) fn report_request(&self) -> Option<crate::reports::lab::Request> {
        let a = &self.sides.a;
        let (scene, settings) = (a.engine.scene()?, a.settings()?);
        Some(crate::reports::lab::Request {
            scene_name: scene.source.label(),
            scene: std::sync::Arc::new(scene.scene.clone()),
            world: scene.world.clone(),
            base: RenderSettings {
                samples: crate::measure::benchmark::MATRIX_SAMPLES,
                ..settings.clone()
            },
            edits: a.history.describe(&scene.scene),
            runs: REPORT_RUNS,
            threads: None,
            encoding: tracer::render::Encoding::Srgb,
            pixel: None,
            quick: false,
        })
    }

    /// The Studies window, started on the current scene, camera and size;
    /// a point the user picks is shown in the main view.
    pub(super) fn studies_window(&mut self, ctx: &egui::Context) {
        let studies = &mut self.tools.studies;
        studies.receive(ctx);
        if !studies.open {
            return;
        }
        let a = &self.sides.a;
        let base = a.settings().cloned().unwrap_or_default();
        let mut start = false;
        let applied = studies.show(ctx, &base, &mut start);
        if start {
            let scene = a.engine.scene();
            let name = scene.map_or_else(String::new, |s| s.source.label());
            studies.start(
                scene.map(|s| s.world.clone()),
                &base,
                &a.controls,
                &name,
                waker(ctx),
            );
        }
        if let Some((param, points, subject)) = studies.chart_to_save()
            && !self.dialogs.save_study_chart(param, points, &subject)
        {
            self.messages.notify("cannot open a file dialog");
        }
        if let Some(applied) = applied {
            self.apply_study_point(&applied);
        }
    }
}
