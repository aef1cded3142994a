//! A subcommand whose stdout is closed early (`workbench lesson check |
//! head -1`) ends quietly, as any Unix tool does: killed by SIGPIPE or
//! done, never a panic's "failed printing to stdout".

use std::io::Read;
use std::os::unix::net::UnixStream;
use std::os::unix::process::ExitStatusExt;
use std::process::{Command, Stdio};

use crate::support::scenes::spheres_on_a_floor;
use crate::support::{Watchdog, scratch, write};

/// Runs `workbench args` with stdout a socket whose reading end is closed
/// before the child starts, so its first line already finds no reader:
/// the child's exit status and its stderr.
fn with_stdout_closed(args: &[&str]) -> (std::process::ExitStatus, String) {
    let (reader, writer) = UnixStream::pair().unwrap();
    drop(reader);
    let mut child = Command::new(crate::support::workbench_exe())
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::from(std::os::fd::OwnedFd::from(writer)))
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let _watchdog = Watchdog::new(child.id());
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    (child.wait().unwrap(), stderr)
}

#[test]
fn a_closed_stdout_ends_each_printing_subcommand_quietly() {
    let dir = scratch("closed-stdout");
    let scene = write(&dir, "scene.p3f", &spheres_on_a_floor(16, 12, "", ""));
    let scene = scene.display().to_string();
    for args in [
        &["lesson", "list"][..],
        &["lesson", "list", "--format", "json"],
        &["lesson", "check", "camera"],
        &["inspect", "--pixel", "8", "8", &scene],
    ] {
        let (status, stderr) = with_stdout_closed(args);
        assert!(!stderr.contains("panicked"), "workbench {args:?}: {stderr}");
        assert!(
            status.success() || status.signal() == Some(libc::SIGPIPE),
            "workbench {args:?} ended with {status}: {stderr}"
        );
    }
}
