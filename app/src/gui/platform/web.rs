//! The web page's side of what differs from the desktop
//! ([`super::target`]): the page's entry point, its workers, and what a
//! page cannot do. A page can start no thread and its main thread may
//! never wait: background work and every render run on rayon's global
//! pool, which `wasm-bindgen-rayon` fills with Web Workers before the
//! window starts (`initThreadPool`, called by `web/index.html`). A page
//! that is not cross-origin isolated can have no workers: it renders in
//! time slices of its own thread between frames, and refuses to measure.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use tracer::render::driver::{Host, Priority, set_viewers_hidden};
use tracer::render::{JobState, run_slices, slices_pending};
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::super::WorkbenchApp;
pub(crate) use super::download::{NO_FILES, SaveTo};
pub(crate) use super::web_link::{fetch, page_address};
use crate::load::SceneSource;
use tracer::scene::Scene;
use tracer::stats::RenderStats;

/// Work on a worker cannot wake the window: eframe's repaint callback
/// reads the page's clock through `window`, which a worker lacks (it
/// panicked "should have a Window"). The page polls instead while a
/// render runs ([`Page`]).
pub(crate) const WORK_WAKES_WINDOW: bool = false;

/// Background work started and not finished ([`spawn`]): while any is,
/// the page keeps looking for its results ([`busy`]).
static IN_FLIGHT: AtomicUsize = AtomicUsize::new(0);

/// The page's Web Workers, as [`start`] was told: none on a page that is
/// not cross-origin isolated, where everything runs on the page's thread.
static WORKERS: AtomicUsize = AtomicUsize::new(0);

fn has_workers() -> bool {
    WORKERS.load(Ordering::Relaxed) > 0
}

/// Counts a piece of background work out of [`IN_FLIGHT`] when it ends.
struct InFlight;

impl Drop for InFlight {
    fn drop(&mut self) {
        IN_FLIGHT.fetch_sub(1, Ordering::Release);
    }
}

/// Runs `work` in the background on one of the page's workers; on a page
/// without workers, at once on the page's thread (a render it waits for
/// runs there to its end: `Host::Slices`).
pub(crate) fn spawn(_name: &str, work: impl FnOnce() + Send + 'static) -> std::io::Result<()> {
    if !has_workers() {
        work();
        return Ok(());
    }
    IN_FLIGHT.fetch_add(1, Ordering::Acquire);
    rayon::spawn(move || {
        let _counted = InFlight;
        work();
    });
    Ok(())
}

/// [`spawn`] for work that measures for long (a benchmark, a study, the
/// lab report): refused on a page without workers, where it would hold
/// the page's only thread for minutes, with its times taking in the page's.
pub(crate) fn spawn_long(name: &str, work: impl FnOnce() + Send + 'static) -> std::io::Result<()> {
    if !has_workers() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "measuring needs the page's Web Workers, which a page that is not \
             cross-origin isolated cannot have (see the web guide, docs/guide/web.md)",
        ));
    }
    spawn(name, work)
}

/// Whether background work started with [`spawn`] is still running.
fn busy() -> bool {
    IN_FLIGHT.load(Ordering::Acquire) > 0
}

/// Where the page renders `stats`' render, for the statistics panel: on
/// how many workers, and the tiles each took.
pub(crate) fn rendered_on(stats: &RenderStats) -> Option<String> {
    let tiles = tiles_by_worker(stats);
    Some(match WORKERS.load(Ordering::Relaxed) {
        0 => "page thread, in slices (the page is not cross-origin isolated: no workers)".into(),
        1 => format!("1 Web Worker (tiles: {tiles})"),
        n => format!("{n} Web Workers (tiles: {tiles})"),
    })
}

/// The tiles each worker rendered, as `40, 38`.
fn tiles_by_worker(stats: &RenderStats) -> String {
    let tiles: Vec<String> = stats.tiles_by_thread.iter().map(u64::to_string).collect();
    tiles.join(", ")
}

/// No pool of the engine's own: a page's jobs render on the global pool
/// of its workers (`Host::Global`, the tracer's default on the web).
pub(crate) fn render_pool(_priority: Priority) -> Result<Option<Arc<rayon::ThreadPool>>, String> {
    Ok(None)
}

/// Workers have no priorities.
pub(crate) fn lowest_priority() {}

/// Where a lesson's step set up puts its scene (`scene`, edits included):
/// in memory, as P3F text named after the lesson, as a page has no files.
pub(crate) fn lesson_scene(name: &str, scene: &Scene) -> anyhow::Result<SceneSource> {
    Ok(SceneSource::Written {
        name: format!("{name}.p3f"),
        text: tracer::scene::write_p3f_in(scene, Path::new("")),
    })
}

