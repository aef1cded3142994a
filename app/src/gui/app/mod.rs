//! The workbench window: the two sides and what surrounds them. A frame
//! takes what arrived (loads, dialogs, images: [`logic`]), draws the
//! panels and windows, which record what the user asked as [`Command`]s,
//! runs those ([`command_handling`]), then plans each side's settings and
//! keeps the engines rendering them.

mod command_handling;
mod editing;
mod lesson_fetch;
mod lessons;
mod linking;
mod logic;
mod messages;
mod navigation;
mod persisted;
pub(crate) mod saving;
mod testing;

pub use saving::{FileDialog, FileQuestion};

use crate::bundled;
use crate::load::SceneSource;

use super::commands::Command;
use super::comparison::Comparison;
use super::editor;
use super::lessons::Lessons;
use super::observer::Observer;
use super::panels::scene_list::{Picked, SceneList};
use super::panels::side_panel::{self, SidePanelView};
use super::panels::{central, stats, unfilled};
use super::platform::clock::Clock;
use super::platform::frame_meter::Pacing;
use super::platform::screenshot::{ScreenshotOutcome, ScreenshotPlan};
use super::sides::{RepaintWakers, SideId, Sides};
use super::windows::{ToolsAndOverlays, help};
use messages::Messages;
use navigation::Navigation;
use persisted::Session;
use saving::{Dialogs, ScreenshotRequest};

/// The window's state: the sides and everything around them.
pub struct WorkbenchApp {
    sides: Sides,
    comparison: Comparison,
    navigation: Navigation,
    tools: ToolsAndOverlays,
    session: Session,
    scene_list: SceneList,
    messages: Messages,
    dialogs: Dialogs,
    pacing: Pacing,
    /// The scene seen from outside.
    observer: Observer,
    /// The title last given to the window, to send it only when it changes
    /// (every viewport command asks for one more frame).
    title: String,
    screenshot: Option<ScreenshotRequest>,
    /// Times what the window times itself (notices, undo steps, the
    /// observer's animation).
    clock: Clock,
    /// The Lessons panel: lessons, steps, checks, progress.
    lessons: Lessons,
    /// A lesson step being set up, waiting for its scene.
    pending_setup: Option<lessons::PendingSetup>,
    /// The lesson progress as last saved: a change is saved at the next
    /// frame, not at the next periodic save, so a closed tab or a crash
    /// loses no step done.
    progress_saved: crate::lessons::progress::Record,
    /// A link's settings and edits, waiting for its scene.
    pending_link: Option<linking::PendingLink>,
    /// Lessons a link is fetching, with their scene files.
    lesson_fetch: Option<lesson_fetch::LessonFetch>,
    /// The files links fetched, for Copy link.
    fetched: linking::Fetched,
}

/// How often the rest of the saved state is saved (eframe's default).
const AUTO_SAVE: std::time::Duration = std::time::Duration::from_secs(30);

impl WorkbenchApp {
    /// Creates the app, restoring the saved state when `storage` has one,
    /// and starts loading `initial` (or the last scene, or the bundled
    /// default).
    pub(crate) fn new(
        ctx: &egui::Context,
        storage: Option<&dyn eframe::Storage>,
        initial: Option<SceneSource>,
    ) -> Self {
        Self::with_clock(ctx, storage, initial, Clock::wall())
    }

