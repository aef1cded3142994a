//! What both test binaries share: run the real binary (killed if it hangs,
//! its pipes drained), make a scratch folder, write a scene into it.
// Each test binary includes this module and uses only part of it.
#![allow(dead_code)]

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

pub mod scenes;

pub use tracer::scratch::Scratch;

/// Longest one `workbench` run of an end-to-end test may take before it is
/// killed and the test fails: the slowest (a study, a large mesh on a
/// loaded debug build) take seconds, so only a hang comes near it, and CI
/// gets a failure naming the command instead of a job that never ends.
pub const RUN_TIMEOUT: Duration = Duration::from_secs(300);

/// Runs `workbench` with `args` and waits for it, for at most
/// [`RUN_TIMEOUT`].
pub fn workbench(args: &[&str]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_workbench"));
    command.args(args);
    output_within(command, RUN_TIMEOUT).unwrap_or_else(|e| panic!("workbench {args:?}: {e}"))
}

/// stdout of a `workbench` run that must succeed (its stderr shown if
/// not).
pub fn workbench_ok(args: &[&str]) -> String {
    let run = workbench(args);
    assert!(
        run.status.success(),
        "workbench {args:?} failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    String::from_utf8_lossy(&run.stdout).into_owned()
}

/// stderr of a `workbench` run that must fail.
pub fn workbench_fails(args: &[&str]) -> String {
    let run = workbench(args);
    assert!(!run.status.success(), "workbench {args:?} should fail");
    String::from_utf8_lossy(&run.stderr).into_owned()
}

/// Runs `command` to completion like [`Command::output`], but kills it
/// and reports an error once it has run for `timeout`.
pub fn output_within(mut command: Command, timeout: Duration) -> Result<Output, String> {
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start: {e}"))?;
    let stdout = drain(child.stdout.take());
    let stderr = drain(child.stderr.take());
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if start.elapsed() >= timeout {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!("still running after {timeout:?}: killed"));
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    Ok(Output {
        status,
        stdout: stdout.join().unwrap_or_default(),
        stderr: stderr.join().unwrap_or_default(),
    })
}

/// Reads a child's pipe to the end on its own thread, so a chatty child
/// cannot block on a full pipe while the test waits for it to exit.
fn drain(pipe: Option<impl Read + Send + 'static>) -> JoinHandle<Vec<u8>> {
    std::thread::spawn(move || {
        let mut bytes = Vec::new();
        if let Some(mut pipe) = pipe {
            let _ = pipe.read_to_end(&mut bytes);
        }
        bytes
    })
}

/// A fresh folder for one test's files, removed when the test passes.
pub fn scratch(name: &str) -> Scratch {
    Scratch::new(&format!("e2e-{name}"))
}

/// Writes `text` as `dir/name` and returns its path.
pub fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}
