//! Where a job runs: the pool its tiles run on, the thread that runs its
//! loop, the clock its times read, and how a failure reaches its viewer.
//! The render loop sees none of these choices: a native window hosts a
//! job on a thread of its own, a web page on its workers' pool.

use std::cell::RefCell;
use std::future::Future;
use std::sync::{Arc, Once, OnceLock};
use std::time::Duration;

use super::RenderError;
pub use super::control::set_viewers_hidden;
use super::slices::{self, SliceId, block_on};

/// The time a job's passes and budgets read.
pub trait Clock: Send + Sync {
    /// Time since an origin of the clock's choosing; never goes back.
    fn now(&self) -> Duration;
}

/// The system's monotonic clock, from when it was made.
#[derive(Debug, Clone, Copy)]
pub struct SystemClock {
    origin: web_time::Instant,
}

impl Default for SystemClock {
    fn default() -> Self {
        Self {
            origin: web_time::Instant::now(),
        }
    }
}

impl Clock for SystemClock {
    fn now(&self) -> Duration {
        self.origin.elapsed()
    }
}

/// How a job's loop is hosted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Host {
    /// A thread of its own, started for the job: dropping the job waits
    /// for it, so nothing of the job outlives its handle.
    Thread,
    /// A task on the job's pool, for a platform where the caller can
    /// neither start a thread nor wait for one (a web page's main thread):
    /// dropping the job cancels it and returns at once.
    Pool,
    /// A task on rayon's global pool, whose threads also render its
    /// tiles: [`super::JobOptions::pool`], `threads` and the priorities
    /// are ignored. For a web page, whose one pool is the global pool that
    /// `wasm-bindgen-rayon` fills with the page's Web Workers (a page can
    /// build no pool of its own). Dropping the job returns at once, as
    /// for [`Host::Pool`].
    Global,
    /// Time slices of the thread that starts the job, which runs its
    /// tiles one after another when that thread calls
    /// [`run_slices`](super::run_slices), and all of them when it waits
    /// for the job. For a web page without workers (one not cross-origin
    /// isolated), whose only thread must keep returning to the browser.
    Slices,
}

/// The host a job takes unless its options say otherwise, when set
/// ([`set_default_host`]).
static DEFAULT_HOST: OnceLock<Host> = OnceLock::new();

/// Makes `host` every job's default host in this process, once, before
/// any job starts: for a web page that learns only when it loads whether
/// it has workers. Gives `host` back if a default was already set.
pub fn set_default_host(host: Host) -> Result<(), Host> {
    DEFAULT_HOST.set(host)
}

impl Default for Host {
    /// The one set by [`set_default_host`]; else a thread of its own,
    /// except on the web, where a page can start no thread: there every
    /// job renders on the page's workers.
    fn default() -> Self {
        if let Some(host) = DEFAULT_HOST.get() {
            *host
        } else if cfg!(target_family = "wasm") {
            Host::Global
        } else {
            Host::Thread
        }
    }
}

/// The pool a job's tiles run on.
#[derive(Clone)]
pub(super) enum JobPool {
    /// A pool made for jobs ([`render_pool`]).
    Own(Arc<rayon::ThreadPool>),
    /// Rayon's global pool ([`Host::Global`]).
    Global,
}

impl JobPool {
    /// Runs `op` where its parallel work uses this pool.
    pub(super) fn install<R: Send>(&self, op: impl FnOnce() -> R + Send) -> R {
        match self {
            JobPool::Own(pool) => pool.install(op),
            JobPool::Global => op(),
        }
    }

    /// Runs `a` and `b` in parallel on this pool.
    pub(super) fn join<A: Send, B: Send>(
        &self,
        a: impl FnOnce() -> A + Send,
        b: impl FnOnce() -> B + Send,
    ) -> (A, B) {
        match self {
            JobPool::Own(pool) => pool.join(a, b),
            JobPool::Global => rayon::join(a, b),
        }
    }
}

/// How render threads share the cores with the rest of the machine.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Priority {
    /// As any thread: a headless render.
    #[default]
    Normal,
    /// Let an interactive viewer's threads run first whenever they wake
    /// (batch scheduling on Linux, the lowest priority elsewhere), while
    /// keeping the share of the cores a headless render gets.
    YieldToViewer,
    /// Only in the time other work leaves (Linux's idle scheduling, the
    /// lowest priority elsewhere): a second view beside the main render.
    Idle,
}

