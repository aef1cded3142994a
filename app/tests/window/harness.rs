//! What the window's kittest suites share: the one way to build a window
//! ([`window`]), waiting on it, drawing it, the broken scene a user
//! drops on it, and the file dialogs answered as a test says ([`Answers`]).

use std::cell::RefCell;
use std::collections::VecDeque;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Instant;

use egui_kittest::kittest::Queryable;
use egui_kittest::{Harness, HarnessBuilder};
use tracer::render::JobState;
use tracer::waiting::PATIENCE;
use workbench::gui::{Activity, Clock, FileDialog, FileQuestion, WorkbenchApp};
use workbench::load::SceneSource;

use crate::support::Scratch;

thread_local! {
    /// This test's turn at the window ([`one_window_at_a_time`]).
    static TURN: RefCell<Option<MutexGuard<'static, ()>>> = const { RefCell::new(None) };
}

/// Makes the calling test wait its turn for the window: one test's
/// window at a time, in a process whose tests otherwise run in parallel.
/// Each window renders its scene on every core and draws itself with
/// Mesa's software rasterizer, and two such windows at once on two cores
/// now and then kept a draw from finishing within egui_kittest's 10 s
/// (`PollError`, one run in four of the suite); taking turns, the suite
/// also runs faster (about 25 s instead of 33). The turn lasts until the
/// test's thread ends; a thread that already has it keeps it (libtest
/// may run every test on one thread). Only [`window`] calls it, and
/// [`wait_for`] checks it was called.
fn one_window_at_a_time() {
    static WINDOW_TURN: Mutex<()> = Mutex::new(());
    TURN.with(|held| {
        let mut held = held.borrow_mut();
        if held.is_none() {
            *held = Some(WINDOW_TURN.lock().unwrap_or_else(PoisonError::into_inner));
        }
    });
}

/// Every test's window, built here only: it takes its turn
/// ([`one_window_at_a_time`]), times what it times itself (a notice's
/// fade, undo merging, the observer's animation) by a stopped clock the
/// test moves ([`Clock::advance`] through [`WorkbenchApp::clock`]), and
/// counts its scene list at normal priority, so that no assertion depends
/// on how fast frames come or on an idle thread getting a core. `storage`
/// stands for eframe's saved state.
pub fn window(
    builder: HarnessBuilder<WorkbenchApp>,
    storage: Option<Box<dyn eframe::Storage>>,
    initial: Option<SceneSource>,
) -> Harness<'static, WorkbenchApp> {
    one_window_at_a_time();
    builder.build_eframe(move |cc| {
        let mut app =
            WorkbenchApp::with_clock(&cc.egui_ctx, storage.as_deref(), initial, Clock::stopped());
        app.count_scenes_at_normal_priority();
        app
    })
}

/// Draws the window with wgpu (a harness built `.wgpu()`). Mesa's
/// software rasterizer beside a build on two cores may miss
/// egui_kittest's fixed 10 s wait for a draw (`PollError`); the draw is
/// then tried again, within [`PATIENCE`], as the GPU work it waited for
/// goes on regardless.
pub fn drawn(harness: &mut Harness<'static, WorkbenchApp>) -> image::RgbaImage {
    let start = Instant::now();
    loop {
        match harness.render() {
            Ok(image) => return image,
            Err(e) if e.contains("PollError") && start.elapsed() < PATIENCE => {
                eprintln!("the draw timed out ({e}); drawing again");
            }
            Err(e) => panic!("the window does not draw: {e}"),
        }
    }
}

/// The window's usual size in these tests.
pub const WINDOW: [f32; 2] = [1280.0, 820.0];

/// The window ([`WINDOW`]) on the bundled `balls_low` at 1/8 of its
/// resolution, 64 x 64, so renders are quick.
pub fn small_window(builder: HarnessBuilder<WorkbenchApp>) -> Harness<'static, WorkbenchApp> {
    small_window_sized(builder, WINDOW)
}

/// [`small_window`] at another window size (a taller side panel, say).
pub fn small_window_sized(
    builder: HarnessBuilder<WorkbenchApp>,
    size: [f32; 2],
) -> Harness<'static, WorkbenchApp> {
    let mut harness = window(
        builder.with_size(size),
        None,
        Some(SceneSource::Bundled("balls_low".into())),
    );
    harness.state_mut().controls_mut().resolution_scale = 0.125;
    harness
}

/// [`small_window`] at `size`, once its scene shows and its structure is
/// built ([`wait_for_scene`]): where most tests start.
pub fn ready_window(size: [f32; 2]) -> Harness<'static, WorkbenchApp> {
    let mut harness = small_window_sized(Harness::builder(), size);
    wait_for_scene(&mut harness);
    harness
}

/// Whether side A's render, and B's in compare mode, are done.
pub fn is_done(app: &WorkbenchApp) -> bool {
    let finished = |e: &workbench::gui::Engine| e.activity() == Activity::Job(JobState::Done);
    finished(app.engine()) && app.side_b().is_none_or(|b| finished(&b.engine))
}

