//! End-to-end tests: the real `workbench` binary on scene files.

use crate::support::scenes::RED_SPHERE_ON_A_BOX;
use crate::support::{scratch, workbench_fails, workbench_ok, write};

#[test]
fn render_writes_the_scene_as_a_png() {
    let dir = scratch("render");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let out = dir.join("small.png");
    let stdout = workbench_ok(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(stdout.contains("48x32"), "{stdout}");
    assert!(stdout.contains("1 sphere"), "{stdout}");

    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (48, 32));
    // The top rows see the sky: the background colour, written directly.
    assert_eq!(img.get_pixel(0, 0).0, [26, 51, 102]);
    // Above the centre the camera sees the red sphere.
    let centre = img.get_pixel(24, 11).0;
    assert!(centre[0] > 2 * centre[1] && centre[0] > 60, "{centre:?}");
    // The floor behind the sphere, away from the light, is in shadow:
    // darker than the lit floor in front of it.
    let lit = img.get_pixel(40, 30).0;
    let shadow = img.get_pixel(20, 19).0;
    assert!(lit[1] > 2 * shadow[1], "lit {lit:?} vs shadow {shadow:?}");
}

#[test]
fn overrides_change_the_size_and_stats_come_as_json() {
    let dir = scratch("json");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let out = dir.join("small.png");
    let stdout = workbench_ok(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--width",
        "20",
        "--height",
        "10",
        "--depth",
        "1",
        "--threads",
        "1",
        "--stats",
        "json",
    ]);
    let stats: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(stats["width"], 20);
    assert_eq!(stats["rays"]["eye"], 200);
    assert!(stats["rays"]["shadow"].as_u64().unwrap() > 0);
    assert!(stats["rays"]["reflection"].as_u64().unwrap() > 0);
    assert_eq!(image::open(&out).unwrap().to_rgb8().dimensions(), (20, 10));
}

#[test]
fn a_bad_scene_fails_with_file_line_and_column() {
    let dir = scratch("bad");
    let scene = write(&dir, "bad.p3f", "bclr 0 0 0\ns 0 0 0 zero\n");
    let out = dir.join("bad.png");
    let stderr = workbench_fails(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(stderr.contains("bad.p3f:2:9"), "{stderr}");
    assert!(!out.exists());
}

#[test]
fn a_missing_scene_and_an_unwritable_output_are_errors() {
    let stderr = workbench_fails(&["render", "/nonexistent/scene.p3f"]);
    assert!(stderr.contains("/nonexistent/scene.p3f"), "{stderr}");

    let dir = scratch("unwritable");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let stderr = workbench_fails(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        "/nonexistent/dir/out.png",
        "--width",
        "8",
        "--height",
        "8",
    ]);
    assert!(
        stderr.contains("cannot write image /nonexistent/dir/out.png"),
        "{stderr}"
    );
}

#[test]
fn help_lists_the_subcommands() {
    let out = workbench_ok(&["--help"]);
    for sub in ["render", "bench", "compare", "gen"] {
        assert!(out.contains(sub), "{out}");
    }
}
