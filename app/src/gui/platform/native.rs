//! The desktop's side of what differs on the web page
//! ([`super::target`]): threads of its own, the desktop's file dialogs,
//! render threads that give way to the window's.

use std::sync::Arc;

use tracer::render::driver::{Priority, render_pool as pool_of};

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
