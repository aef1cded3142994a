//! `workbench observe` end to end: the figure as a PNG, the segments as
//! JSON (the pixel's rays in number and kind, the eye ray from the camera),
//! and bad input refused with the value and the valid range.

use serde_json::Value;

use crate::support::scenes::RED_SPHERE_ON_A_BOX;
use crate::support::{Watchdog, scratch, workbench, workbench_fails, workbench_ok, write};

fn observe(scene: &str, out: &str, extra: &[&str]) -> Value {
    let mut args = vec!["observe", scene, "-o", out, "--format", "json"];
    args.extend(extra);
    serde_json::from_str(&workbench_ok(&args)).unwrap()
}

#[test]
fn the_figure_draws_the_pixels_rays_from_the_camera() {
    let dir = scratch("observe-json");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let scene = scene.to_str().unwrap();
    let out = dir.join("figure.png");
    let out = out.to_str().unwrap();
    let json = observe(scene, out, &["--pixel", "24", "11", "--size", "160", "120"]);
    let figure = image::open(out).unwrap();
    assert_eq!((figure.width(), figure.height()), (160, 120));

    let segments = json["segments"].as_array().unwrap();
    let rays: Vec<&Value> = segments
        .iter()
        .filter(|s| s["part"] == "ray" || s["part"] == "blocked_shadow")
        .collect();
    // The same rays as `inspect` records for that pixel, in its order.
    let tree: Value = serde_json::from_str(&workbench_ok(&[
        "inspect", scene, "--pixel", "24", "11", "--format", "json",
    ]))
    .unwrap();
    let nodes = tree["nodes"].as_array().unwrap();
    assert_eq!(json["pixels"][0]["rays"], nodes.len());
    let first_pieces: Vec<&Value> = {
        // A segment cut where it is hidden shows as several pieces.
        let mut seen = std::collections::BTreeSet::new();
        rays.iter()
            .copied()
            .filter(|s| seen.insert(s["segment"].as_u64().unwrap()))
            .collect()
    };
    assert_eq!(first_pieces.len(), nodes.len());
    for (segment, node) in first_pieces.iter().zip(nodes) {
        let kind = if segment["part"] == "blocked_shadow" {
            "shadow"
        } else {
            segment["kind"].as_str().unwrap()
        };
        assert_eq!(kind, node["kind"], "{segment}");
        assert_eq!(segment["depth"], node["depth"]);
    }
    // The eye ray starts at the camera (the scene's `from`, 0 -6 2).
    let eye = first_pieces[0];
    assert_eq!(eye["kind"], "eye");
    let from: Vec<f64> = serde_json::from_value(eye["from"].clone()).unwrap();
    assert!(
        (from[1] + 6.0).abs() < 1e-4 && (from[2] - 2.0).abs() < 1e-4,
        "{from:?}"
    );
    // The camera's frustum and its light are in the figure too.
    for part in ["frustum", "image_plane", "light"] {
        assert!(segments.iter().any(|s| s["part"] == part), "no {part}");
    }
    // The pixels of a row: one tree each.
    let row = observe(scene, out, &["--pixel", "24", "11", "--pixels", "row:20"]);
    assert!(
        row["pixels"].as_array().unwrap().len() > 8,
        "{}",
        row["pixels"]
    );
    // A text summary without --format.
    let text = workbench_ok(&["observe", scene, "-o", out, "--pixel", "24", "11"]);
    assert!(
        text.contains("1 pixel(s)") && text.contains("segments"),
        "{text}"
    );
}

#[test]
fn bad_observer_input_names_the_value_and_writes_nothing() {
    let dir = scratch("observe-bad");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let scene = scene.to_str().unwrap();
    let out = dir.join("figure.png");
    let out = out.to_str().unwrap();
    let fails = |extra: &[&str]| {
        let mut args = vec!["observe", scene, "-o", out];
        args.extend(extra);
        workbench_fails(&args)
    };
    let outside = fails(&["--pixel", "48", "5"]);
    assert!(
        outside.contains("--pixel 48 5 is outside the 48 x 32 image")
            && outside.contains("x in 0..47"),
        "{outside}"
    );
    let same = fails(&[
        "--pixel", "1", "1", "--from", "1", "2", "3", "--at", "1", "2", "3",
    ]);
    assert!(same.contains("are the same point"), "{same}");
    let along = fails(&[
        "--pixel", "1", "1", "--from", "0", "0", "5", "--at", "0", "0", "0", "--up", "0", "0", "1",
    ]);
    assert!(along.contains("--up") && along.contains("along"), "{along}");
    let pattern = fails(&["--pixel", "1", "1", "--pixels", "rows:4"]);
    assert!(
        pattern.contains("'rows:4' is not row:Y, column:X or grid:STEP"),
        "{pattern}"
    );
    let row = fails(&["--pixel", "1", "1", "--pixels", "row:40"]);
    assert!(
        row.contains("row 40 is outside the image: rows 0..31"),
        "{row}"
    );
    assert!(!std::path::Path::new(out).exists(), "nothing written");
}

