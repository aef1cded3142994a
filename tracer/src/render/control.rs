//! A job's controls, shared between its viewer and its render threads:
//! cancel, pause, and the progress signal a viewer wakes up on. A viewer's
//! calls never wait for a render thread (a web page's main thread may not
//! wait at all); render threads wait while the job is paused.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Condvar, Mutex, MutexGuard, PoisonError, TryLockError};
use std::time::Duration;

/// Called from a render thread after each tile and pass, so a viewer can
/// wake up (e.g. `egui::Context::request_repaint`).
pub(crate) type ProgressListener = Box<dyn Fn() + Send + Sync>;

/// Cancel, pause and progress of one job.
pub(super) struct Control {
    cancel: AtomicBool,
    paused: AtomicBool,
    /// Render threads sleep on it while paused; the viewer never takes
    /// its lock, it only notifies.
    sleep: Mutex<()>,
    resumed: Condvar,
    version: AtomicU64,
    on_progress: Option<ProgressListener>,
    pause_after_tiles: Option<u64>,
    tiles_done: AtomicU64,
    /// Shown live, so held while the viewers are hidden ([`set_viewers_hidden`]).
    viewed: bool,
}

/// Whether the process's viewers are hidden ([`set_viewers_hidden`]).
static VIEWERS_HIDDEN: AtomicBool = AtomicBool::new(false);

/// Holds every viewed job ([`super::JobOptions::viewed`]) between tiles
/// while `hidden`, or lets them go on: a web page whose tab is hidden
/// stops rendering what nobody sees, and gives the cores back. Jobs that
/// measure are not viewed, so their times do not take in the hidden time.
pub fn set_viewers_hidden(hidden: bool) {
    VIEWERS_HIDDEN.store(hidden, Ordering::SeqCst);
}

/// How long a paused render thread sleeps before it looks again: a
/// viewer resumes without taking the sleepers' lock (see
/// [`Control::set_paused`]), so a notification sent just before a thread
/// starts to wait is missed, and this bounds what that costs.
const PAUSED_RECHECK: Duration = Duration::from_millis(50);

impl Control {
    pub(super) fn new(
        paused: bool,
        pause_after_tiles: Option<u64>,
        on_progress: Option<ProgressListener>,
        viewed: bool,
    ) -> Self {
        Self {
            cancel: AtomicBool::new(false),
            paused: AtomicBool::new(paused),
            sleep: Mutex::new(()),
            resumed: Condvar::new(),
            version: AtomicU64::new(0),
            on_progress,
            pause_after_tiles,
            tiles_done: AtomicU64::new(0),
            viewed,
        }
    }

    pub(super) fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
        self.set_paused(false);
    }

    pub(super) fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    pub(super) fn set_paused(&self, paused: bool) {
        self.paused.store(paused, Ordering::SeqCst);
        self.resumed.notify_all();
    }

    pub(super) fn is_paused(&self) -> bool {
        self.paused.load(Ordering::SeqCst)
    }

    /// Whether the job may start no tile now: paused, or viewed while the
    /// viewers are hidden.
    pub(super) fn held(&self) -> bool {
        self.is_paused() || (self.viewed && VIEWERS_HIDDEN.load(Ordering::SeqCst))
    }

    /// Blocks a render thread while the job is [`held`](Self::held); false
    /// once it is cancelled (the thread then starts nothing more).
    pub(super) fn proceed(&self) -> bool {
        if self.held() && !self.cancelled() {
            let mut sleeping = lock(&self.sleep);
            while self.held() && !self.cancelled() {
                sleeping = self
                    .resumed
                    .wait_timeout(sleeping, PAUSED_RECHECK)
                    .unwrap_or_else(PoisonError::into_inner)
                    .0;
            }
        }
        !self.cancelled()
    }

    /// A tile is in: pauses the job when it was asked to after this many,
    /// and wakes the viewer.
    pub(super) fn tile_done(&self) {
        let tiles = self.tiles_done.fetch_add(1, Ordering::Relaxed) + 1;
        if self.pause_after_tiles == Some(tiles) {
            self.set_paused(true);
        }
        self.notify();
    }

    /// Something a viewer shows changed: bumps the version and wakes it.
    pub(super) fn notify(&self) {
        self.version.fetch_add(1, Ordering::Relaxed);
        if let Some(wake) = &self.on_progress {
            wake();
        }
    }

    pub(super) fn version(&self) -> u64 {
        self.version.load(Ordering::Relaxed)
    }
}

/// Locks a mutex from a render thread, ignoring poisoning: a failure is
/// reported as the job's state, and the data stays usable.
pub(super) fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Locks a mutex without ever parking the calling thread: a viewer's
/// call, which on a web page runs on the main thread, where browsers
/// refuse to wait (`memory.atomic.wait`). Render threads hold these locks
/// for a tile's bookkeeping only, so the spin is short.
pub(super) fn lock_spinning<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    loop {
        match m.try_lock() {
            Ok(guard) => return guard,
            Err(TryLockError::Poisoned(poisoned)) => return poisoned.into_inner(),
            Err(TryLockError::WouldBlock) => {
                std::hint::spin_loop();
                std::thread::yield_now();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;
    use std::sync::atomic::AtomicUsize;

    use super::*;

    #[test]
    fn a_job_pauses_after_its_tiles_and_wakes_its_viewer_each_time() {
        let woken = Arc::new(AtomicUsize::new(0));
        let count = woken.clone();
        let control = Control::new(
            false,
            Some(2),
            Some(Box::new(move || {
                count.fetch_add(1, Ordering::Relaxed);
            })),
            false,
        );
        control.tile_done();
        assert!(!control.is_paused());
        control.tile_done();
        assert!(control.is_paused());
        assert_eq!(woken.load(Ordering::Relaxed), 2);
        assert_eq!(control.version(), 2);
    }

    #[test]
    fn a_paused_thread_proceeds_when_resumed_and_stops_when_cancelled() {
        let control = Arc::new(Control::new(true, None, None, false));
        let waiting = control.clone();
        let thread = std::thread::spawn(move || waiting.proceed());
        control.set_paused(false);
        assert!(thread.join().unwrap(), "resumed");
        control.set_paused(true);
        let waiting = control.clone();
        let thread = std::thread::spawn(move || waiting.proceed());
        control.cancel();
        assert!(!thread.join().unwrap(), "cancelled");
    }

    #[test]
    fn a_viewer_waits_out_a_held_lock_and_reads_through_a_poisoned_one() {
        let m = Arc::new(Mutex::new(0));
        let (held, viewer_waits) = (m.clone(), Arc::new(AtomicBool::new(false)));
        let (tx, rx) = std::sync::mpsc::channel();
        let waits = viewer_waits.clone();
        let thread = std::thread::spawn(move || {
            let mut guard = lock(&held);
            tx.send(()).unwrap();
            while !waits.load(Ordering::SeqCst) {
                std::hint::spin_loop();
            }
            *guard += 1;
        });
        rx.recv().unwrap();
        viewer_waits.store(true, Ordering::SeqCst);
        assert_eq!(*lock_spinning(&m), 1, "after the render thread's write");
        thread.join().unwrap();
        let poisoner = m.clone();
        let _ = std::thread::spawn(move || {
            let _guard = lock(&poisoner);
            panic!("a render thread fails holding the lock");
        })
        .join();
        assert!(m.is_poisoned());
        assert_eq!(*lock_spinning(&m), 1);
    }
}