    /// [`WorkbenchApp::new`] timing what it times itself by `clock`: a
    /// test gives it a stopped clock and moves it.
    pub fn with_clock(
        ctx: &egui::Context,
        storage: Option<&dyn eframe::Storage>,
        initial: Option<SceneSource>,
        clock: Clock,
    ) -> Self {
        let (controls, session, progress) = persisted::restore(storage);
        let pacing = Pacing::default();
        let wakes = RepaintWakers::of(ctx, &pacing.progress_pace);
        let mut app = Self {
            observer: Observer::new(&wakes),
            sides: Sides::new(controls, wakes, clock.clone()),
            comparison: Comparison::default(),
            navigation: Navigation::default(),
            tools: ToolsAndOverlays::default(),
            session,
            scene_list: SceneList::new(clock.clone()),
            messages: Messages::new(clock.clone()),
            dialogs: Dialogs::default(),
            pacing,
            title: String::new(),
            screenshot: None,
            clock,
            lessons: Lessons::default(),
            pending_setup: None,
            progress_saved: progress.clone(),
            pending_link: None,
            lesson_fetch: None,
            fetched: linking::Fetched::default(),
        };
        app.lessons.progress = progress;
        let last_scene = match app.session.last_scene.clone() {
            Some(SceneSource::File(path)) if initial.is_none() && !path.exists() => {
                app.messages.notify(format!(
                    "{} is gone: the last scene of the previous session was moved or deleted",
                    path.display()
                ));
                None
            }
            last => last,
        };
        // Restoring the last session keeps the saved controls.
        let restoring = initial.is_none() && last_scene.is_some();
        let first = initial.or(last_scene).or_else(default_scene);
        // A scene beside the page, remembered by name: fetched again.
        let on_site = match &first {
            Some(SceneSource::Bundled(name)) => bundled::site_scene(name),
            _ => None,
        };
        if let Some(scene) = on_site {
            app.fetch_site_scene(scene);
        } else if let Some(source) = first {
            app.sides.adopt_loaded_scene = !restoring;
            app.sides.a.engine.load(source);
        }
        app
    }

    /// Takes a screenshot as `plan` says, reports it in `outcome` and closes
    /// the window.
    pub(crate) fn with_screenshot(
        mut self,
        plan: ScreenshotPlan,
        outcome: ScreenshotOutcome,
    ) -> Self {
        self.screenshot = Some(ScreenshotRequest::new(plan, outcome));
        self
    }

    /// Whether a scene is being fetched, or a side's or the observer's
    /// engine is loading a scene or rendering: the web page, which its
    /// workers cannot wake, keeps looking while so.
    #[cfg(target_family = "wasm")]
    pub(crate) fn is_rendering(&self) -> bool {
        use super::sides::Activity;
        use tracer::render::JobState;
        if self.fetched.scene().is_some() {
            return true;
        }
        let sides = self.sides.each().map(|side| &side.engine);
        sides.chain([self.observer.engine()]).any(|engine| {
            matches!(
                engine.activity(),
                Activity::Loading { .. } | Activity::Job(JobState::Building | JobState::Rendering)
            )
        })
    }

    /// Turns the observer view on or off, as O does.
    pub(crate) fn show_observer(&mut self, on: bool) {
        self.observer.on = on;
    }

    /// Opens a scene as the user would: first asking, when edits are
    /// unsaved, whether to throw them away.
    pub fn open(&mut self, source: SceneSource) {
        // The last scene asked for wins over one still being fetched.
        self.cancel_scene_fetch();
        self.open_or_ask(editor::Pending::Open(source));
    }

    /// Starts loading `source`, which A's controls adopt.
    fn open_now(&mut self, source: SceneSource) {
        self.sides.adopt_loaded_scene = true;
        self.sides.a.engine.load(source);
    }

    /// Reads the current scene file again, keeping the controls.
    fn reload_now(&mut self) {
        match self.session.last_scene.clone() {
            Some(source) => {
                self.sides.adopt_loaded_scene = false;
                self.sides.a.engine.load(source);
            }
            None => self.messages.notify("no scene to reload"),
        }
    }

