//! `workbench sweep` end to end: a tiny grid-m study as CSV with its
//! chart, the level study on small levels, the spp study's error columns,
//! bad input, and Ctrl-C keeping what was measured.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::support::scenes::spheres_on_a_floor;
use crate::support::{scratch, workbench, workbench_fails, workbench_ok, write};

fn scene(dir: &Path) -> PathBuf {
    write(dir, "scene.p3f", &spheres_on_a_floor(48, 32, "", ""))
}

#[test]
fn a_grid_m_sweep_prints_a_csv_row_per_point_and_draws_the_chart() {
    let dir = scratch("sweep-grid-m");
    let scene = scene(&dir);
    let chart = dir.join("chart.png");
    let csv = workbench_ok(&[
        "sweep",
        scene.to_str().unwrap(),
        "--param",
        "grid-m",
        "--values",
        "0.5..2:x2",
        "--structures",
        "grid,bvh",
        "--runs",
        "2",
        "--format",
        "csv",
        "--plot",
        chart.to_str().unwrap(),
        "--threads",
        "1",
    ]);
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "accel,grid-m,build ms,frame ms,min..max ms,runs,rays,rays/s,tests/ray,steps/ray,best"
    );
    assert_eq!(lines.len(), 1 + 2 * 3, "{csv}");
    let rows: Vec<Vec<&str>> = lines[1..].iter().map(|l| l.split(',').collect()).collect();
    let firsts: Vec<(&str, &str)> = rows.iter().map(|r| (r[0], r[1])).collect();
    assert_eq!(
        firsts,
        [
            ("grid", "0.5"),
            ("grid", "1"),
            ("grid", "2"),
            ("bvh", "0.5"),
            ("bvh", "1"),
            ("bvh", "2")
        ]
    );
    for row in &rows {
        assert_eq!(row.len(), 11);
        assert_eq!(row[5], "2", "two runs per point");
        assert!(row[3].parse::<f64>().unwrap() > 0.0);
        // Every structure traces the same rays.
        assert_eq!(row[6], rows[0][6]);
    }
    // The grid's fastest m is marked (m changes nothing for the BVH).
    let fastest: Vec<&Vec<&str>> = rows.iter().filter(|r| r[10] == "fastest").collect();
    assert_eq!(fastest.len(), 1);
    assert_eq!(fastest[0][0], "grid");
    let image = image::open(&chart).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (800, 500));
}

#[test]
fn the_level_study_grows_a_generated_scene() {
    let json = workbench_ok(&[
        "sweep",
        "--param",
        "level",
        "--generator",
        "balls",
        "--levels",
        "0..2",
        "--structures",
        "none,bvh",
        "--runs",
        "1",
        "--width",
        "16",
        "--height",
        "16",
        "--format",
        "json",
    ]);
    let points: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    assert_eq!(points.len(), 6);
    let primitives: Vec<u64> = points
        .iter()
        .map(|p| p["primitives"].as_u64().unwrap())
        .collect();
    assert!(primitives[0] < primitives[2] && primitives[2] < primitives[4]);
    for p in &points {
        assert_eq!(p["x"].as_f64().unwrap(), p["primitives"].as_f64().unwrap());
        assert_eq!(p["width"], 16);
    }
    // Brute force tests more primitives per ray as the scene grows.
    let none: Vec<f64> = points
        .iter()
        .filter(|p| p["accel"] == "none")
        .map(|p| p["tests_per_ray"].as_f64().unwrap())
        .collect();
    assert!(none.windows(2).all(|w| w[0] < w[1]), "{none:?}");
}

#[test]
fn the_spp_study_reports_image_error() {
    let dir = scratch("sweep-spp");
    let scene = scene(&dir);
    let run = workbench(&[
        "sweep",
        scene.to_str().unwrap(),
        "--param",
        "spp",
        "--values",
        "1,2",
        "--runs",
        "1",
        "--format",
        "json",
    ]);
    assert!(run.status.success());
    let points: Vec<serde_json::Value> = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(points.len(), 2);
    for p in &points {
        assert!(p["mse"].as_f64().unwrap() > 0.0, "{p}");
        assert!(p["flip"].as_f64().unwrap() > 0.0, "{p}");
    }
    let stderr = String::from_utf8(run.stderr).unwrap();
    assert!(stderr.contains("reference of N = 4"), "{stderr}");
}

