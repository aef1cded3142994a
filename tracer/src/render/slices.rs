//! Jobs hosted in time slices ([`super::driver::Host::Slices`]): for a
//! web page without Web Workers, whose one thread must return to the
//! browser to draw. Such a job's loop is kept, paused mid-render, in a
//! list of the thread that started it; [`run_slices`], called by that
//! thread once a frame, advances every loop for a while. The loop gives
//! way between tiles once the slice is spent, and while its job is
//! paused.

use std::cell::{Cell, RefCell};
use std::future::Future;
use std::pin::Pin;
use std::task::{Context, Poll, Waker};
use std::time::Duration;

use web_time::Instant;

/// A loop in the list, by the number [`host`] gave it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct SliceId(u64);

struct Sliced {
    id: SliceId,
    work: Pin<Box<dyn Future<Output = ()>>>,
}

thread_local! {
    /// The thread's loops, in the order they take their slices.
    static LOOPS: RefCell<Vec<Sliced>> = const { RefCell::new(Vec::new()) };
    static NEXT_ID: Cell<u64> = const { Cell::new(0) };
    /// When the slice being run ends; `None`: never (a loop waited for).
    static SLICE_END: Cell<Option<Instant>> = const { Cell::new(None) };
    /// A loop gave way with work it could do at once (not only paused).
    static WANTS_MORE: Cell<bool> = const { Cell::new(false) };
    /// The loop that [`finish`] drives to its end, if any.
    static WAITED_FOR: Cell<bool> = const { Cell::new(false) };
}

/// Keeps `work`, a job's loop, to be advanced on this thread by
/// [`run_slices`] (or run to its end by [`finish`]).
pub(super) fn host(work: impl Future<Output = ()> + 'static) -> SliceId {
    let id = SliceId(NEXT_ID.with(|n| {
        let id = n.get();
        n.set(id + 1);
        id
    }));
    LOOPS.with(|l| {
        l.borrow_mut().push(Sliced {
            id,
            work: Box::pin(work),
        })
    });
    id
}

/// Advances every loop this thread hosts for about `budget` in all, each
/// at least one tile, the first taking what it needs and the next loop
/// first next time. True when a loop gave way with more it could do at
/// once: call again soon. A paused loop waits for the next call.
pub fn run_slices(budget: Duration) -> bool {
    WANTS_MORE.with(|w| w.set(false));
    SLICE_END.with(|e| e.set(Some(Instant::now() + budget)));
    let mut loops = LOOPS.with(|l| std::mem::take(&mut *l.borrow_mut()));
    if !loops.is_empty() {
        loops.rotate_left(1);
    }
    loops.retain_mut(|sliced| poll(&mut sliced.work).is_pending());
    // Loops started while these ran were added to the emptied list.
    LOOPS.with(|l| {
        let mut list = l.borrow_mut();
        let started = std::mem::take(&mut *list);
        *list = loops;
        list.extend(started);
    });
    WANTS_MORE.with(Cell::get)
}

/// Whether this thread hosts a loop that has not ended.
pub fn slices_pending() -> bool {
    LOOPS.with(|l| !l.borrow().is_empty())
}

/// Runs loop `id` to its end on this thread, now: a caller that waits for
/// its job. A paused job is cancelled, as nothing could resume it while
/// its only thread waits.
pub(super) fn finish(id: SliceId) {
    let taken = LOOPS.with(|l| {
        let mut list = l.borrow_mut();
        let at = list.iter().position(|s| s.id == id)?;
        Some(list.remove(at))
    });
    let Some(mut sliced) = taken else {
        return;
    };
    let (end, waited) = (
        SLICE_END.with(|e| e.replace(None)),
        WAITED_FOR.with(|w| w.replace(true)),
    );
    while poll(&mut sliced.work).is_pending() {}
    SLICE_END.with(|e| e.set(end));
    WAITED_FOR.with(|w| w.set(waited));
}

/// Drops loop `id`, whose job is gone.
pub(super) fn forget(id: SliceId) {
    LOOPS.with(|l| l.borrow_mut().retain(|s| s.id != id));
}

fn poll(work: &mut Pin<Box<dyn Future<Output = ()>>>) -> Poll<()> {
    work.as_mut().poll(&mut Context::from_waker(Waker::noop()))
}

/// Whether the running loop's slice is spent: it gives way after its tile.
pub(super) fn spent() -> bool {
    SLICE_END.with(|e| e.get().is_some_and(|end| Instant::now() >= end))
}

/// Whether the running loop is waited for ([`finish`]).
pub(super) fn waited_for() -> bool {
    WAITED_FOR.with(Cell::get)
}

/// Gives the thread back until the next slice: `more`, with work the loop
/// could do at once (its slice is spent), else only waiting (paused).
pub(super) async fn give_way(more: bool) {
    if more {
        WANTS_MORE.with(|w| w.set(true));
    }
    GiveWay(false).await
}

/// Pending once, then ready: a loop's one step back to its host.
struct GiveWay(bool);

impl Future for GiveWay {
    type Output = ();

    fn poll(mut self: Pin<&mut Self>, _: &mut Context<'_>) -> Poll<()> {
        if self.0 {
            Poll::Ready(())
        } else {
            self.0 = true;
            Poll::Pending
        }
    }
}

/// Runs `work`, which never gives way (a loop hosted on threads), to its
/// end on the calling thread.
pub(super) fn block_on<T>(work: impl Future<Output = T>) -> T {
    let mut work = std::pin::pin!(work);
    loop {
        if let Poll::Ready(value) = work.as_mut().poll(&mut Context::from_waker(Waker::noop())) {
            return value;
        }
    }
}
