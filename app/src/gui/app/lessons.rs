//! The Lessons panel's part of the frame: the current step's check kept
//! evaluated against the window's real state (both sides' scenes and
//! settings, the pinned pixel, the layout), and "Set up this step", which
//! opens the step's scene, settings and layout as `lesson check` replays
//! them.

use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::Path;
use std::sync::Arc;

use anyhow::Result;
use tracer::render::{RenderSettings, View};
use tracer::scene::Scene;

use super::WorkbenchApp;
use crate::gui::comparison::Comparison;
use crate::gui::lessons;
use crate::gui::platform::{target, waker};
use crate::gui::sides::{Controls, Side, Sides};
use crate::lessons::format::{Lesson, LessonErrors, read_bundled, read_lesson_file};
use crate::lessons::replay::{open_scene, state_at_step};
use crate::lessons::state::Layout;
use crate::lessons::state::{LessonState, SideState};
use crate::load::Loaded;
use crate::load::SceneSource;

/// A step set up, waiting for its scene to load.
pub(super) struct PendingSetup {
    source: SceneSource,
    state: LessonState,
}

impl WorkbenchApp {
    /// Opens the lesson file `path` in the Lessons panel and sets up its
    /// first step (a dropped or opened file).
    pub(crate) fn open_lesson(&mut self, path: &Path) {
        self.set_up_lesson(read_lesson_file(path));
    }

    /// Opens `workbench --lesson`'s argument: a lesson file, or a bundled
    /// lesson's name as `workbench lesson check` takes it.
    pub fn open_lesson_argument(&mut self, name_or_file: &Path) {
        match crate::lessons::bundled::read_name_or_file(name_or_file) {
            Ok(lesson) => self.set_up_lesson(Ok(lesson)),
            Err(e) => self.messages.lasting_error(format!("{e:#}")),
        }
    }

    /// Opens the bundled lesson `name` as [`Self::open_lesson`] opens a
    /// file (a page's `?lesson=NAME&step=N`), at `step` (from 1) if given;
    /// an unknown name is said with the names there are.
    pub(crate) fn open_bundled_lesson(&mut self, name: &str, step: Option<usize>) {
        match crate::lessons::bundled::find(name) {
            Some(bundled) => self.set_up_lesson_at(read_bundled(bundled), step),
            None => self.messages.lasting_error(format!(
                "no bundled lesson is called {name:?}: the lessons are {}",
                crate::lessons::bundled::names().join(", ")
            )),
        }
    }

    /// Shows `lesson` in the Lessons panel with its first step not done
    /// set up, or says why it does not read.
    pub(super) fn set_up_lesson(&mut self, lesson: Result<Lesson, LessonErrors>) {
        self.set_up_lesson_at(lesson, None);
    }

    /// [`Self::set_up_lesson`] at `step` (from 1, as a link counts them)
    /// when given; a step the lesson does not have is said.
    pub(super) fn set_up_lesson_at(
        &mut self,
        lesson: Result<Lesson, LessonErrors>,
        step: Option<usize>,
    ) {
        match lesson {
            Ok(lesson) => {
                let (name, steps) = (lesson.name.clone(), lesson.steps.len());
                self.lessons.add(lesson);
                self.lessons.open = true;
                match step {
                    Some(step) if step > steps => self.messages.lasting_error(format!(
                        "lesson {name} has {steps} steps, not a step {step}"
                    )),
                    Some(step) => self.lessons.go_to(step - 1),
                    None => {}
                }
                self.set_up_lesson_step();
            }
            Err(e) => self.messages.lasting_error(e.to_string()),
        }
    }

    /// Opens the lessons of folder `dir` as a class does
    /// (`workbench --lesson-folder DIR`): listed, and the folder's first
    /// lesson set up at its first step not done.
    pub(crate) fn open_class(&mut self, dir: &Path) {
        if self.open_lesson_folder(dir) {
            self.set_up_lesson_step();
        }
    }

    /// Adds the lessons of folder `dir` to the Lessons panel's list (the
    /// "Lesson folder..." button), opens it on the folder's first lesson,
    /// and says whether the folder gave any; the files that do not read
    /// are said, the others still listed.
    pub fn open_lesson_folder(&mut self, dir: &Path) -> bool {
        match crate::lessons::folder::read(dir) {
            Ok(read) => {
                self.add_lessons(read.into_iter().map(|(_, l)| l.map_err(|e| e.to_string())))
            }
            Err(e) => {
                self.messages.lasting_error(format!("{e:#}"));
                false
            }
        }
    }

    /// Adds a folder's lessons, each read or why not, to the Lessons
    /// panel's list, opens it on the folder's first, says the files that
    /// do not read, and says whether any did.
    pub(super) fn add_lessons(
        &mut self,
        read: impl IntoIterator<Item = Result<Lesson, String>>,
    ) -> bool {
        let mut problems = Vec::new();
        let mut lessons = Vec::new();
        for lesson in read {
            match lesson {
                Ok(lesson) => lessons.push(lesson),
                Err(e) => problems.push(e),
            }
        }
        let any = !lessons.is_empty();
        self.lessons.add_folder(lessons);
        self.lessons.open = true;
        if !problems.is_empty() {
            self.messages.lasting_error(problems.join("\n"));
        }
        any
    }