#[test]
fn bad_input_gets_a_clear_error() {
    let dir = scratch("sweep-bad");
    let scene = scene(&dir);
    let scene = scene.to_str().unwrap();
    let bad_values = workbench_fails(&["sweep", scene, "--param", "depth", "--values", "1..x"]);
    assert!(bad_values.contains("`x` in `1..x`"), "{bad_values}");
    let backwards = workbench_fails(&["sweep", scene, "--param", "depth", "--values", "5..1"]);
    assert!(backwards.contains("backwards"), "{backwards}");
    let fraction = workbench_fails(&["sweep", scene, "--param", "spp", "--values", "1.5"]);
    assert!(fraction.contains("whole numbers"), "{fraction}");
    let param = workbench_fails(&["sweep", scene, "--param", "speed"]);
    assert!(param.contains("grid-m"), "{param}");
    let level = workbench_fails(&["sweep", "--param", "level"]);
    assert!(level.contains("--generator"), "{level}");
    let generator = workbench_fails(&["sweep", "--param", "level", "--generator", "kettle"]);
    assert!(
        generator.contains("unknown generator `kettle`"),
        "{generator}"
    );
    let range = workbench_fails(&[
        "sweep",
        "--param",
        "level",
        "--generator",
        "balls",
        "--levels",
        "4..7",
    ]);
    assert!(range.contains("levels 0..=5"), "{range}");
    let no_scene = workbench_fails(&["sweep", "--param", "grid-m"]);
    assert!(no_scene.contains("scene file"), "{no_scene}");
}

/// Ctrl-C during a sweep finishes the frame under way, prints its point and
/// fails. When the signal lands is decided by events, not by time or the
/// machine's speed: the child's stdout is a socket this test has filled,
/// so the child blocks writing its header, which it does right after
/// setting its Ctrl-C handler and before any frame. The signal goes once
/// the kernel shows the handler set; the socket is drained once the child
/// has said it will stop after this frame. So exactly one point of one
/// frame is measured, on a fast machine or a loaded one, with a tiny
/// scene or a large one.
#[cfg(target_os = "linux")]
#[test]
fn ctrl_c_stops_after_the_frame_and_prints_what_was_measured() {
    use std::io::{ErrorKind, Write};
    use std::os::fd::OwnedFd;
    use std::os::unix::net::UnixStream;

    let dir = scratch("sweep-interrupt");
    let scene = scene(&dir);
    let (mut ours, theirs) = UnixStream::pair().unwrap();
    // Fill the child's stdout to the brim: whole pages, then single bytes,
    // until the kernel takes no more.
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
    let mut child = Command::new(env!("CARGO_BIN_EXE_workbench"))
        .args([
            "sweep",
            scene.to_str().unwrap(),
            "--param",
            "depth",
            "--values",
            "1..8",
            "--runs",
            "5",
            "--format",
            "md",
            "--threads",
            "1",
        ])
        .stdout(Stdio::from(OwnedFd::from(theirs)))
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id();
    wait_until("the sweep to catch SIGINT", || catches_sigint(pid));
    let interrupted = Command::new("kill")
        .args(["-INT", &pid.to_string()])
        .status()
        .unwrap();
    assert!(interrupted.success());
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut said = String::new();
    while !said.contains("stopping after this frame") {
        let mut line = String::new();
        let read = stderr.read_line(&mut line).unwrap();
        assert!(
            read > 0,
            "the sweep ended without a word about Ctrl-C: {said}"
        );
        said.push_str(&line);
    }
    // Only now may the child write its header and render.
    let mut stdout = Vec::new();
    ours.read_to_end(&mut stdout).unwrap();
    let mut rest = String::new();
    stderr.read_to_string(&mut rest).unwrap();
    let status = child.wait().unwrap();
    assert!(!status.success(), "an interrupted sweep must fail");
    assert!(
        rest.contains("interrupted: 1 of 8 points measured"),
        "{rest}"
    );
    let table = String::from_utf8(stdout.split_off(filler)).unwrap();
    assert!(stdout.iter().all(|&b| b == b'#'), "the filler comes first");
    let lines: Vec<&str> = table.lines().filter(|l| l.starts_with('|')).collect();
    let cells =
        |line: &str| -> Vec<String> { line.split('|').map(|c| c.trim().to_string()).collect() };
    let header = cells(lines[0]);
    let runs = header.iter().position(|c| c == "runs").unwrap();
    // Header, separator, and the one point whose frame was under way.
    assert_eq!(lines.len(), 3, "{table}");
    let point = cells(lines[2]);
    assert_eq!(
        point[header.iter().position(|c| c == "depth").unwrap()],
        "1"
    );
    assert_eq!(point[runs], "1", "{table}");
}

/// Whether process `pid` has a handler for SIGINT (the kernel's `SigCgt`
/// mask in `/proc/PID/status`; SIGINT is signal 2, bit 1).
#[cfg(target_os = "linux")]
fn catches_sigint(pid: u32) -> bool {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|line| line.strip_prefix("SigCgt:"))
        .and_then(|mask| u64::from_str_radix(mask.trim(), 16).ok())
        .is_some_and(|mask| mask & (1 << 1) != 0)
}

/// Polls `condition`, failing (not hanging) after a minute: a condition
/// that never comes is a bug to report.
#[cfg(target_os = "linux")]
fn wait_until(what: &str, condition: impl Fn() -> bool) {
    let start = std::time::Instant::now();
    while !condition() {
        assert!(
            start.elapsed() < std::time::Duration::from_secs(60),
            "gave up waiting for {what}"
        );
        std::thread::sleep(std::time::Duration::from_millis(1));
    }
}