/// Reads a dropped file's bytes, which a page gives only asynchronously,
/// and gives them to `done` on the page's thread once read.
pub(crate) fn read_dropped(
    file: Arc<dyn egui::DroppedFile>,
    done: impl FnOnce(Result<Vec<u8>, String>) + 'static,
) {
    wasm_bindgen_futures::spawn_local(async move { done(file.bytes_async().await) });
}

/// A page has no synchronous file dialog and no folder picker: every
/// question is unanswered, which the window reports where it was asked
/// as a dialog cancelled.
#[derive(Debug, Default)]
pub struct FileDialog;

impl FileDialog {
    pub(crate) fn new() -> Self {
        Self
    }

    pub(crate) fn add_filter(self, _name: &str, _extensions: &[&str]) -> Self {
        self
    }

    pub(crate) fn set_directory(self, _folder: impl Into<PathBuf>) -> Self {
        self
    }

    pub(crate) fn set_file_name(self, _name: impl Into<String>) -> Self {
        self
    }

    pub(crate) fn set_title(self, _title: impl Into<String>) -> Self {
        self
    }

    pub(crate) fn pick_file(self) -> Option<PathBuf> {
        None
    }

    pub(crate) fn pick_folder(self) -> Option<PathBuf> {
        None
    }

    pub(crate) fn save_file(self) -> Option<PathBuf> {
        None
    }
}

/// Starts the window on the page's canvas `canvas_id`, on the bundled
/// default scene, then opens what the page's link asks for
/// (`?lesson=NAME`, `?scene=NAME`), or runs the page mode the link asks
/// for instead of the window (`?replay`, `?bench=…`, `?compare=…`). The
/// page calls it once its `workers` are up: none on a page that is not
/// cross-origin isolated, which then renders in time slices of its own
/// thread.
#[wasm_bindgen]
pub async fn start(canvas_id: String, workers: usize) -> Result<(), JsValue> {
    WORKERS.store(workers, Ordering::Relaxed);
    if workers == 0 {
        let _ = tracer::render::driver::set_default_host(Host::Slices);
    }
    say_panics_on_the_page();
    let query = web_sys::window()
        .and_then(|w| w.location().search().ok())
        .unwrap_or_default();
    if let Some(mode) = super::page_modes::asked(&query) {
        return mode.run().await;
    }
    hold_renders_while_hidden()?;
    let canvas = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id(&canvas_id))
        .ok_or_else(|| JsValue::from_str(&format!("no element #{canvas_id} on the page")))?
        .dyn_into::<web_sys::HtmlCanvasElement>()?;
    let options = eframe::WebOptions {
        // As on the desktop: the render is shown exactly as computed.
        dithering: false,
        ..eframe::WebOptions::default()
    };
    let runner = eframe::WebRunner::new();
    RUNNER.with(|r| r.replace(Some(runner.clone())));
    runner
        .start(
            canvas,
            options,
            Box::new(move |cc| {
                let mut app = WorkbenchApp::new(&cc.egui_ctx, cc.storage, None);
                app.open_link(&query);
                Ok(Box::new(Page {
                    app,
                    said: String::new(),
                    slice_ended: None,
                }))
            }),
        )
        .await
}

thread_local! {
    /// The page's runner, for [`rays_traced`], which a script calls
    /// between frames.
    static RUNNER: std::cell::RefCell<Option<eframe::WebRunner>> = const { std::cell::RefCell::new(None) };
}

/// The rays side A's render has traced so far, read from the render
/// itself: a script checking that a hidden tab holds the render asks it,
/// as the page draws no frame (and says nothing in `<body data-…>`)
/// while hidden. -1 before a render starts.
#[wasm_bindgen]
pub fn rays_traced() -> f64 {
    RUNNER.with(|r| {
        let runner = r.borrow();
        let page = runner.as_ref().and_then(|r| r.app_mut::<Page>());
        page.and_then(|page| page.app.engine().live_stats())
            .map_or(-1.0, |stats| stats.counters.total_rays() as f64)
    })
}

/// Shows a panic on the page's thread in the page's `#status` element,
/// and in `<body data-render>`: panics abort on the web, so the window
/// stops there and then, and the page would otherwise just freeze. (A
/// worker's panic fails its job instead, which the window says.)
fn say_panics_on_the_page() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        previous(info);
        let Some(document) = web_sys::window().and_then(|w| w.document()) else {
            return;
        };
        let text =
            format!("The workbench stopped on a bug: {info}. Reload the page to start again.");
        if let Some(status) = document.get_element_by_id("status") {
            status.set_text_content(Some(&text));
            let _ = status.set_attribute("class", "error");
            let _ = status.remove_attribute("hidden");
        }
        if let Some(body) = document.body() {
            let _ = body.set_attribute("data-render", &format!("panic: {info}"));
        }
    }));
}

