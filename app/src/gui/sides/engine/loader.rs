//! A scene read and prepared on a thread of its own, so the window keeps
//! drawing (and the current scene rendering) while a large mesh loads.

use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError, channel};

use crate::gui::platform::target;
use crate::load::{Loaded, SceneSource};

use super::Wake;

/// A scene being loaded on its thread.
pub(super) struct SceneLoad {
    pub(crate) label: String,
    result: Receiver<Result<Loaded, String>>,
    /// Thousandths of a mesh file read so far, or [`NO_FRACTION`].
    per_mille: Arc<AtomicU32>,
}

/// The loading thread's name (the tests tell its wakes from a render's).
pub(crate) const THREAD_NAME: &str = "scene-loader";

/// A load that has reported no progress (a scene file, a small mesh).
const NO_FRACTION: u32 = u32::MAX;

impl SceneLoad {
    /// Starts reading `source`; `wake` is called with progress and when it
    /// is done.
    pub(crate) fn start(source: SceneSource, wake: Wake) -> Self {
        let (tx, rx) = channel();
        let label = source.label();
        let per_mille = Arc::new(AtomicU32::new(NO_FRACTION));
        let progress = per_mille.clone();
        let spawned = target::spawn(THREAD_NAME, move || {
            let mut on_progress = |p: tracer::scene::mesh_io::LoadProgress| {
                let fraction = p.bytes_read as f64 / p.total_bytes.max(1) as f64;
                progress.store((fraction.min(1.0) * 1000.0) as u32, Ordering::Relaxed);
                wake();
            };
            let result = Loaded::read(source, &[], &mut on_progress).map_err(|e| format!("{e:#}"));
            let _ = tx.send(result);
            wake();
        });
        let result = match spawned {
            Ok(_) => rx,
            Err(e) => {
                let (tx, rx) = channel();
                let _ = tx.send(Err(format!("cannot start the scene loader: {e}")));
                rx
            }
        };
        Self {
            label,
            result,
            per_mille,
        }
    }

    /// The loaded scene or why it failed, once the thread is done.
    pub(crate) fn poll(&self) -> Option<Result<Loaded, String>> {
        match self.result.try_recv() {
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                Some(Err("the scene loader stopped unexpectedly".into()))
            }
            Ok(result) => Some(result),
        }
    }

    /// How much of a large mesh file is read, when it reports it.
    pub(crate) fn fraction(&self) -> Option<f32> {
        let per_mille = self.per_mille.load(Ordering::Relaxed);
        (per_mille != NO_FRACTION).then(|| per_mille as f32 / 1000.0)
    }
}
