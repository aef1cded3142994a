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

/// Total internal reflection in a rendered pixel: an eye ray enters a
/// glass box's top at a grazing angle, refracts steeply, and meets a side
/// face from inside beyond the critical angle (48.5 degrees against 41.8
/// for ior 1.5): that hit reports it, and spawns a reflection and no
/// refraction. With ior 1 nothing bends and nothing is reflected totally.
#[test]
fn a_grazing_ray_into_glass_is_reflected_totally_inside() {
    let dir = scratch("render-tir");
    let scene = write(
        &dir,
        "glass_box.p3f",
        "bclr 0.2 0.3 0.5\nv\nfrom 0 -6 2.3\nat 0 0 2\nup 0 0 1\nangle 30\nhither 0.01\n\
         resolution 41 41\nl 4 -3 6 1 1 1\nf 1 1 1 0.1 1 1 1 0.1 100 0.9 1.5\nbox -1 -1 0 1 1 2\n",
    );
    let scene = scene.to_str().unwrap();
    let inspect = |extra: &[&str]| -> Vec<serde_json::Value> {
        let mut args = vec!["inspect", scene, "--pixel", "20", "20", "--format", "json"];
        args.extend(extra);
        let json: serde_json::Value = serde_json::from_str(&workbench_ok(&args)).unwrap();
        json["nodes"].as_array().unwrap().clone()
    };
    let totally = |nodes: &[serde_json::Value]| -> Vec<usize> {
        (0..nodes.len())
            .filter(|&i| nodes[i]["outcome"]["total_internal_reflection"] == true)
            .collect()
    };
    let nodes = inspect(&[]);
    let tir = totally(&nodes);
    let first = *tir.first().expect("a total internal reflection");
    assert_eq!(
        nodes[first]["kind"], "refraction",
        "the ray inside the glass"
    );
    assert_eq!(nodes[first]["outcome"]["from_inside"], true);
    assert_eq!(nodes[first]["outcome"]["fresnel"], 1.0);
    let children: Vec<&serde_json::Value> = nodes
        .iter()
        .filter(|n| n["parent"] == first)
        .map(|n| &n["kind"])
        .collect();
    assert!(
        children.contains(&&serde_json::json!("reflection")),
        "{children:?}"
    );
    assert!(
        !children.contains(&&serde_json::json!("refraction")),
        "{children:?}"
    );
    assert!(totally(&inspect(&["--set", "object 0 ior 1"])).is_empty());
}