    /// The Lessons panel, what it asked for, and the check kept current.
    pub(super) fn lessons_panel(&mut self, ui: &mut egui::Ui) {
        if !self.lessons.open {
            return;
        }
        let ctx = ui.ctx().clone();
        let asked = lessons::show(ui, &mut self.lessons);
        if asked.set_up {
            self.set_up_lesson_step();
        }
        if asked.folder && !self.dialogs.open_lesson_folder() {
            self.messages.notify("cannot open a file dialog");
        }
        if asked.export && !self.dialogs.save_progress(self.lessons.progress.export()) {
            self.messages.notify("cannot open a file dialog");
        }
        let looked_at = self.looked_at();
        let (sides, tools, observer) = (&self.sides, &self.tools, &self.observer);
        let layout = Layout {
            view: (tools.views.view != View::Shaded).then_some(tools.views.view),
            observer: observer.on,
        };
        self.lessons.keep_checking(
            looked_at,
            || window_state(sides, tools.inspector.pinned, layout),
            waker(&ctx),
        );
    }

    /// What a check may look at, fingerprinted: each side's settings and
    /// scene (its world's address: an edit or a load makes another), the
    /// pinned pixel, the view, the observer.
    fn looked_at(&self) -> u64 {
        let mut hasher = DefaultHasher::new();
        for side in self.sides.each() {
            format!("{:?}", side.settings()).hash(&mut hasher);
            side.engine
                .scene()
                .map(|s| Arc::as_ptr(&s.world) as usize)
                .hash(&mut hasher);
        }
        (self.tools.inspector.pinned, self.observer.on).hash(&mut hasher);
        self.tools.views.view.name().hash(&mut hasher);
        hasher.finish()
    }

    /// Replays the lesson up to the current step and opens the result: its
    /// scene (written as P3F under the lesson's name, edits included:
    /// `target::lesson_scene`), then, once loaded, its settings, compare
    /// mode, pixel and layout.
    pub(super) fn set_up_lesson_step(&mut self) {
        let Some(lesson) = self.lessons.lesson().cloned() else {
            return;
        };
        let step = self.lessons.step();
        let prepared = (|| -> Result<PendingSetup> {
            let (scene, world) = open_scene(&lesson)?;
            let state = state_at_step(&lesson, &scene, &world, step)?;
            let source = target::lesson_scene(&lesson.name, &shown_scene(&state.a))?;
            Ok(PendingSetup { source, state })
        })();
        match prepared {
            Ok(setup) => {
                let source = setup.source.clone();
                self.pending_setup = Some(setup);
                self.open(source);
            }
            Err(e) => self.messages.lasting_error(format!("{e:#}")),
        }
    }

    /// Once the set-up step's scene has loaded: its settings on each side
    /// (at full scale: the lesson's pixels are the image's), compare mode
    /// on or off, B's scene when the lesson made it differ from A's, the pinned pixel, the view and the observer. The lesson's
    /// scene file is not a recent file of the user's.
    pub(super) fn finish_lesson_setup(&mut self, loaded: &SceneSource) {
        let Some(setup) = self.pending_setup.take() else {
            return;
        };
        if *loaded != setup.source {
            return;
        }
        if let SceneSource::File(path) = &setup.source {
            self.session.recent.retain(|p| p != path);
        }
        let state = setup.state;
        // A shows the replay's scene: the file written for it, but with its
        // objects where the teacher wrote them, so that the ray tree and
        // the editor name the lesson's lines, not the written file's.
        show_replayed(&mut self.sides.a, &state.a);
        adopt(&mut self.sides.a.controls, &state.a.settings);
        if state.b.is_some() != self.sides.b.is_some() {
            self.sides.toggle_b();
            self.comparison = Comparison::default();
        }
        if let (Some(b), Some(side)) = (&state.b, &mut self.sides.b) {
            adopt(&mut side.controls, &b.settings);
            // B's own edits, or A's since compare mode began, make B's scene
            // another than A's: B shows it as the replay left it.
            if !Arc::ptr_eq(&b.world, &state.a.world) {
                show_replayed(side, b);
            }
        }
        self.tools.inspector.pinned = state.pixel;
        self.tools.views.view = state.layout.view.unwrap_or(View::Shaded);
        self.observer.on = state.layout.observer;
        self.navigation.camera = None;
    }
}

/// Shows the replay's scene and world of `replayed` on `side` in place of
/// the ones its scene file loaded, under the same source.
fn show_replayed(side: &mut Side, replayed: &SideState) {
    let Some(shown) = side.engine.scene() else {
        return;
    };
    let scene = Loaded {
        source: shown.source.clone(),
        scene: shown_scene(replayed),
        world: replayed.world.clone(),
        load_time: shown.load_time,
    };
    side.engine.show(scene);
    side.image.forget();
}

/// The scene a side shows for `replayed`: its camera at the settings'
/// resolution, as a lesson's settings may change it.
fn shown_scene(replayed: &SideState) -> Scene {
    let mut scene = replayed.scene.clone();
    scene.view.width = replayed.settings.width;
    scene.view.height = replayed.settings.height;
    scene
}

/// `settings` as a side's controls, at full resolution.
fn adopt(controls: &mut Controls, settings: &RenderSettings) {
    controls.render = RenderSettings {
        camera: None,
        ..settings.clone()
    };
    controls.resolution_scale = 1.0;
    controls.set_accel(settings.accel);
}

/// The window's state as a check sees it; `None` until A's scene is loaded
/// and planned (and B's, in compare mode).
fn window_state(sides: &Sides, pixel: Option<(u32, u32)>, layout: Layout) -> Option<LessonState> {
    let side = |s: &Side| -> Option<SideState> {
        let loaded = s.engine.scene()?;
        Some(SideState {
            scene: loaded.scene.clone(),
            world: loaded.world.clone(),
            // A check renders a side to its end (a measurement, the
            // samples a pixel took): "keep refining" would have none.
            settings: RenderSettings {
                keep_refining: false,
                ..s.settings()?.clone()
            },
        })
    };
    let b = match &sides.b {
        Some(b) => Some(side(b)?),
        None => None,
    };
    Some(LessonState {
        a: side(&sides.a)?,
        b,
        pixel,
        answer: None,
        layout,
    })
}
