//! Your own data in and out, end to end through the binary: a bare OBJ
//! rendered framed, the linear film as OpenEXR, and a reference image as
//! side B of `workbench compare`.

use crate::support::{scratch, workbench, write};

/// A unit cube of quads, with a red MTL material beside it.
const CUBE_OBJ: &str = "mtllib cube.mtl\nusemtl red\n\
    v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
    f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 3 7 8 4\nf 4 8 5 1\n";

fn stderr(run: &std::process::Output) -> String {
    String::from_utf8_lossy(&run.stderr).into_owned()
}

#[test]
fn a_bare_obj_renders_framed_in_its_mtl_colour() {
    let dir = scratch("bare-obj");
    write(&dir, "cube.mtl", "newmtl red\nKd 0.9 0.1 0.1\n");
    let obj = write(&dir, "cube.obj", CUBE_OBJ);
    let out = dir.join("cube.png");
    let run = workbench(&[
        "render",
        obj.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--width",
        "64",
        "--height",
        "48",
    ]);
    assert!(run.status.success(), "{}", stderr(&run));
    assert!(
        stderr(&run).contains("framed bare mesh"),
        "{}",
        stderr(&run)
    );
    let image = image::open(&out).unwrap().to_rgb8();
    // The cube fills the middle of the frame, red.
    let centre = image.get_pixel(32, 24).0;
    assert!(centre[0] > 2 * centre[1] && centre[0] > 60, "{centre:?}");
}

/// The EXR holds the film before encoding: encoded the way the PNG is,
/// it gives the PNG's pixels; and it keeps values the PNG clamps.
#[test]
fn exr_output_is_the_linear_film_before_encoding() {
    let dir = scratch("exr");
    // A light far brighter than 1 over a white sphere: highlights above 1.
    let scene = write(
        &dir,
        "bright.p3f",
        "v from 0 0 5 at 0 0 0 resolution 24 16\nl 0 3 5 4 4 4\n\
         f 1 1 1 1 1 1 1 1 20 0 1\ns 0 0 0 1.5\n",
    );
    let render = |name: &str| {
        let out = dir.join(name);
        let run = workbench(&[
            "render",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{}", stderr(&run));
        out
    };
    let png = image::open(render("out.png")).unwrap().to_rgb8();
    let exr = image::open(render("out.exr")).unwrap().to_rgb32f();
    assert_eq!(exr.dimensions(), (24, 16));
    let encode = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    for (p, e) in png.pixels().zip(exr.pixels()) {
        assert_eq!(p.0, e.0.map(encode));
    }
    let brightest = exr.pixels().flat_map(|p| p.0).fold(0.0f32, f32::max);
    assert!(brightest > 1.5, "{brightest}");
}

#[test]
fn a_reference_image_is_side_b() {
    let dir = scratch("b-image");
    let scene = write(
        &dir,
        "scene.p3f",
        "v from 0 0 5 at 0 0 0 resolution 32 24\nl 2 3 5\ns 0 0 0 1\n",
    );
    let scene = scene.to_str().unwrap();
    let reference = dir.join("reference.png");
    let run = workbench(&["render", scene, "-o", reference.to_str().unwrap()]);
    assert!(run.status.success(), "{}", stderr(&run));
    let out = dir.join("compare.png");
    let compare = |extra: &[&str]| {
        let mut args = vec![
            "compare",
            scene,
            "--b-image",
            reference.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--format",
            "json",
        ];
        args.extend_from_slice(extra);
        workbench(&args)
    };
    // The same render as the image: identical.
    let run = compare(&[]);
    assert!(run.status.success(), "{}", stderr(&run));
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(json["mse"], 0.0);
    assert!(json["psnr"].is_null(), "{json}");
    assert_eq!(
        image::open(&out).unwrap().to_rgb8().dimensions(),
        (3 * 32 + 8, 24 + 8)
    );
    // Anti-aliasing changes A: positive metrics against the same image.
    let run = compare(&["--a", "--aa --spp 3"]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert!(json["mse"].as_f64().unwrap() > 0.0, "{json}");
    // Another size is refused with both sizes, or fitted.
    let run = compare(&["--width", "64", "--height", "48"]);
    assert!(!run.status.success());
    assert!(
        stderr(&run).contains("32x24 but the render is 64x48"),
        "{}",
        stderr(&run)
    );
    let run = compare(&["--width", "64", "--height", "48", "--fit"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(json["b"]["resized_from"], serde_json::json!([32, 24]));
}

/// The bundled NFF scene and PLY mesh through the binary: every kind of
/// object they hold is counted, and the image shows more than its
/// background.
#[test]
fn the_bundled_nff_scene_and_ply_mesh_render() {
    let dir = scratch("bundled-nff-ply");
    let scenes = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/");
    for (file, objects, triangles) in [
        (
            "nff_classic.nff",
            serde_json::json!({"cone": 1, "polygon": 1, "sphere": 2}),
            2,
        ),
        // The pyramid's six faces, on the ground plane the framing adds.
        (
            "ply_pyramid.ply",
            serde_json::json!({"mesh": 1, "plane": 1}),
            6,
        ),
    ] {
        let out = dir.join(format!("{file}.png"));
        let scene = format!("{scenes}{file}");
        let args = [
            "render",
            &scene,
            "-o",
            out.to_str().unwrap(),
            "--stats",
            "json",
        ];
        let run = workbench(&args);
        assert!(run.status.success(), "{file}: {}", stderr(&run));
        let stats: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
        assert_eq!(stats["scene"]["objects"], objects, "{file}");
        assert_eq!(stats["scene"]["triangles"], triangles, "{file}");
        let image = image::open(&out).unwrap().to_rgb8();
        let colours: std::collections::HashSet<[u8; 3]> = image.pixels().map(|p| p.0).collect();
        assert!(colours.len() > 50, "{file}: {} colours", colours.len());
    }
}