/// A pool of `threads` render threads (`None`: one per core) at
/// `priority`. Made once and passed to each job
/// ([`super::JobOptions::pool`]), or made per job when none is.
pub fn render_pool(
    threads: Option<usize>,
    priority: Priority,
) -> Result<Arc<rayon::ThreadPool>, RenderError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .thread_name(|i| format!("render-{i}"))
        .start_handler(move |_| set_priority(priority))
        .build()
        .map(Arc::new)
        .map_err(|e| RenderError::Threads(e.to_string()))
}

/// Where a job's loop went ([`host`]): what waiting for it and dropping
/// it deal with.
pub(super) enum Hosted {
    /// Its own thread, joined.
    Thread(std::thread::JoinHandle<()>),
    /// A pool's task: its end is signalled by the job's state.
    Task,
    /// This thread's time slices.
    Slices(SliceId),
}

/// Starts `work`, the job's loop, where `host` says: on a thread or a
/// pool it runs to its end at once ([`Host::Slices`] alone makes it give
/// way).
pub(super) fn host(
    host: Host,
    pool: &JobPool,
    work: impl Future<Output = ()> + Send + 'static,
) -> Result<Hosted, RenderError> {
    match (host, pool) {
        (Host::Slices, _) => Ok(Hosted::Slices(slices::host(work))),
        (Host::Thread, _) => std::thread::Builder::new()
            .name("render-job".into())
            .spawn(move || block_on(work))
            .map(Hosted::Thread)
            .map_err(|e| RenderError::Threads(e.to_string())),
        (_, JobPool::Own(pool)) => {
            pool.spawn(move || block_on(work));
            Ok(Hosted::Task)
        }
        (_, JobPool::Global) => {
            rayon::spawn(move || block_on(work));
            Ok(Hosted::Task)
        }
    }
}

/// Where a job's failure is written: the first panic on any thread
/// working for the job. Filled by a panic hook, which runs before the
/// panic unwinds or aborts, so a failure is reported even where panics
/// abort (the web build) and `catch_unwind` catches nothing.
pub(super) type FailureSlot = Arc<OnceLock<String>>;

thread_local! {
    /// The job the current thread is working for, if any.
    static WORKING_FOR: RefCell<Option<FailureSlot>> = const { RefCell::new(None) };
}

/// While alive, a panic on this thread is written to a job's
/// [`FailureSlot`]; dropping it restores what the thread worked for
/// before (a render thread may run another job's tile while it waits).
pub(super) struct WorkingFor(Option<FailureSlot>);

impl WorkingFor {
    pub(super) fn job(slot: &FailureSlot) -> Self {
        static HOOK: Once = Once::new();
        HOOK.call_once(install_hook);
        Self(WORKING_FOR.with(|w| w.replace(Some(slot.clone()))))
    }
}

impl Drop for WorkingFor {
    fn drop(&mut self) {
        let previous = self.0.take();
        // Gone only while the thread itself ends.
        let _ = WORKING_FOR.try_with(|w| w.replace(previous));
    }
}

fn install_hook() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = panic_message(info.payload());
        let _ = WORKING_FOR.try_with(|w| {
            if let Ok(w) = w.try_borrow()
                && let Some(slot) = w.as_ref()
            {
                let _ = slot.set(message);
            }
        });
        previous(info);
    }));
}

pub(super) fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        format!("render thread panicked: {s}")
    } else if let Some(s) = payload.downcast_ref::<String>() {
        format!("render thread panicked: {s}")
    } else {
        "render thread panicked".to_string()
    }
}

/// Sets the calling render thread's share of the cores (see [`Priority`]).
/// Best effort: a viewer works either way, only less smoothly if the OS
/// refuses.
fn set_priority(priority: Priority) {
    match priority {
        Priority::Normal => {}
        Priority::YieldToViewer => yield_to_interactive_threads(),
        Priority::Idle => run_when_idle(),
    }
}

/// Marks the calling render thread as batch work. The lowest priority
/// (nice 19) made a viewer's render several times slower than a headless one
/// as soon as anything else ran on the machine (the software rasterizer
/// painting the window, other processes); `SCHED_BATCH` at the usual nice
/// value keeps the thread's share of the cores and only gives way to
/// threads that wake up, such as the UI's.
fn yield_to_interactive_threads() {
    #[cfg(target_os = "linux")]
    {
        use thread_priority::unix::{
            NormalThreadSchedulePolicy, ThreadSchedulePolicy, set_thread_priority_and_policy,
            thread_native_id,
        };
        use thread_priority::{ThreadPriority, ThreadPriorityValue};
        // The crate maps its 0..=99 scale onto nice 19..=-20: 47 is nice 0,
        // the value every thread starts with.
        if let Ok(usual) = ThreadPriorityValue::try_from(47u8) {
            let _ = set_thread_priority_and_policy(
                thread_native_id(),
                ThreadPriority::Crossplatform(usual),
                ThreadSchedulePolicy::Normal(NormalThreadSchedulePolicy::Batch),
            );
        }
    }
    #[cfg(not(target_os = "linux"))]
    lowest_priority();
}

