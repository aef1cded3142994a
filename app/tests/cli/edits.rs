//! Scene edits from the command line (`--set`, `--save-scene`, `sweep
//! --param object:N:ior`) end to end: the same image as the file edited by
//! hand, a saved scene that renders the same, an edit undone by its
//! inverse, structures that agree on a moved object, refusals that say
//! why and write nothing, and a material sweep.

use std::path::{Path, PathBuf};

use tracer::scene::edit::Edit;
use tracer::scene::{Limits, parse_scene};

use crate::support::scenes::spheres_on_a_floor;
use crate::support::{scratch, workbench, workbench_fails, workbench_ok, write};

/// Objects: 0 the mirror floor, 1 the red sphere, 2 the glass sphere, 3 a
/// small glass sphere sharing 2's material. Light 0 is the scene's one.
const EXTRA: &str = "s 0 2 0.5 0.5";

fn scene(dir: &Path) -> PathBuf {
    write(dir, "scene.p3f", &spheres_on_a_floor(48, 32, "", EXTRA))
}

/// The pixels of `render scene -o name.png FLAGS...`.
fn render(dir: &Path, scene: &Path, name: &str, flags: &[&str]) -> Vec<u8> {
    let out = dir.join(format!("{name}.png"));
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend(flags);
    workbench_ok(&args);
    image::open(&out).unwrap().to_rgb8().into_raw()
}

/// `--set` makes the image of the file edited by hand: a material shared
/// by two spheres changed for one of them, a sphere moved, the light moved
/// and recoloured, the lens opened.
#[test]
fn set_gives_the_image_of_the_scene_edited_by_hand() {
    let dir = scratch("edits-by-hand");
    let scene = scene(&dir);
    let edited = render(
        &dir,
        &scene,
        "set",
        &[
            "--set",
            "object 2 ior 1.33",
            "--set",
            "object 1 translate 0.5 0 0",
            "--set",
            "light 0 position 3 -2 5",
            "--set",
            "light 0 colour 1 0.9 0.8",
            "--set",
            "camera aperture 2",
        ],
    );
    let by_hand = spheres_on_a_floor(48, 32, "aperture 2", "")
        .replace("l 4 -3 6 1 1 1", "l 3 -2 5 1 0.9 0.8")
        .replace("s -1 1 1 1", "s -0.5 1 1 1")
        .replace(
            "s 1.2 -1 0.8 0.8",
            "f 1 1 1 0.1 1 1 1 0.2 100 0.8 1.33\ns 1.2 -1 0.8 0.8\n\
             f 1 1 1 0.1 1 1 1 0.2 100 0.8 1.5\ns 0 2 0.5 0.5",
        );
    let by_hand = write(&dir, "by_hand.p3f", &by_hand);
    assert_eq!(edited, render(&dir, &by_hand, "by_hand", &[]));
    assert_ne!(edited, render(&dir, &scene, "plain", &[]));
}

/// `--save-scene` writes the edited scene; rendering that file gives the
/// edited render byte for byte.
#[test]
fn a_saved_scene_renders_as_the_edited_one() {
    let dir = scratch("edits-save");
    let scene = scene(&dir);
    let saved = dir.join("saved.p3f");
    let edited = render(
        &dir,
        &scene,
        "edited",
        &[
            "--set",
            "object 3 kd 0.9",
            "--set",
            "object 0 translate 0 0 -0.25",
            "--set",
            "light 0 add al 0 0 6 0 0 0 1 1 0.5 0.5 0.5",
            "--save-scene",
            saved.to_str().unwrap(),
        ],
    );
    let text = std::fs::read_to_string(&saved).unwrap();
    assert!(text.contains("al 0 0 6 0 0 0 1 1 0.5 0.5 0.5"), "{text}");
    assert_eq!(render(&dir, &saved, "reopened", &[]), edited);
}

/// Each edit, then the inverse the library gives for it (its `--set`
/// line), renders the original image byte for byte.
#[test]
fn an_edit_then_its_inverse_gives_the_original_image() {
    let dir = scratch("edits-inverse");
    let scene = scene(&dir);
    let original = render(&dir, &scene, "original", &[]);
    let mut document = parse_scene(
        &std::fs::read_to_string(&scene).unwrap(),
        None,
        &Limits::default(),
    )
    .unwrap();
    let edits = [
        "object 3 ior 1.2",
        "material 1 diffuse 0.1 0.8 0.1",
        "object 0 translate 0.3 0.1 -0.2",
        "object 2 radius 0.6",
        "light 0 remove",
        "camera from 0.5 -6 3",
    ];
    for text in edits {
        let edit: Edit = text.parse().unwrap();
        let inverse = edit.apply(&mut document).unwrap().to_string();
        let flags = ["--set", text, "--set", &inverse];
        let undone = render(&dir, &scene, "undone", &flags);
        assert!(undone == original, "'{text}' then '{inverse}'");
        assert_ne!(
            render(&dir, &scene, "edited", &flags[..2]),
            original,
            "{text}"
        );
    }
}