/// A course file's trap: `accel 0` over a large mesh (the course's dragon
/// is 100 000 triangles; this one is 199 712) at 512 x 512. The figure and
/// its image plane are traced with a BVH whatever the file says, so the
/// run takes seconds (brute force ran for over 10 minutes, and here would
/// meet the runner's kill timeout); the pixel's rays follow the file's
/// brute force, which the warning says.
#[test]
fn a_large_brute_force_scene_is_observed_in_seconds_with_a_warning() {
    let dir = scratch("observe-brute");
    let scene = write(&dir, "terrain.p3f", &large_brute_force_scene());
    let scene = scene.to_str().unwrap();
    let out = dir.join("figure.png");
    let out = out.to_str().unwrap();
    let run = workbench(&[
        "observe", scene, "-o", out, "--pixel", "256", "300", "--size", "160", "120", "--format",
        "json",
    ]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains("no acceleration structure (accel 0) over 199712 primitives")
            && stderr.contains("traced with a BVH"),
        "{stderr}"
    );
    let json: Value = serde_json::from_slice(&run.stdout).unwrap();
    assert!(json["pixels"][0]["rays"].as_u64().unwrap() >= 2, "{json}");
    assert_eq!(image::open(out).unwrap().width(), 160);
}

/// `sweep` says so before it renders a point brute force over a large
/// scene; stopped once it has.
#[test]
fn a_sweep_with_brute_force_over_a_large_scene_warns_first() {
    use std::io::{BufRead, BufReader};
    use std::process::{Command, Stdio};

    let dir = scratch("sweep-brute");
    let scene = write(&dir, "terrain.p3f", &large_brute_force_scene());
    let mut child = Command::new(crate::support::workbench_exe())
        .args([
            "sweep",
            scene.to_str().unwrap(),
            "--param",
            "depth",
            "--values",
            "1",
        ])
        .args(["--runs", "1", "--structures", "none"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let _watchdog = Watchdog::new(child.id());
    let mut said = String::new();
    for line in BufReader::new(child.stderr.take().unwrap()).lines() {
        let line = line.unwrap();
        said.push_str(&line);
        said.push('\n');
        if line.starts_with("warning:") {
            break;
        }
    }
    let _ = child.kill();
    let _ = child.wait();
    assert!(
        said.contains("no acceleration structure (accel 0) over 199712 primitives")
            && said.contains("leave `none` out of --structures"),
        "{said}"
    );
}

/// A terrain of 199 712 triangles in one mesh under one light, 512 x 512,
/// `accel 0`: brute force would test every ray against every triangle.
fn large_brute_force_scene() -> String {
    use std::fmt::Write;
    const SIDE: usize = 317;
    let mut text = String::from(
        "accel 0\nbclr 0.1 0.2 0.4\nv\nfrom 0 -3 2\nat 0 0 0\nup 0 0 1\nangle 45\n\
         hither 0.01\nresolution 512 512\nl 2 -2 4 1 1 1\nf 0.6 0.5 0.4 0.8 1 1 1 0.1 10 0 1\n",
    );
    let cells = SIDE - 1;
    writeln!(text, "mesh {} {}", SIDE * SIDE, 2 * cells * cells).unwrap();
    for j in 0..SIDE {
        for i in 0..SIDE {
            let (x, y) = (
                i as f32 / cells as f32 * 4.0 - 2.0,
                j as f32 / cells as f32 * 4.0 - 2.0,
            );
            let z = 0.2 * (3.0 * x).sin() * (2.0 * y).cos();
            writeln!(text, "{x} {y} {z}").unwrap();
        }
    }
    for j in 0..cells {
        for i in 0..cells {
            let a = j * SIDE + i + 1;
            let (b, c, d) = (a + 1, a + SIDE, a + SIDE + 1);
            writeln!(text, "{a} {b} {d}\n{a} {d} {c}").unwrap();
        }
    }
    text
}
