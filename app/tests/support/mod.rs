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
/// The workspace's one bound on a test's wait.
pub const RUN_TIMEOUT: Duration = tracer::waiting::PATIENCE;

/// The binary under test: cargo's build of it, or the one `WORKBENCH_BIN`
/// names. CI runs the command-line tests a second time on its build
/// without the window: cargo cannot build that beside these tests, whose
/// dev-dependencies (egui_kittest) would compile the GPU stack a second
/// time with other features.
pub fn workbench_exe() -> PathBuf {
    std::env::var_os("WORKBENCH_BIN")
        .map_or_else(|| env!("CARGO_BIN_EXE_workbench").into(), PathBuf::from)
}

/// Runs `workbench` with `args` and waits for it, for at most
/// [`RUN_TIMEOUT`].
pub fn workbench(args: &[&str]) -> Output {
    let mut command = Command::new(workbench_exe());
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

/// Kills a child that is still running after [`RUN_TIMEOUT`], for a test
/// that talks to it through its pipes (blocking reads) instead of
/// [`output_within`]: the reads then end, and the test fails instead of
/// hanging. Dropping the watchdog calls it off.
pub struct Watchdog {
    /// Dropped, it wakes the watching thread, which then leaves the child be.
    _stop: std::sync::mpsc::Sender<()>,
}

impl Watchdog {
    pub fn new(pid: u32) -> Self {
        let (stop, stopped) = std::sync::mpsc::channel::<()>();
        std::thread::spawn(move || {
            if stopped.recv_timeout(RUN_TIMEOUT) == Err(std::sync::mpsc::RecvTimeoutError::Timeout)
            {
                eprintln!("process {pid} still running after {RUN_TIMEOUT:?}: killed");
                let _ = Command::new("kill")
                    .args(["-KILL", &pid.to_string()])
                    .status();
            }
        });
        Self { _stop: stop }
    }
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

/// Whether process `pid` has a handler for SIGINT (the kernel's `SigCgt`
/// mask in `/proc/PID/status`; SIGINT is signal 2, bit 1).
#[cfg(target_os = "linux")]
pub fn catches_sigint(pid: u32) -> bool {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|line| line.strip_prefix("SigCgt:"))
        .and_then(|mask| u64::from_str_radix(mask.trim(), 16).ok())
        .is_some_and(|mask| mask & (1 << 1) != 0)
}

/// A connected socket pair whose second end is full to the brim (whole
/// pages, then single bytes, until the kernel takes no more), and how many
/// bytes fill it: a child given that end as stdout blocks on its first
/// write until the first end is read, an event a test can wait for.
#[cfg(target_os = "linux")]
pub fn full_socket() -> (
    std::os::unix::net::UnixStream,
    std::os::unix::net::UnixStream,
    usize,
) {
    use std::io::{ErrorKind, Write};
    let (ours, theirs) = std::os::unix::net::UnixStream::pair().unwrap();
    theirs.set_nonblocking(true).unwrap();
    let mut filler = 0;
    for chunk in [&[b'#'; 4096][..], b"#"] {
        loop {
            match (&theirs).write(chunk) {
                Ok(n) => filler += n,
                Err(e) if e.kind() == ErrorKind::WouldBlock => break,
                Err(e) => panic!("cannot fill the socket: {e}"),
            }
        }
    }
    theirs.set_nonblocking(false).unwrap();
    (ours, theirs, filler)
}

/// What a `workbench` run interrupted by Ctrl-C did.
#[cfg(target_os = "linux")]
pub struct Interrupted {
    /// stdout, after the socket's filler.
    pub stdout: String,
    /// stderr after the child said it stops.
    pub stderr: String,
    pub status: std::process::ExitStatus,
}

/// Runs `workbench args` and presses Ctrl-C at a moment decided by events,
/// not by time or the machine's speed: the child's stdout is a socket
/// filled to the brim ([`full_socket`]), so the child blocks on its first
/// line, which it writes right after setting its Ctrl-C handler and before
/// any work. SIGINT goes once the kernel shows the handler set; the socket
/// is drained once the child has said `said` on stderr.
#[cfg(target_os = "linux")]
pub fn interrupted(args: &[&str], said: &str) -> Interrupted {
    use std::io::{BufRead, BufReader};
    use std::os::fd::OwnedFd;

    let (mut ours, theirs, filler) = full_socket();
    let mut child = Command::new(workbench_exe())
        .args(args)
        .stdout(Stdio::from(OwnedFd::from(theirs)))
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    let _watchdog = Watchdog::new(pid);
    tracer::waiting::wait_until("the child to catch SIGINT", || catches_sigint(pid));
    let signalled = Command::new("kill")
        .args(["-INT", &pid.to_string()])
        .status()
        .unwrap();
    assert!(signalled.success());
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut before = String::new();
    while !before.contains(said) {
        let mut line = String::new();
        let read = stderr.read_line(&mut line).unwrap();
        assert!(
            read > 0,
            "the child ended without saying {said:?}: {before}"
        );
        before.push_str(&line);
    }
    // Only now may the child write its first line and work.
    let mut stdout = Vec::new();
    ours.read_to_end(&mut stdout).unwrap();
    let mut rest = String::new();
    stderr.read_to_string(&mut rest).unwrap();
    let status = child.wait().unwrap();
    let output = stdout.split_off(filler);
    assert!(stdout.iter().all(|&b| b == b'#'), "the filler comes first");
    Interrupted {
        stdout: String::from_utf8(output).unwrap(),
        stderr: rest,
        status,
    }
}