/// None, the grid and the BVH give one image of a scene with moved
/// objects.
#[test]
fn moving_an_object_keeps_none_grid_and_bvh_identical() {
    let dir = scratch("edits-structures");
    let scene = scene(&dir);
    let moves = [
        "--set",
        "object 1 translate 0.7 -0.4 0.2",
        "--set",
        "object 3 centre -1.5 -1 0.5",
        "--set",
        "object 0 translate 0 0 0.1",
    ];
    let image = |accel: &str| {
        let mut flags = moves.to_vec();
        flags.extend(["--accel", accel]);
        render(&dir, &scene, accel, &flags)
    };
    let none = image("none");
    assert!(image("grid") == none, "grid differs from none");
    assert!(image("bvh") == none, "bvh differs from none");
    assert_ne!(none, render(&dir, &scene, "unmoved", &[]));
}

/// A bad `--set` is refused with what is wrong, nothing is written and
/// the exit status is not zero.
#[test]
fn bad_set_values_are_refused_with_the_message() {
    let dir = scratch("edits-refused");
    let scene = scene(&dir);
    let scene = scene.to_str().unwrap();
    let out = dir.join("out.png");
    let saved = dir.join("saved.p3f");
    let cases = [
        (
            "object 4 kd 0.5",
            "object 4: the scene has 4 objects (0..3)",
        ),
        (
            "object 2 iorr 1.3",
            "no field 'iorr' for a sphere; fields: diffuse, kd, specular, ks, shine, t, ior, \
             centre, radius, translate, shape, own, share",
        ),
        (
            "object 0 radius 1",
            "no field 'radius' for a polygon; fields: diffuse, kd, specular, ks, shine, t, ior, \
             translate, shape, own, share",
        ),
        (
            "object 1 radius 0",
            "invalid sphere radius: must not be zero",
        ),
        (
            "object 2 t 1.5",
            "invalid transmittance: must lie in 0..1, found 1.5",
        ),
        ("object 2 ior nan", "ior must be a finite number, found nan"),
        (
            "light 1 position 0 0 0",
            "light 1: the scene has 1 light (0)",
        ),
        (
            "camera at 0 -7 2.5",
            "invalid camera: `from` and `at` are the same point",
        ),
        (
            "sphere 2 ior 1",
            "unknown edit 'sphere': an edit starts with object, material, light or camera",
        ),
    ];
    for (set, message) in cases {
        let run = workbench(&[
            "render",
            scene,
            "-o",
            out.to_str().unwrap(),
            "--set",
            set,
            "--save-scene",
            saved.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "--set '{set}' was accepted");
        assert!(
            stderr.contains(&format!("--set '{set}': {message}")),
            "--set '{set}': {stderr}"
        );
        assert!(
            !out.exists() && !saved.exists(),
            "--set '{set}' wrote a file"
        );
    }
    // Inside a side's flags too.
    let refused = workbench_fails(&[
        "compare",
        scene,
        "-o",
        out.to_str().unwrap(),
        "--b",
        "--set 'object 9 kd 1'",
    ]);
    assert!(
        refused.contains("--b \"--set 'object 9 kd 1'\"")
            && refused.contains("object 9: the scene has 4 objects (0..3)"),
        "{refused}"
    );
    assert!(!out.exists());
}

/// `compare` applies `--set` to both sides and a side's own `--set` to that
/// side, and labels B by its edit.
#[test]
fn compare_applies_edits_to_both_sides_and_per_side() {
    let dir = scratch("edits-compare");
    let scene = scene(&dir);
    let scene = scene.to_str().unwrap();
    let out = dir.join("compare.png");
    let compare = |flags: &[&str]| {
        let mut args = vec![
            "compare",
            scene,
            "-o",
            out.to_str().unwrap(),
            "--format",
            "json",
        ];
        args.extend(flags);
        let json: serde_json::Value = serde_json::from_str(&workbench_ok(&args)).unwrap();
        json
    };
    let per_side = compare(&["--b", "--set 'object 2 ior 1.33'"]);
    assert_eq!(per_side["b"]["label"], "sphere #2 ior 1.33", "{per_side}");
    assert!(per_side["mse"].as_f64().unwrap() > 0.0, "{per_side}");
    // The same edit on both sides, or for both: identical images.
    let both = compare(&[
        "--a",
        "--set 'object 2 ior 1.33'",
        "--b",
        "--set \"object 2 ior 1.33\"",
    ]);
    assert_eq!(both["mse"], 0.0, "{both}");
    let shared = compare(&["--set", "object 2 ior 1.33", "--b", "--accel grid"]);
    assert_eq!(shared["mse"], 0.0, "{shared}");
    // B with the edit is the render with it.
    let b_image = dir.join("b.png");
    let edited = render(&dir, Path::new(scene), "b", &["--set", "object 2 ior 1.33"]);
    let against = workbench_ok(&[
        "compare",
        scene,
        "-o",
        out.to_str().unwrap(),
        "--a",
        "--set 'object 2 ior 1.33'",
        "--b-image",
        b_image.to_str().unwrap(),
        "--format",
        "json",
    ]);
    let against: serde_json::Value = serde_json::from_str(&against).unwrap();
    assert_eq!(against["mse"], 0.0, "{against}");
    assert!(!edited.is_empty());
}

/// `inspect`, `bench`, `sweep` and `observe` trace the edited scene.
#[test]
fn inspect_bench_sweep_and_observe_see_the_edits() {
    let dir = scratch("edits-others");
    let scene = scene(&dir);
    let scene = scene.to_str().unwrap();
    // Pixel (30, 20) sees the glass sphere, object 2.
    let inspect = |flags: &[&str]| {
        let mut args = vec!["inspect", scene, "--pixel", "30", "20"];
        args.extend(flags);
        workbench_ok(&args)
    };
    let plain = inspect(&[]);
    assert!(
        plain.contains("sphere #2") && plain.contains("ior 1.5;"),
        "{plain}"
    );
    let edited = inspect(&["--set", "object 2 ior 1.33"]);
    assert!(edited.contains("ior 1.33;"), "{edited}");

    let rays = |flags: &[&str]| {
        let mut args = vec![
            "bench",
            scene,
            "--runs",
            "1",
            "--structures",
            "bvh",
            "--format",
            "json",
        ];
        args.extend(flags);
        let json: serde_json::Value = serde_json::from_str(&workbench_ok(&args)).unwrap();
        json[0]["rays"].as_u64().unwrap()
    };
    // Opaque glass spawns no refraction rays.
    assert!(rays(&["--set", "material 2 t 0"]) < rays(&[]));

    let sweep = |flags: &[&str]| {
        let mut args = vec![
            "sweep", scene, "--param", "depth", "--values", "1", "--runs", "1", "--format", "json",
        ];
        args.extend(flags);
        let json: serde_json::Value = serde_json::from_str(&workbench_ok(&args)).unwrap();
        json[0]["rays"].as_u64().unwrap()
    };
    assert!(sweep(&["--set", "material 2 t 0"]) < sweep(&[]));

    let figure = dir.join("figure.png");
    let observed = |flags: &[&str]| {
        let mut args = vec![
            "observe",
            scene,
            "-o",
            figure.to_str().unwrap(),
            "--pixel",
            "30",
            "20",
            "--format",
            "json",
        ];
        args.extend(flags);
        let json: serde_json::Value = serde_json::from_str(&workbench_ok(&args)).unwrap();
        json["pixels"][0]["rays"].as_u64().unwrap()
    };
    assert!(observed(&["--set", "material 2 t 0"]) < observed(&[]));
}

/// `sweep --param object:N:ior` prints a row per value, with the rays by
/// kind, and charts them.
#[test]
fn sweep_param_object_ior_prints_a_row_per_value() {
    let dir = scratch("edits-sweep");
    let scene = scene(&dir);
    let chart = dir.join("ior.png");
    let csv = workbench_ok(&[
        "sweep",
        scene.to_str().unwrap(),
        "--param",
        "object:2:ior",
        "--values",
        "1..2:0.25",
        "--structures",
        "bvh",
        "--runs",
        "1",
        "--format",
        "csv",
        "--plot",
        chart.to_str().unwrap(),
    ]);
    let lines: Vec<&str> = csv.lines().collect();
    assert!(
        lines[0].starts_with("accel,object:2:ior,")
            && lines[0].ends_with(",reflection rays,refraction rays"),
        "{csv}"
    );
    let values: Vec<&str> = lines[1..]
        .iter()
        .map(|l| l.split(',').nth(1).unwrap())
        .collect();
    assert_eq!(values, ["1", "1.25", "1.5", "1.75", "2"], "{csv}");
    // The index of refraction bends the rays: not every value spawns the
    // same refraction rays.
    let refraction: Vec<&str> = lines[1..]
        .iter()
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert!(refraction.iter().any(|r| *r != refraction[0]), "{csv}");
    let (w, h) = image::image_dimensions(&chart).unwrap();
    assert_eq!((w, h), (1600, 500), "two panels: time and rays by kind");

    let bad = workbench_fails(&[
        "sweep",
        scene.to_str().unwrap(),
        "--param",
        "object:2:ior",
        "--values",
        "0..1:0.5",
    ]);
    assert!(
        bad.contains("object:2:ior = 0")
            && bad.contains("invalid index of refraction: must be greater than 0"),
        "{bad}"
    );
    let missing = workbench_fails(&["sweep", scene.to_str().unwrap(), "--param", "object:7:kd"]);
    assert!(
        missing.contains("object 7: the scene has 4 objects (0..3)"),
        "{missing}"
    );
    let unknown = workbench_fails(&["sweep", scene.to_str().unwrap(), "--param", "object:2:iorr"]);
    assert!(
        unknown.contains("object:N:FIELD with FIELD one of kd, ks, shine, t, ior"),
        "{unknown}"
    );
}
