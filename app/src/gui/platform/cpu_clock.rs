//! CPU clocks of the process and of the render threads: what a window frame
//! costs is the process's CPU time minus the render threads', because a
//! software rasterizer (llvmpipe) paints on threads of its own after the UI
//! thread has handed the frame over, so the UI thread's clock alone saw a
//! tenth of it and let redraws take half the machine.

use std::cell::Cell;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

/// CPU time used so far by the whole process and by its render threads.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct CpuTimes {
    pub(crate) process: Duration,
    pub(crate) render: Duration,
}

impl CpuTimes {
    /// The times now; `None` where the OS has no per-process CPU clock.
    pub(crate) fn now() -> Option<CpuTimes> {
        Some(CpuTimes {
            process: cpu_clock(CpuClock::Process)?,
            render: Duration::from_nanos(RENDER_CPU_NANOS.load(Ordering::Relaxed)),
        })
    }
}

/// CPU time of every render thread so far, nanoseconds.
static RENDER_CPU_NANOS: AtomicU64 = AtomicU64::new(0);

/// Counts the CPU time the calling render thread used since its previous
/// call as render time. Render threads call it with every progress report,
/// so the window can tell its own cost from the render's.
pub(crate) fn count_render_thread_cpu() {
    thread_local! {
        static COUNTED: Cell<Duration> = const { Cell::new(Duration::ZERO) };
    }
    let Some(now) = cpu_clock(CpuClock::Thread) else {
        return;
    };
    let new = COUNTED.with(|counted| now.saturating_sub(counted.replace(now)));
    RENDER_CPU_NANOS.fetch_add(new.as_nanos() as u64, Ordering::Relaxed);
}

enum CpuClock {
    Process,
    Thread,
}

/// CPU time used by the process or the calling thread.
#[cfg(unix)]
fn cpu_clock(clock: CpuClock) -> Option<Duration> {
    let id = match clock {
        CpuClock::Process => libc::CLOCK_PROCESS_CPUTIME_ID,
        CpuClock::Thread => libc::CLOCK_THREAD_CPUTIME_ID,
    };
    let mut time = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime only writes the timespec it is given, which
    // lives on this stack frame for the whole call.
    let read = unsafe { libc::clock_gettime(id, &mut time) } == 0;
    read.then(|| Duration::new(time.tv_sec as u64, time.tv_nsec as u32))
}

#[cfg(not(unix))]
fn cpu_clock(_clock: CpuClock) -> Option<Duration> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn render_threads_count_their_own_cpu_time() {
        let before = CpuTimes::now().expect("CPU clocks on this OS");
        std::thread::spawn(|| {
            let mut x = 0u64;
            while cpu_clock(CpuClock::Thread).unwrap() < 20 * MS {
                x = std::hint::black_box(x.wrapping_mul(31).wrapping_add(1));
            }
            count_render_thread_cpu();
        })
        .join()
        .unwrap();
        let after = CpuTimes::now().unwrap();
        let render = after.render - before.render;
        assert!(render >= 20 * MS, "{render:?}");
        // Render threads of other tests count into the same total (time
        // they spent before `before` among it), so only this thread's part
        // is sure to be in the process's clock.
        let process = after.process - before.process;
        assert!(process >= 20 * MS, "{process:?}");
    }
}
