//! The web page's side of what differs from the desktop
//! ([`super::target`]): the page's entry point, its workers, and what a
//! page cannot do. A page can start no thread and its main thread may
//! never wait: background work and every render run on rayon's global
//! pool, which `wasm-bindgen-rayon` fills with Web Workers before the
//! window starts (`initThreadPool`, called by `web/index.html`).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use tracer::render::JobState;
use tracer::render::driver::Priority;
use wasm_bindgen::JsCast;
use wasm_bindgen::prelude::*;

use super::super::WorkbenchApp;
pub use super::download::{NO_FILES, SaveTo};
pub use super::web_link::{fetch, page_address};
use crate::load::SceneSource;
use tracer::scene::Scene;

/// Work on a worker cannot wake the window: eframe's repaint callback
/// reads the page's clock through `window`, which a worker lacks (it
/// panicked "should have a Window"). The page polls instead while a
/// render runs ([`Page`]).
pub const WORK_WAKES_WINDOW: bool = false;

/// Background work started and not finished ([`spawn`]): while any is,
/// the page keeps looking for its results ([`busy`]).
static IN_FLIGHT: AtomicUsize = AtomicUsize::new(0);

/// Counts a piece of background work out of [`IN_FLIGHT`] when it ends.
struct InFlight;

impl Drop for InFlight {
    fn drop(&mut self) {
        IN_FLIGHT.fetch_sub(1, Ordering::Release);
    }
}

/// Runs `work` in the background on one of the page's workers.
pub fn spawn(_name: &str, work: impl FnOnce() + Send + 'static) -> std::io::Result<()> {
    IN_FLIGHT.fetch_add(1, Ordering::Acquire);
    rayon::spawn(move || {
        let _counted = InFlight;
        work();
    });
    Ok(())
}

/// Whether background work started with [`spawn`] is still running.
fn busy() -> bool {
    IN_FLIGHT.load(Ordering::Acquire) > 0
}

/// No pool of the engine's own: a page's jobs render on the global pool
/// of its workers (`Host::Global`, the tracer's default on the web).
pub fn render_pool(_priority: Priority) -> Result<Option<Arc<rayon::ThreadPool>>, String> {
    Ok(None)
}

/// Workers have no priorities.
pub fn lowest_priority() {}

/// Where a lesson's step set up puts its scene (`scene`, edits included):
/// in memory, as P3F text named after the lesson, as a page has no files.
pub fn lesson_scene(name: &str, scene: &Scene) -> anyhow::Result<SceneSource> {
    Ok(SceneSource::Written {
        name: format!("{name}.p3f"),
        text: tracer::scene::write_p3f_in(scene, Path::new("")),
    })
}

/// Reads a dropped file's bytes, which a page gives only asynchronously,
/// and gives them to `done` on the page's thread once read.
pub fn read_dropped(
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
    pub fn new() -> Self {
        Self
    }

    pub fn add_filter(self, _name: &str, _extensions: &[&str]) -> Self {
        self
    }

    pub fn set_directory(self, _folder: impl Into<PathBuf>) -> Self {
        self
    }

    pub fn set_file_name(self, _name: impl Into<String>) -> Self {
        self
    }

    pub fn set_title(self, _title: impl Into<String>) -> Self {
        self
    }

    pub fn pick_file(self) -> Option<PathBuf> {
        None
    }

    pub fn pick_folder(self) -> Option<PathBuf> {
        None
    }

    pub fn save_file(self) -> Option<PathBuf> {
        None
    }
}

/// Starts the window on the page's canvas `canvas_id`, on the bundled
/// default scene, then opens what the page's link asks for
/// (`?lesson=NAME`, `?scene=NAME`). The page calls it once its
/// workers are up.
#[wasm_bindgen]
pub async fn start(canvas_id: String) -> Result<(), JsValue> {
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
    eframe::WebRunner::new()
        .start(
            canvas,
            options,
            Box::new(|cc| {
                let mut app = WorkbenchApp::new(&cc.egui_ctx, cc.storage, None);
                let query = web_sys::window().and_then(|w| w.location().search().ok());
                app.open_link(&query.unwrap_or_default());
                Ok(Box::new(Page {
                    app,
                    said: String::new(),
                }))
            }),
        )
        .await
}

/// How often the page looks at a running render.
const POLL: std::time::Duration = std::time::Duration::from_millis(100);

/// The window on a page, which says how side A's render stands in the
/// page's `<body data-…>` attributes: for a script driving the page (the
/// smoke test, `scripts/check_web_page.py`), as the desktop's tests ask
/// the window itself.
struct Page {
    app: WorkbenchApp,
    /// The attributes last written, so unchanged frames write nothing.
    said: String,
}

impl Page {
    fn tell_page(&mut self) {
        let (state, passes) = match self.app.shown() {
            Some(shown) => (
                match &shown.state {
                    JobState::Building => "building".to_string(),
                    JobState::Rendering => "rendering".to_string(),
                    JobState::Done => "done".to_string(),
                    JobState::Cancelled => "cancelled".to_string(),
                    JobState::Failed(message) => format!("failed: {message}"),
                },
                shown.stats.passes_done,
            ),
            None => ("starting".to_string(), 0),
        };
        let state = match self.app.error() {
            Some(error) => format!("error: {error}"),
            None => state,
        };
        let lessons = self.app.lessons();
        let lesson = match lessons.lesson() {
            Some(lesson) if lessons.open => lesson.name.clone(),
            _ => String::new(),
        };
        let scene = self.app.engine().scene().map(|s| s.source.label());
        let scene = scene.unwrap_or_default();
        let said = format!("{state}|{passes}|{lesson}|{scene}");
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
            let _ = body.set_attribute("data-scene", &scene);
            let workers = rayon::current_num_threads().to_string();
            let _ = body.set_attribute("data-workers", &workers);
        }
        self.said = said;
    }
}

impl eframe::App for Page {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.app.ui(ui, frame);
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
}