/// Whether the observer's render is done and on screen.
pub fn observer_done(app: &WorkbenchApp) -> bool {
    let observer = app.observer();
    observer.engine().activity() == Activity::Job(JobState::Done)
        && observer.image.is_current(observer.engine())
}

/// Drags the left button across the image named `label` ("Render",
/// "Observer"), as a user orbits its camera.
pub fn drag(harness: &mut Harness<'static, WorkbenchApp>, label: &str) {
    let at = drag_holding(harness, label);
    harness.drop_at(at);
    harness.step();
}

/// [`drag`] without the release: the camera is still moving. Returns
/// where the pointer is, to drop it there.
pub fn drag_holding(harness: &mut Harness<'static, WorkbenchApp>, label: &str) -> egui::Pos2 {
    let view = harness
        .get_by_role_and_label(egui::accesskit::Role::Image, label)
        .rect();
    let mut at = view.center();
    harness.drag_at(at);
    for _ in 0..4 {
        at += egui::vec2(15.0, 5.0);
        harness.hover_at(at);
        harness.step();
    }
    at
}

/// Steps the window until `done` holds (the render runs on other
/// threads), within the workspace's one bound ([`PATIENCE`]); `done` may
/// also assert what must hold on the way.
pub fn wait_for(
    harness: &mut Harness<'static, WorkbenchApp>,
    what: &str,
    done: impl Fn(&WorkbenchApp) -> bool,
) {
    assert!(
        TURN.with(|held| held.borrow().is_some()),
        "a window built outside harness::window: it would not take its turn"
    );
    tracer::waiting::wait_until(what, || {
        harness.step();
        done(harness.state())
    });
}

/// Steps the window until its scene is loaded and rendering with its
/// acceleration structure built: until then the engine holds new settings
/// back (a restart would build the structure a second time), so a test
/// that changes a setting and reads the engine's a few frames later starts
/// from here, as a user acts on a window that shows its scene.
pub fn wait_for_scene(harness: &mut Harness<'static, WorkbenchApp>) {
    wait_for(harness, "the scene and its structure", |app| {
        app.engine().settings().is_some() && app.engine().index().is_some()
    });
}

/// Writes a scene whose line 5, column 7 is wrong, in a folder of its own
/// named after `test`: the folder (keep it while the scene is used) and
/// the scene's path.
pub fn broken_scene(test: &str) -> (Scratch, PathBuf) {
    let dir = Scratch::new(&format!("broken-{test}"));
    let path = dir.join("broken.p3f");
    std::fs::write(&path, "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle forty\n").unwrap();
    (dir, path)
}

/// A file dropped on the window, as the native integration delivers it.
#[derive(Debug)]
pub struct DroppedPath(pub PathBuf);

impl egui::DroppedFile for DroppedPath {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        std::fs::read(&self.0).map_err(|e| e.to_string())
    }
}

/// The file dialogs as a test answers them: each question asked is kept,
/// each answered with the next path given (`None`: cancelled).
#[derive(Default)]
pub struct Answers {
    pub paths: Mutex<VecDeque<Option<PathBuf>>>,
    pub asked: Mutex<Vec<FileQuestion>>,
}

impl FileDialog for Answers {
    fn ask(&self, question: &FileQuestion) -> Option<PathBuf> {
        self.asked.lock().unwrap().push(question.clone());
        self.paths
            .lock()
            .unwrap()
            .pop_front()
            .expect("a dialog no answer was given for")
    }
}

impl Answers {
    pub fn next(&self, path: Option<&Path>) {
        self.paths
            .lock()
            .unwrap()
            .push_back(path.map(Path::to_path_buf));
    }

    /// The last question's filter extensions and offered name.
    pub fn last(&self) -> (Vec<&'static str>, Option<String>, bool) {
        let asked = self.asked.lock().unwrap();
        let q = asked.last().expect("a question");
        (q.filter.1.to_vec(), q.name.clone(), q.save)
    }
}

/// Has `harness`'s file dialogs answered by a test ([`Answers`]), whose
/// answers it returns.
pub fn answer_dialogs(harness: &mut Harness<'static, WorkbenchApp>) -> Arc<Answers> {
    let answers = Arc::new(Answers::default());
    harness
        .state_mut()
        .answer_file_dialogs_with(answers.clone());
    answers
}

/// A file dropped as a web page drops one: a name that is no file on
/// disk, and its bytes.
#[derive(Debug)]
pub struct DroppedBytes {
    pub name: PathBuf,
    pub bytes: Vec<u8>,
}

impl egui::DroppedFile for DroppedBytes {
    fn path(&self) -> &Path {
        &self.name
    }

    fn bytes(&self) -> Result<Vec<u8>, String> {
        Ok(self.bytes.clone())
    }
}
