//! The one bound on every wait in the workspace's tests: a test waits for
//! an event (a job done, a file written, a window's render shown) by
//! polling for it, and fails, naming what it waited for, only when the
//! event has not come after [`PATIENCE`]. Generous on purpose: on a
//! loaded two-core machine a debug build's render may take a hundred
//! times its usual time, and only a hang should ever reach the bound.

use std::time::Duration;

use web_time::Instant;

/// How long any test waits for anything before it calls it a hang.
pub const PATIENCE: Duration = Duration::from_secs(300);

/// Polls `done` until it holds, failing the test after [`PATIENCE`].
pub fn wait_until(what: &str, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(
            start.elapsed() < PATIENCE,
            "gave up waiting for {what} after {PATIENCE:?}"
        );
        std::thread::sleep(Duration::from_millis(2));
    }
}