    /// The side panel: scene, settings of the side being edited, views.
    fn side_panel(&mut self, ui: &mut egui::Ui, commands: &mut Vec<Command>) {
        let Sides { a, b, editing, .. } = &mut self.sides;
        let current = a.engine.scene().map(|s| s.source.clone());
        let counts = a.engine.scene().map(|s| s.world.counts.clone());
        let paused = a.engine.is_paused();
        let comparing = b.is_some();
        let (controls, engine) = match (b, *editing) {
            (Some(b), SideId::B) => (&mut b.controls, &b.engine),
            _ => (&mut a.controls, &a.engine),
        };
        let view = SidePanelView {
            scene_view: engine.scene().map(|s| &s.scene.view),
            scene_list: &self.scene_list,
            current: current.as_ref(),
            recent: &self.session.recent,
            fetching: self.fetched.scene().map(|f| (f.url.as_str(), &f.transfer)),
            counts: counts.as_ref(),
            editing: comparing.then_some(editing),
            controls,
            paused,
            views: &mut self.tools.views,
            overlay: &mut self.tools.overlay,
            active: &mut self.tools.active,
            observer: &mut self.observer,
        };
        let mut picked = None;
        egui::Panel::left("controls")
            .resizable(true)
            .default_size(270.0)
            .frame(unfilled(egui::Frame::side_top_panel(ui.style())))
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    picked = side_panel::show(ui, view, commands);
                });
            });
        match picked {
            Some(Picked::Scene(source)) => self.open(source),
            Some(Picked::Site(scene)) => self.fetch_site_scene(scene),
            None => {}
        }
    }

    fn statistics_panel(&mut self, ui: &mut egui::Ui) {
        if !self.session.show_stats {
            return;
        }
        egui::Panel::right("statistics")
            .resizable(true)
            .default_size(280.0)
            .frame(unfilled(egui::Frame::side_top_panel(ui.style())))
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| {
                    stats::panel(ui, &self.sides, &self.comparison, &self.pacing.frame_meter);
                });
            });
    }

    fn central_panel(&mut self, ui: &mut egui::Ui) {
        let moving = self.navigation.is_camera_moving();
        let view = central::CentralView {
            sides: &self.sides,
            comparison: &mut self.comparison,
            placement: &mut self.navigation.placement,
            tools: &mut self.tools,
            error: &mut self.messages.error,
            moving,
            observer: &mut self.observer,
        };
        let mut outcome = egui::CentralPanel::default()
            .frame(unfilled(egui::Frame::central_panel(ui.style())))
            .show(ui, |ui| central::show(ui, view))
            .inner;
        if let Some(request) = &mut self.screenshot {
            request.saw_image_at(outcome.viewport.image_rect);
        }
        self.move_selected(&mut outcome.viewport);
        self.apply_observer_edits(outcome.observer_edits);
        let scene = self.sides.a.engine.scene().map(|s| &s.scene);
        self.navigation.take(&outcome.viewport, scene);
        for id in outcome.switch_to_bvh {
            if let Some(side) = self.sides.each_mut().find(|s| s.id == id) {
                side.controls.set_accel(tracer::accel::AccelKind::Bvh);
            }
        }
    }

    /// The windows over the image: help, the editor, benchmark, studies.
    fn tool_windows(&mut self, ctx: &egui::Context, commands: &mut Vec<Command>) {
        help::window(ctx, &mut self.tools.help_open);
        self.editor_window(ctx, commands);
        self.benchmark_window(ctx);
        self.report_window(ctx);
        self.studies_window(ctx);
    }
}

/// The bundled showcase scene, or the first bundled scene.
fn default_scene() -> Option<SceneSource> {
    bundled::find(bundled::DEFAULT_SCENE)
        .or(bundled::SCENES.first())
        .map(|s| SceneSource::Bundled(s.name.to_string()))
}

impl eframe::App for WorkbenchApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.pacing.begin(frame.info().cpu_usage);
        // Before anything is drawn, so the numbers and the image of a
        // frame describe the same render.
        self.take_arrivals(&ctx);
        let mut commands = Command::pressed(&ctx);
        self.side_panel(ui, &mut commands);
        self.statistics_panel(ui);
        self.lessons_panel(ui);
        let b = self.sides.b.as_ref();
        self.tools.inspector.update(&self.sides.a, b);
        self.tools.inspector.panel(ui, b.is_some());
        self.central_panel(ui);
        self.messages.show_notice(&ctx);
        self.tool_windows(&ctx, &mut commands);
        for command in commands {
            self.run_command(command, &ctx);
        }
        self.keep_rendering(&ctx);
        self.pacing.end();
    }

    /// The panels' colour: the panels leave their fill to the clear.
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        visuals.panel_fill.to_normalized_gamma_f32()
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        persisted::save(
            storage,
            &self.sides.a.controls,
            &self.session,
            &self.lessons.progress,
        );
        self.progress_saved.clone_from(&self.lessons.progress);
    }

    /// At once while the lesson progress has changed since it was saved
    /// (a step done, a note, the student's name).
    fn auto_save_interval(&self) -> std::time::Duration {
        if self.lessons.progress == self.progress_saved {
            AUTO_SAVE
        } else {
            std::time::Duration::ZERO
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_scene_is_bundled() {
        assert_eq!(
            default_scene(),
            Some(SceneSource::Bundled(bundled::DEFAULT_SCENE.into()))
        );
    }
}