/// Holds the window's renders while the page's tab is hidden
/// (`set_viewers_hidden`): nobody sees them, and the workers give the
/// cores back. Measurements go on.
fn hold_renders_while_hidden() -> Result<(), JsValue> {
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or_else(|| JsValue::from_str("no document"))?;
    let seen = document.clone();
    let changed = Closure::<dyn Fn()>::new(move || set_viewers_hidden(seen.hidden()));
    document
        .add_event_listener_with_callback("visibilitychange", changed.as_ref().unchecked_ref())?;
    // The page listens as long as it lives.
    changed.forget();
    set_viewers_hidden(document.hidden());
    Ok(())
}

/// How long the page's thread renders in a frame, without workers: as
/// long as the rest of the frame took, so the render gets at least half
/// the thread, within these bounds (the window still drawn 10 times a
/// second when drawing is slow, as on a software WebGL).
const SLICE_MIN: Duration = Duration::from_millis(25);
const SLICE_MAX: Duration = Duration::from_millis(100);

/// How often the page looks at a running render.
const POLL: Duration = Duration::from_millis(100);

/// The window on a page, which says how side A's render stands in the
/// page's `<body data-…>` attributes: for a script driving the page (the
/// smoke test, `scripts/check_web_page.py`), as the desktop's tests ask
/// the window itself.
struct Page {
    app: WorkbenchApp,
    /// The attributes last written, so unchanged frames write nothing.
    said: String,
    /// When the page's thread last stopped rendering, without workers.
    slice_ended: Option<web_time::Instant>,
}

impl Page {
    fn tell_page(&mut self) {
        let (state, passes, tiles, on) = match self.app.shown() {
            Some(shown) => (
                match &shown.state {
                    JobState::Building => "building".to_string(),
                    JobState::Rendering => "rendering".to_string(),
                    JobState::Done => "done".to_string(),
                    JobState::Cancelled => "cancelled".to_string(),
                    JobState::Failed(message) => format!("failed: {message}"),
                },
                shown.stats.passes_done,
                tiles_by_worker(&shown.stats),
                rendered_on(&shown.stats).unwrap_or_default(),
            ),
            None => ("starting".to_string(), 0, String::new(), String::new()),
        };
        let state = match self.app.error() {
            Some(error) => format!("error: {error}"),
            None => state,
        };
        let lessons = self.app.lessons();
        // The step as the panel counts it, from 1.
        let (lesson, step) = match lessons.lesson() {
            Some(lesson) if lessons.open => (lesson.name.clone(), (lessons.step() + 1).to_string()),
            _ => (String::new(), String::new()),
        };
        let scene = self.app.engine().scene().map(|s| s.source.label());
        let scene = scene.unwrap_or_default();
        let said = format!("{state}|{passes}|{tiles}|{lesson}|{step}|{scene}");
        if said == self.said {
            return;
        }
        if let Some(body) = web_sys::window()
            .and_then(|w| w.document())
            .and_then(|d| d.body())
        {
            let _ = body.set_attribute("data-render", &state);
            let _ = body.set_attribute("data-passes", &passes.to_string());
            let _ = body.set_attribute("data-lesson", &lesson);
            let _ = body.set_attribute("data-step", &step);
            let _ = body.set_attribute("data-scene", &scene);
            let workers = WORKERS.load(Ordering::Relaxed).to_string();
            let _ = body.set_attribute("data-workers", &workers);
            let _ = body.set_attribute("data-tiles", &tiles);
            let _ = body.set_attribute("data-rendered-on", &on);
        }
        self.said = said;
    }
}

impl eframe::App for Page {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.app.ui(ui, frame);
        // Without workers, the renders run here, between frames.
        if slices_pending() {
            let others = self.slice_ended.map_or(SLICE_MIN, |end| end.elapsed());
            if run_slices(others.clamp(SLICE_MIN, SLICE_MAX)) {
                ui.ctx().request_repaint();
            }
            self.slice_ended = Some(web_time::Instant::now());
        } else {
            self.slice_ended = None;
        }
        self.tell_page();
        let downloads_waiting = super::download::give_downloads();
        // Workers do not wake the page (WORK_WAKES_WINDOW): it looks again
        // while a render or other background work runs, and once after
        // (the frame that sees it done shows its result).
        if self.app.is_rendering() || busy() || downloads_waiting {
            ui.ctx().request_repaint_after(POLL);
        }
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        self.app.clear_color(visuals)
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.app.save(storage);
    }

    fn auto_save_interval(&self) -> Duration {
        self.app.auto_save_interval()
    }

    /// For [`rays_traced`] (`WebRunner::app_mut`).
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        Some(self)
    }
}
