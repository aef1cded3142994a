//! End-to-end tests of the views: `render --view` and `compare --view`.

use crate::support::scenes::RED_SPHERE_ON_A_BOX;
use crate::support::{scratch, workbench, workbench_fails, workbench_ok, write};
use tracer::render::{HEAT_PALETTE, NO_VALUE};

#[test]
fn render_view_writes_a_heat_map_with_its_legend_and_numbers() {
    let dir = scratch("view-tests");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let out = dir.join("tests.png");
    let (scene, out_str) = (scene.to_str().unwrap(), out.to_str().unwrap());
    let stdout = workbench_ok(&[
        "render", scene, "-o", out_str, "--view", "tests", "--accel", "none", "--stats", "json",
    ]);
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let view = &json["view"];
    assert_eq!(view["name"], "tests");
    let number = |k: &str| view[k].as_f64().unwrap();
    let (median, p99, max) = (number("median"), number("p99"), number("max"));
    assert!(median > 0.0 && median <= p99 && p99 <= max, "{view}");
    assert_eq!(number("scale_top"), max);
    assert_eq!(view["pixels_with_value"], 48 * 32);
    // The mean over the pixels is the render's tests per pixel.
    let tests = json["intersection_tests"].as_f64().unwrap();
    assert!(
        (number("mean") - tests / (48.0 * 32.0)).abs() < 1e-3,
        "{view}"
    );

    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.width(), 48);
    assert!(img.height() > 32, "the legend goes under the image");
    // The top-left pixel sees the sky: its eye ray tested the 2 primitives.
    let expected = HEAT_PALETTE.colour((2.0 / max) as f32);
    assert_eq!(img.get_pixel(0, 0), &expected);
    // The legend bar runs over the whole palette.
    let bar = (0..img.height())
        .find(|&y| *img.get_pixel(47, y) == HEAT_PALETTE.colour(1.0) && y > 32)
        .expect("a legend bar");
    assert_eq!(img.get_pixel(0, bar), &HEAT_PALETTE.colour(0.0));
}

#[test]
fn render_views_scale_log_and_colour_views() {
    let dir = scratch("view-kinds");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let scene = scene.to_str().unwrap();
    let out = dir.join("v.png");
    let out_str = out.to_str().unwrap();

    // No structure: no steps anywhere.
    let stdout = workbench_ok(&[
        "render", scene, "-o", out_str, "--view", "steps", "--accel", "none",
    ]);
    assert!(
        stdout.contains("view steps: mean 0, median 0, p99 0, max 0"),
        "{stdout}"
    );

    // A fixed scale tops out: everything above it is the palette's end.
    workbench_ok(&[
        "render",
        scene,
        "-o",
        out_str,
        "--view",
        "rays",
        "--view-scale",
        "1",
    ]);
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.get_pixel(0, 0), &HEAT_PALETTE.colour(1.0));

    // Distance: the sky has no value.
    let stdout = workbench_ok(&[
        "render", scene, "-o", out_str, "--view", "distance", "--log",
    ]);
    assert!(stdout.contains("(log)"), "{stdout}");
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.get_pixel(0, 0).0, NO_VALUE[..3]);

    // Objects: a colour image without a legend, the sky black.
    let stdout = workbench_ok(&["render", scene, "-o", out_str, "--view", "objects"]);
    assert!(stdout.contains("view objects: colours"), "{stdout}");
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (48, 32));
    assert_eq!(img.get_pixel(0, 0).0, [0, 0, 0]);
    assert_ne!(
        img.get_pixel(24, 11),
        img.get_pixel(40, 30),
        "sphere vs floor"
    );

    let bad = workbench(&["render", scene, "-o", out_str, "--view", "cost"]);
    assert!(!bad.status.success());
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(
        stderr.contains("no view 'cost'") && stderr.contains("tests, steps"),
        "{stderr}"
    );
    // `=`: a separate "-3" would be refused as an unknown flag, not as
    // a scale.
    for scale in ["-3", "0"] {
        let flag = format!("--view-scale={scale}");
        let stderr = workbench_fails(&["render", scene, "-o", out_str, "--view", "tests", &flag]);
        assert!(
            stderr.contains(&format!("'{scale}' is not max, p99 or a positive number")),
            "{stderr}"
        );
    }
}

