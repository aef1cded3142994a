//! The desktop's side of what differs on the web page
//! ([`super::target`]): threads of its own, the desktop's file dialogs,
//! render threads that give way to the window's.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context;
use tracer::scene::Scene;
use tracer::stats::RenderStats;

use tracer::render::driver::{Priority, render_pool as pool_of};

use super::transfer::Transfer;
use crate::gui::app::{FileDialog as AskFile, FileQuestion};
use crate::load::SceneSource;

/// The desktop's own file dialogs, asked from a background thread.
pub use rfd::FileDialog;

/// The desktop opens and writes any file (see [`super::file_button`]).
pub(crate) const NO_FILES: Option<&str> = None;

/// Background work wakes the window itself (egui's repaint works from
/// any thread).
pub(crate) const WORK_WAKES_WINDOW: bool = true;

/// Runs `work` in the background on a thread called `name`.
pub(crate) fn spawn(name: &str, work: impl FnOnce() + Send + 'static) -> std::io::Result<()> {
    std::thread::Builder::new()
        .name(name.into())
        .spawn(work)
        .map(drop)
}

/// [`spawn`] for work that measures for long: the desktop has threads
/// for it.
pub(crate) fn spawn_long(name: &str, work: impl FnOnce() + Send + 'static) -> std::io::Result<()> {
    spawn(name, work)
}

/// Where the window renders a render, when the statistics panel should
/// say it: never on the desktop, where it is always the machine's cores.
pub(crate) fn rendered_on(_: &RenderStats) -> Option<String> {
    None
}

/// A pool of render threads at `priority`, one per core, for an engine's
/// jobs.
pub(crate) fn render_pool(priority: Priority) -> Result<Option<Arc<rayon::ThreadPool>>, String> {
    pool_of(None, priority).map(Some).map_err(|e| e.to_string())
}

/// Lets the calling background thread run only when nothing else wants
/// the cores (best effort).
pub(crate) fn lowest_priority() {
    let _ = thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Min);
}

/// Where a lesson's step set up puts its scene (`scene`, edits included):
/// a P3F file named after the lesson in the temp folder, which the window
/// opens as any scene file (its paths written relative to that folder).
pub(crate) fn lesson_scene(name: &str, scene: &Scene) -> anyhow::Result<SceneSource> {
    let dir = std::env::temp_dir().join("whitted-workbench-lessons");
    std::fs::create_dir_all(&dir).with_context(|| format!("{}", dir.display()))?;
    let path = dir.join(format!("{name}.p3f"));
    let text = tracer::scene::write_p3f_in(scene, &dir);
    std::fs::write(&path, text).with_context(|| format!("{}", path.display()))?;
    Ok(SceneSource::File(path))
}

/// Reads the file a link names (`url`, relative to the current folder as
/// a page's is to the page) and gives its bytes to `done`, at once: no
/// progress to follow.
pub(crate) fn fetch(url: &str, _: Transfer, done: impl FnOnce(Result<Vec<u8>, String>) + 'static) {
    done(std::fs::read(url).map_err(|e| format!("{url}: {e}")));
}

/// Where Copy link's query goes after: the page's file, as the desktop
/// has no address of its own (the query is the same as a page's).
pub(crate) fn page_address() -> String {
    "index.html".into()
}

/// Reads a dropped file's bytes and gives them to `done`, at once.
pub(crate) fn read_dropped(
    file: Arc<dyn egui::DroppedFile>,
    done: impl FnOnce(Result<Vec<u8>, String>) + 'static,
) {
    done(file.bytes());
}

/// Where bytes the user saves go on the desktop: the file chosen in the
/// save dialog.
pub(crate) struct SaveTo(PathBuf);

impl SaveTo {
    /// Asks `dialog` where to save (offering `question`'s name); `None`
    /// when cancelled.
    pub(crate) fn ask(dialog: &dyn AskFile, question: &FileQuestion) -> Option<Self> {
        dialog.ask(question).map(Self)
    }

    /// Where the bytes go, as the window says it.
    pub(crate) fn describe(&self) -> String {
        self.0.display().to_string()
    }

    /// Writes `bytes` there, whole or not at all (a temporary file
    /// renamed over it).
    pub(crate) fn write(&self, bytes: &[u8]) -> anyhow::Result<()> {
        crate::image_file::write_atomically(&self.0, |file| {
            std::io::Write::write_all(file, bytes)?;
            Ok(())
        })
        .with_context(|| format!("cannot write {}", self.0.display()))
    }
}
