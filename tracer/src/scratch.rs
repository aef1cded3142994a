//! A test's scratch folder in the system temp dir that removes itself when
//! the test passes and stays, with its path printed, when the test fails,
//! so daily test runs do not fill the disk and a failure can be inspected.
//!
//! One type for the whole workspace: `tracer`'s own unit tests use it, and
//! `workbench`'s tests through the `test-util` feature.

use std::ops::Deref;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// An empty folder `workbench-NAME-PID-N` in the temp dir; derefs to its
/// path. Dropped while its thread panics (a failing test), it is kept.
#[derive(Debug)]
pub struct Scratch(PathBuf);

impl Scratch {
    /// A fresh, empty folder named after `name`. The process id and a
    /// counter keep the tests of one binary, running in parallel, and of
    /// several runs at once apart.
    pub fn new(name: &str) -> Self {
        static MADE: AtomicUsize = AtomicUsize::new(0);
        let n = MADE.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("workbench-{name}-{}-{n}", std::process::id()));
        // Left by an earlier process with the same id whose test failed.
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir)
            .unwrap_or_else(|e| panic!("cannot create {}: {e}", dir.display()));
        Self(dir)
    }
}

impl Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("test failed: its files are kept in {}", self.0.display());
        } else {
            // A test may have removed the folder itself.
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}
