//! The desktop's side of what differs on the web page
//! ([`super::target`]): threads of its own, the desktop's file dialogs,
//! render threads that give way to the window's.

use std::sync::Arc;

use anyhow::Context;
use tracer::scene::Scene;
use tracer::stats::RenderStats;

use tracer::render::driver::{Priority, render_pool as pool_of};

use crate::load::SceneSource;

/// The desktop's own file dialogs, asked from a background thread.
pub use rfd::FileDialog;

/// Background work wakes the window itself (egui's repaint works from
/// any thread).
pub const WORK_WAKES_WINDOW: bool = true;

/// Runs `work` in the background on a thread called `name`.
pub fn spawn(name: &str, work: impl FnOnce() + Send + 'static) -> std::io::Result<()> {
    std::thread::Builder::new()
        .name(name.into())
        .spawn(work)
        .map(drop)
}

/// [`spawn`] for work that measures for long: the desktop has threads
/// for it.
pub fn spawn_long(name: &str, work: impl FnOnce() + Send + 'static) -> std::io::Result<()> {
    spawn(name, work)
}

/// Where the window renders a render, when the statistics panel should
/// say it: never on the desktop, where it is always the machine's cores.
pub fn rendered_on(_: &RenderStats) -> Option<String> {
    None
}

/// A pool of render threads at `priority`, one per core, for an engine's
/// jobs.
pub fn render_pool(priority: Priority) -> Result<Option<Arc<rayon::ThreadPool>>, String> {
    pool_of(None, priority).map(Some).map_err(|e| e.to_string())
}

/// Lets the calling background thread run only when nothing else wants
/// the cores (best effort).
pub fn lowest_priority() {
    let _ = thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Min);
}

/// Where a lesson's step set up puts its scene (`scene`, edits included):
/// a P3F file named after the lesson in the temp folder, which the window
/// opens as any scene file (its paths written relative to that folder).
pub fn lesson_scene(name: &str, scene: &Scene) -> anyhow::Result<SceneSource> {
    let dir = std::env::temp_dir().join("whitted-workbench-lessons");
    std::fs::create_dir_all(&dir).with_context(|| format!("{}", dir.display()))?;
    let path = dir.join(format!("{name}.p3f"));
    let text = tracer::scene::write_p3f_in(scene, &dir);
    std::fs::write(&path, text).with_context(|| format!("{}", path.display()))?;
    Ok(SceneSource::File(path))
}

/// Reads a dropped file's bytes and gives them to `done`, at once.
pub fn read_dropped(
    file: Arc<dyn egui::DroppedFile>,
    done: impl FnOnce(Result<Vec<u8>, String>) + 'static,
) {
    done(file.bytes());
}