#[test]
fn compare_views_share_one_scale() {
    let dir = scratch("view-compare");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/balls_low.p3f");
    let out = dir.join("cmp.png");
    let stdout = workbench_ok(&[
        "compare",
        scene,
        "-o",
        out.to_str().unwrap(),
        "--width",
        "40",
        "--height",
        "30",
        "--a",
        "--accel none",
        "--b",
        "--accel bvh",
        "--view",
        "tests",
        "--format",
        "json",
    ]);
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let (a, b) = (&json["view"]["a"], &json["view"]["b"]);
    // One scale: the larger side's maximum.
    assert_eq!(a["scale_top"], b["scale_top"]);
    assert_eq!(a["scale_top"], a["max"]);
    assert!(
        a["mean"].as_f64().unwrap() > 3.0 * b["mean"].as_f64().unwrap(),
        "{json}"
    );
    // The difference is signed: brute force tests more everywhere, so
    // A - B is positive (red) wherever there is a difference, never blue.
    let d = &json["view"]["difference"];
    assert!(d["ratio"].as_f64().unwrap() > 3.0, "{json}");
    assert!(d["mean_abs_difference"].as_f64().unwrap() > 0.0, "{json}");
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.width(), 3 * 40 + 2 * 4);
    assert!(img.height() > 30);
    let panel = (2 * (40 + 4)..3 * 40 + 2 * 4).flat_map(|x| (0..30).map(move |y| (x, y)));
    let (mut red, mut blue) = (0, 0);
    for (x, y) in panel {
        let [r, _, b] = img.get_pixel(x, y).0;
        red += usize::from(r > 100 && r > b);
        blue += usize::from(b > 100 && b > r);
    }
    assert!(red > 100 && blue == 0, "red {red}, blue {blue}");
}

#[test]
fn inspect_prints_the_ray_tree_as_json_and_as_text() {
    let dir = scratch("inspect");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let scene = scene.to_str().unwrap();
    // Above the centre the eye ray meets the red sphere: object 1, after
    // the slab.
    let stdout = workbench_ok(&["inspect", scene, "--pixel", "24", "11", "--format", "json"]);
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(json["pixel"], serde_json::json!([24, 11]));
    let nodes = json["nodes"].as_array().unwrap();
    let eye = &nodes[0];
    assert_eq!(eye["kind"], "eye");
    assert_eq!(eye["parent"], serde_json::Value::Null);
    assert_eq!(eye["outcome"]["object_kind"], "sphere");
    assert_eq!(eye["outcome"]["object"], 1);
    assert_eq!(eye["outcome"]["line_column"], serde_json::json!([7, 1]));
    assert_eq!(eye["outcome"]["material"]["shine"], 40.0);
    // A shadow ray towards the one light, and a reflection (Ks > 0).
    let kinds: Vec<&str> = nodes.iter().map(|n| n["kind"].as_str().unwrap()).collect();
    assert!(
        kinds.contains(&"shadow") && kinds.contains(&"reflection"),
        "{kinds:?}"
    );
    for n in &nodes[1..] {
        let parent = n["parent"].as_u64().unwrap() as usize;
        assert!(parent < nodes.len());
    }
    // The parts add up to the colour.
    for c in 0..3 {
        let colour = json["colour"][c].as_f64().unwrap();
        let sum = json["sum_of_contributions"][c].as_f64().unwrap();
        assert!((colour - sum).abs() < 1e-4, "{json}");
    }

    // The floor behind the sphere is in its shadow: blocked by the sphere.
    let stdout = workbench_ok(&["inspect", scene, "--pixel", "20", "19"]);
    assert!(
        stdout.starts_with("pixel (20, 19), sample 0: colour"),
        "{stdout}"
    );
    assert!(stdout.contains("eye (depth 0): hit box #0"), "{stdout}");
    assert!(
        stdout.contains("  shadow to light 0: blocked by sphere #1"),
        "{stdout}"
    );

    let outside = workbench(&["inspect", scene, "--pixel", "48", "0"]);
    assert!(!outside.status.success());
    let stderr = String::from_utf8_lossy(&outside.stderr);
    assert!(stderr.contains("outside the 48x32 image"), "{stderr}");
    let no_sample = workbench(&["inspect", scene, "--pixel", "1", "1", "--sample", "1"]);
    assert!(!no_sample.status.success());
    let stderr = String::from_utf8_lossy(&no_sample.stderr);
    assert!(stderr.contains("1 sample(s) per pixel"), "{stderr}");
}

#[test]
fn render_overlay_draws_the_structure_over_the_image() {
    let dir = scratch("overlay");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let scene = scene.to_str().unwrap();
    let out = dir.join("o.png");
    let out_str = out.to_str().unwrap();
    let wire = |path: &std::path::Path| {
        let img = image::open(path).unwrap().to_rgb8();
        img.pixels().filter(|p| p.0 == [80, 255, 120]).count()
    };
    workbench_ok(&["render", scene, "-o", out_str]);
    assert_eq!(wire(&out), 0);
    workbench_ok(&["render", scene, "-o", out_str, "--overlay", "bvh:0"]);
    let root = wire(&out);
    assert!(root > 50, "{root}");
    workbench_ok(&["render", scene, "-o", out_str, "--overlay", "grid"]);
    let grid = wire(&out);
    assert!(
        grid > root,
        "the lattice draws more than one box: {grid} vs {root}"
    );
    // Over a view too, with the legend kept below.
    workbench_ok(&[
        "render",
        scene,
        "-o",
        out_str,
        "--overlay",
        "bvh:leaves",
        "--view",
        "tests",
    ]);
    assert!(wire(&out) > 0);
    for (bad, why) in [
        ("bvh:x", "'x' is not a depth (0 is the root) or 'leaves'"),
        ("octree", "'octree' is not bvh:DEPTH, bvh:leaves or grid"),
    ] {
        let stderr = workbench_fails(&["render", scene, "-o", out_str, "--overlay", bad]);
        assert!(stderr.contains(why), "{bad}: {stderr}");
    }
}

