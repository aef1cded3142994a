//! Who gets the CPU while a render runs: the render, ahead of a software
//! rasterizer painting the window.
//!
//! Without a GPU, Mesa paints the window on threads of its own (`llvmpipe-N`,
//! for GL and for Vulkan's lavapipe alike), one per core. At the same
//! priority as the render threads they took a large share of a two-core
//! machine during a first render, and the window rendered well below a
//! headless render's rays/s. At [`NICENESS`] more than the process, the
//! scheduler gives them about a quarter of a core's time next to a busy
//! render thread and all of it otherwise, and the window keeps its frame
//! rate (`docs/PERFORMANCE.md` has the figures).
//!
//! A GPU driver has no such threads; then nothing changes.

/// How much lower than the rest of the process a rasterizer thread runs.
pub(crate) const NICENESS: i32 = 5;

/// Lowers the priority of the process's software rasterizer threads by
/// [`NICENESS`] (once each: a thread already lowered is skipped); returns
/// how many it lowered. Call once the window's graphics device exists.
pub(crate) fn lower_software_rasterizer() -> usize {
    lower_threads_named(is_software_rasterizer)
}

/// Whether a thread of this name paints for Mesa's llvmpipe or lavapipe.
fn is_software_rasterizer(name: &str) -> bool {
    name.starts_with("llvmpipe-")
}

#[cfg(target_os = "linux")]
fn lower_threads_named(matches: impl Fn(&str) -> bool) -> usize {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return 0;
    };
    let Some(process_nice) = nice_of(0) else {
        return 0;
    };
    let target = (process_nice + NICENESS).min(19);
    let mut lowered = 0;
    for task in tasks.flatten() {
        let Some(tid) = task.file_name().to_str().and_then(|t| t.parse().ok()) else {
            continue;
        };
        let name = std::fs::read_to_string(task.path().join("comm")).unwrap_or_default();
        if !matches(name.trim_end()) {
            continue;
        }
        if nice_of(tid).is_some_and(|nice| nice < target) && set_nice(tid, target) {
            lowered += 1;
        }
    }
    lowered
}

#[cfg(not(target_os = "linux"))]
fn lower_threads_named(_matches: impl Fn(&str) -> bool) -> usize {
    0
}

/// The nice value of thread `tid` (0: the calling thread).
#[cfg(target_os = "linux")]
fn nice_of(tid: libc::id_t) -> Option<i32> {
    // SAFETY: errno is this thread's own; getpriority reads the scheduler's
    // value and writes nothing. -1 is a valid nice value, so errno (cleared
    // first) tells it from a failure.
    unsafe {
        *libc::__errno_location() = 0;
        let nice = libc::getpriority(libc::PRIO_PROCESS, tid);
        (*libc::__errno_location() == 0).then_some(nice)
    }
}

/// Sets thread `tid`'s nice value; whether it took.
#[cfg(target_os = "linux")]
fn set_nice(tid: libc::id_t, nice: i32) -> bool {
    // SAFETY: setpriority takes plain integers and changes only the
    // scheduling weight of a thread of this process.
    unsafe { libc::setpriority(libc::PRIO_PROCESS, tid, nice) == 0 }
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;
    use std::sync::mpsc;

    #[test]
    fn only_the_rasterizer_threads_are_named_so() {
        assert!(is_software_rasterizer("llvmpipe-0"));
        assert!(is_software_rasterizer("llvmpipe-15"));
        assert!(!is_software_rasterizer("render-0"));
        assert!(!is_software_rasterizer("workbench"));
        assert!(!is_software_rasterizer("llvmpipe"));
    }

    /// The named thread runs [`NICENESS`] lower than the process, once
    /// however often it is asked; the others keep theirs.
    #[test]
    fn a_named_thread_is_lowered_once_and_no_other() {
        fn parked(name: &str) -> (libc::pid_t, mpsc::Sender<()>) {
            let (tid_tx, tid_rx) = mpsc::channel();
            let (stop_tx, stop_rx) = mpsc::channel::<()>();
            std::thread::Builder::new()
                .name(name.into())
                .spawn(move || {
                    // SAFETY: gettid has no arguments and cannot fail.
                    tid_tx.send(unsafe { libc::gettid() }).unwrap();
                    stop_rx.recv().ok();
                })
                .unwrap();
            (tid_rx.recv().unwrap(), stop_tx)
        }
        let (painter, stop_painter) = parked("paint-test-a");
        let (other, stop_other) = parked("paint-test-b");
        let process = nice_of(0).unwrap();
        let lower = || lower_threads_named(|name| name == "paint-test-a");

        let first = lower();
        let second = lower();
        let painter_nice = nice_of(painter as libc::id_t).unwrap();
        let other_nice = nice_of(other as libc::id_t).unwrap();
        drop((stop_painter, stop_other));

        if process + NICENESS <= 19 {
            assert_eq!((first, second), (1, 0));
            assert_eq!(painter_nice, process + NICENESS);
        }
        assert_eq!(other_nice, process);
    }
}
