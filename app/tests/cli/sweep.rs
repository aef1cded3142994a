//! `workbench sweep` end to end: a tiny grid-m study as CSV with its
//! chart, the level study on small levels, the spp study's error columns,
//! bad input, and Ctrl-C keeping what was measured.

use std::path::{Path, PathBuf};

#[cfg(target_os = "linux")]
use crate::support::interrupted;
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
/// fails. The signal lands after the handler is set and before any frame
/// ([`interrupted`]), so exactly one point of one frame is measured, on a
/// fast machine or a loaded one, with a tiny scene or a large one.
#[cfg(target_os = "linux")]
#[test]
fn ctrl_c_stops_after_the_frame_and_prints_what_was_measured() {
    let dir = scratch("sweep-interrupt");
    let scene = scene(&dir);
    let run = interrupted(
        &[
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
        ],
        "stopping after this frame",
    );
    assert!(!run.status.success(), "an interrupted sweep must fail");
    assert!(
        run.stderr.contains("interrupted: 1 of 8 points measured"),
        "{}",
        run.stderr
    );
    let table = run.stdout;
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