/// Cells of an inspected eye ray as `[x, y, z]`, from `inspect`'s JSON.
fn walked_cells(json: &serde_json::Value) -> Vec<[i64; 3]> {
    json["eye_visits"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| {
            assert_eq!(v["kind"], "cell", "{v}");
            let c = |i: usize| v["cell"][i].as_i64().unwrap();
            [c(0), c(1), c(2)]
        })
        .collect()
}

#[test]
fn inspect_lists_the_cells_and_nodes_the_eye_ray_visited() {
    let dir = scratch("inspect-visits");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let scene = scene.to_str().unwrap();
    let inspect = |accel: &str| {
        let stdout = workbench_ok(&[
            "inspect", scene, "--pixel", "24", "11", "--accel", accel, "--format", "json",
        ]);
        serde_json::from_str::<serde_json::Value>(&stdout).unwrap()
    };
    // The grid: an Amanatides-Woo walk, each cell a face neighbour of the
    // one before.
    let cells = walked_cells(&inspect("grid"));
    assert!(!cells.is_empty());
    for pair in cells.windows(2) {
        let steps: i64 = (0..3).map(|i| (pair[1][i] - pair[0][i]).abs()).sum();
        assert_eq!(steps, 1, "{cells:?}");
    }
    // The BVH: the root's box first, then boxes below it.
    let bvh = inspect("bvh");
    let visits = bvh["eye_visits"].as_array().unwrap();
    assert_eq!(visits[0]["kind"], "node");
    assert_eq!(visits[0]["depth"], 0);
    assert!(visits.iter().any(|v| v["kind"] == "leaf"), "{bvh}");
    assert!(
        visits[1..]
            .iter()
            .all(|v| v["depth"].as_u64().unwrap() >= 1)
    );
    assert!(inspect("none")["eye_visits"].as_array().unwrap().is_empty());

    let text = workbench_ok(&["inspect", scene, "--pixel", "24", "11", "--accel", "grid"]);
    let heading = format!("eye ray walked {} grid cells:", cells.len());
    assert!(text.contains(&heading), "{text}");
    let [x, y, z] = cells[0];
    assert!(
        text.contains(&format!("  cell ({x}, {y}, {z}), box (")),
        "{text}"
    );
}

#[test]
fn render_overlay_highlights_the_pixels_eye_ray_walk() {
    let dir = scratch("overlay-pixel");
    let scene = write(&dir, "small.p3f", RED_SPHERE_ON_A_BOX);
    let scene = scene.to_str().unwrap();
    let (plain, walk) = (dir.join("plain.png"), dir.join("walk.png"));
    let render = |out: &std::path::Path, extra: &[&str]| {
        let mut args = vec!["render", scene, "-o", out.to_str().unwrap()];
        args.extend_from_slice(extra);
        workbench_ok(&args);
        image::open(out).unwrap().to_rgb8()
    };
    for layer in ["grid", "bvh:1"] {
        let without = render(&plain, &["--overlay", layer]);
        let with = render(&walk, &["--overlay", layer, "--pixel", "24", "11"]);
        let changed: Vec<[u8; 3]> = without
            .pixels()
            .zip(with.pixels())
            .filter(|(a, b)| a != b)
            .map(|(_, b)| b.0)
            .collect();
        assert!(changed.len() > 20, "{layer}: {}", changed.len());
        // Only the walk's colours: yellow (first) through red (last).
        assert!(
            changed.iter().all(|&[r, _, b]| r == 255 && b <= 40),
            "{layer}: {changed:?}"
        );
        assert!(changed.contains(&[255, 230, 0]), "{layer}: the first visit");
    }
    // --sample picks the sample whose walk is drawn: through a wide lens
    // two samples of one pixel start far apart.
    let lens = [
        "--overlay",
        "grid",
        "--pixel",
        "24",
        "11",
        "--aa",
        "--spp",
        "4",
    ];
    let lens = [&lens[..], &["--aperture", "30"]].concat();
    let first = render(&walk, &[&lens[..], &["--sample", "0"]].concat());
    let last = render(&walk, &[&lens[..], &["--sample", "15"]].concat());
    assert_ne!(first, last, "another sample walks other cells");
    // --pixel draws on the overlay: without one it is refused, and
    // nothing is written.
    let refused = dir.join("refused.png");
    let stderr = workbench_fails(&[
        "render",
        scene,
        "-o",
        refused.to_str().unwrap(),
        "--pixel",
        "1",
        "1",
    ]);
    assert!(
        stderr.contains("required arguments were not provided") && stderr.contains("--overlay"),
        "{stderr}"
    );
    assert!(!refused.exists());
}