/// The calling render thread runs only when the cores have nothing else
/// to do (see [`Priority::Idle`]).
fn run_when_idle() {
    #[cfg(target_os = "linux")]
    {
        use thread_priority::unix::{
            NormalThreadSchedulePolicy, ThreadSchedulePolicy, set_thread_priority_and_policy,
            thread_native_id,
        };
        // SCHED_IDLE takes no priority but the minimum (a crossplatform
        // value is refused as out of its 0..=0 range).
        let _ = set_thread_priority_and_policy(
            thread_native_id(),
            thread_priority::ThreadPriority::Min,
            ThreadSchedulePolicy::Normal(NormalThreadSchedulePolicy::Idle),
        );
    }
    #[cfg(not(target_os = "linux"))]
    lowest_priority();
}

/// Elsewhere than Linux: the lowest priority the platform has, where it
/// has threads with priorities at all.
#[cfg(not(target_os = "linux"))]
fn lowest_priority() {
    #[cfg(not(target_family = "wasm"))]
    let _ = thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Min);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_is_written_to_the_job_the_thread_works_for_and_no_other() {
        let (job, other) = (FailureSlot::default(), FailureSlot::default());
        let (for_job, for_other) = (job.clone(), other.clone());
        let outcome = std::thread::spawn(move || {
            let _other = WorkingFor::job(&for_other);
            {
                let _job = WorkingFor::job(&for_job);
            }
            let _job = WorkingFor::job(&for_job);
            panic!("a bug");
        })
        .join();
        assert!(outcome.is_err());
        assert_eq!(
            job.get().map(String::as_str),
            Some("render thread panicked: a bug")
        );
        assert_eq!(other.get(), None);
        // The scope ended with its thread: a later panic here is no job's.
        let _ = std::thread::spawn(|| panic!("unrelated")).join();
        assert_eq!(
            job.get().map(String::as_str),
            Some("render thread panicked: a bug")
        );
    }

    #[test]
    fn a_restored_scope_reports_to_the_outer_job() {
        let (outer, inner) = (FailureSlot::default(), FailureSlot::default());
        let (for_outer, for_inner) = (outer.clone(), inner.clone());
        let _ = std::thread::spawn(move || {
            let _outer = WorkingFor::job(&for_outer);
            drop(WorkingFor::job(&for_inner));
            panic!("after the inner job's tile");
        })
        .join();
        assert!(outer.get().is_some());
        assert_eq!(inner.get(), None);
    }

    #[test]
    fn the_system_clock_never_goes_back() {
        let clock = SystemClock::default();
        let (a, b) = (clock.now(), clock.now());
        assert!(b >= a);
    }

    #[test]
    fn a_pool_hosted_loop_runs_on_the_pool() {
        let pool = render_pool(Some(1), Priority::Normal).unwrap();
        let (tx, rx) = std::sync::mpsc::channel();
        let hosted = host(Host::Pool, &JobPool::Own(pool), async move {
            tx.send(std::thread::current().name().map(str::to_owned))
                .unwrap();
        })
        .unwrap();
        assert!(matches!(hosted, Hosted::Task), "nothing to join");
        assert_eq!(rx.recv().unwrap().as_deref(), Some("render-0"));
    }

    #[test]
    fn a_globally_hosted_loop_runs_on_the_global_pool() {
        let (tx, rx) = std::sync::mpsc::channel();
        let hosted = host(Host::Global, &JobPool::Global, async move {
            let thread = std::thread::current();
            let in_pool = rayon::current_thread_index().is_some();
            tx.send((in_pool, thread.name().map(str::to_owned)))
                .unwrap();
        })
        .unwrap();
        assert!(matches!(hosted, Hosted::Task), "nothing to join");
        let (in_pool, name) = rx.recv().unwrap();
        assert!(in_pool, "not on a pool's thread");
        // The global pool's threads are unnamed; a render pool's are not.
        assert_eq!(name, None);
    }
}
