//! Comparison and benchmark matrix, end to end: `workbench compare` on a
//! small scene (metrics zero for the same settings, positive otherwise)
//! and `workbench bench` in every format, with and without `--matrix`.

use std::path::Path;

use crate::support::scenes::spheres_on_a_floor;
use crate::support::{scratch, workbench, workbench_ok, write};

/// `workbench compare` with `a` and `b` at 48x48, JSON metrics.
fn compare(dir: &Path, a: &str, b: &str) -> serde_json::Value {
    let scene = write(dir, "scene.p3f", &spheres_on_a_floor(48, 48, "", ""));
    let out = dir.join("compare.png");
    let stdout = workbench_ok(&[
        "compare",
        scene.to_str().unwrap(),
        "--a",
        a,
        "--b",
        b,
        "-o",
        out.to_str().unwrap(),
        "--format",
        "json",
    ]);
    // A | B | difference, 4 px apart, with a 4 px legend under a 4 px gap.
    let image = image::open(&out).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (3 * 48 + 8, 48 + 8));
    serde_json::from_str(&stdout).unwrap()
}

#[test]
fn the_same_settings_measure_zero() {
    let dir = scratch("compare-same");
    // Different structures, same image.
    let m = compare(&dir, "--accel none", "--accel grid --grid-m 3");
    assert_eq!(m["mse"], 0.0);
    assert_eq!(m["flip"], 0.0);
    assert!(m["psnr"].is_null(), "{m}");
    assert_eq!(m["a"]["label"], "no acceleration");
    assert_eq!(m["b"]["label"], "grid on, m = 3");
    assert_eq!(m["a"]["rays"], m["b"]["rays"]);
    assert!(m["time_ratio_a_over_b"].as_f64().unwrap() > 0.0);
}

#[test]
fn different_settings_measure_positive() {
    let dir = scratch("compare-different");
    let m = compare(&dir, "", "--soft-shadows --aa --spp 2");
    assert!(m["mse"].as_f64().unwrap() > 0.0, "{m}");
    assert!(m["flip"].as_f64().unwrap() > 0.0, "{m}");
    assert!(m["psnr"].as_f64().unwrap().is_finite(), "{m}");
    assert_eq!(m["b"]["label"], "AA 2x2, soft shadows on");
    assert_eq!(m["a"]["samples_per_pixel"], 1);
    assert_eq!(m["b"]["samples_per_pixel"], 4);
    assert_eq!(m["b"]["width"], 48);
}

#[test]
fn compare_prints_times_and_metrics_as_text() {
    let dir = scratch("compare-text");
    let scene = write(&dir, "scene.p3f", &spheres_on_a_floor(48, 48, "", ""));
    let out = dir.join("c.png");
    let stdout = workbench_ok(&[
        "compare",
        scene.to_str().unwrap(),
        "--width",
        "32",
        "--height",
        "24",
        "--b=--dof --aperture 4",
        "--heatmap",
        "abs",
        "-o",
        out.to_str().unwrap(),
    ]);
    for word in [
        "A: no DOF",
        "B: DOF aperture 4",
        "rays/s",
        "time A/B",
        "MSE",
        "PSNR",
        "FLIP",
    ] {
        assert!(stdout.contains(word), "{word}: {stdout}");
    }
    let image = image::open(&out).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (3 * 32 + 8, 24 + 4 + 4));
}

#[test]
fn a_bad_side_names_the_flag_and_writes_nothing() {
    let dir = scratch("compare-bad");
    let scene = write(&dir, "scene.p3f", &spheres_on_a_floor(48, 48, "", ""));
    let out = dir.join("c.png");
    let run = workbench(&[
        "compare",
        scene.to_str().unwrap(),
        "--a",
        "--aa --turbo",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("--a") && stderr.contains("'--turbo'"),
        "{stderr}"
    );
    assert!(!out.exists());

    let run = workbench(&["compare", scene.to_str().unwrap(), "--b", "--spp lots"]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("--spp") && stderr.contains("lots"),
        "{stderr}"
    );
}

/// `workbench bench` on the scene at 32x32, one run per row.
fn bench(dir: &Path, extra: &[&str]) -> String {
    let scene = write(dir, "scene.p3f", &spheres_on_a_floor(48, 48, "", ""));
    let mut args = vec![
        "bench",
        scene.to_str().unwrap(),
        "--runs",
        "1",
        "--width",
        "32",
        "--height",
        "32",
        "--spp",
        "2",
    ];
    args.extend_from_slice(extra);
    workbench_ok(&args)
}

#[test]
fn the_matrix_has_every_row_structures_agree_and_each_feature_shows() {
    let dir = scratch("matrix");
    let images = dir.join("images");
    let stdout = bench(
        &dir,
        &[
            "--matrix",
            "--format",
            "json",
            "--images",
            images.to_str().unwrap(),
        ],
    );
    let rows: Vec<serde_json::Value> = serde_json::from_str(&stdout).unwrap();
    assert_eq!(rows.len(), 18);
    let stems = [
        "",
        "_aa2",
        "_aa2_dof",
        "_soft",
        "_soft_aa2",
        "_soft_aa2_dof",
    ];
    for (i, accel) in ["none", "grid", "bvh"].into_iter().enumerate() {
        for (j, stem) in stems.iter().enumerate() {
            let row = &rows[i * 6 + j];
            assert_eq!(row["accel"], accel);
            assert_eq!(row["soft_shadows"], j >= 3);
            assert_eq!(row["antialiasing"], j % 3 != 0);
            assert_eq!(row["depth_of_field"], j % 3 == 2);
            assert_eq!(row["runs"], 1);
            assert!(row["rays"].as_u64().unwrap() > 0);
            let file = images.join(format!("{accel}{stem}.png"));
            assert!(file.exists(), "{}", file.display());
        }
    }
    let image = |name: &str| {
        image::open(images.join(format!("{name}.png")))
            .unwrap()
            .to_rgb8()
    };
    // The structures change the time, never the image.
    for stem in stems {
        let none = image(&format!("none{stem}"));
        assert_eq!(none.dimensions(), (32, 32));
        assert!(
            none == image(&format!("grid{stem}")),
            "grid differs from none for {stem}"
        );
        assert!(
            none == image(&format!("bvh{stem}")),
            "bvh differs from none for {stem}"
        );
        // A picture of the scene, not a blank or a flat fill.
        let colours = distinct_colours(&none);
        assert!(colours >= 32, "none{stem} has only {colours} colours");
    }
    // Each feature changes the image it is added to: soft shadows widen
    // the shadow's edge, anti-aliasing smooths the outlines, the lens blurs
    // what is out of focus.
    for (with, without) in [
        ("_aa2", ""),
        ("_aa2_dof", "_aa2"),
        ("_soft", ""),
        ("_soft_aa2", "_aa2"),
        ("_soft_aa2_dof", "_aa2_dof"),
    ] {
        let changed = pixels_differing(
            &image(&format!("bvh{with}")),
            &image(&format!("bvh{without}")),
        );
        assert!(
            changed >= 8,
            "bvh{with} differs from bvh{without} in only {changed} pixels"
        );
    }
}

fn distinct_colours(image: &image::RgbImage) -> usize {
    image
        .pixels()
        .map(|p| p.0)
        .collect::<std::collections::HashSet<_>>()
        .len()
}

/// Pixels where a channel differs by more than 8 levels.
fn pixels_differing(a: &image::RgbImage, b: &image::RgbImage) -> usize {
    a.pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > 8))
        .count()
}

#[test]
fn matrix_tables_in_markdown_and_csv() {
    let dir = scratch("matrix-tables");
    let md = bench(
        &dir,
        &["--matrix", "--structures", "grid", "--format", "md"],
    );
    let table: Vec<&str> = md.lines().filter(|l| l.starts_with('|')).collect();
    // Header, rule, six rows for one structure.
    assert_eq!(table.len(), 8, "{md}");
    let columns = table[0].matches('|').count();
    assert!(
        table.iter().all(|l| l.matches('|').count() == columns),
        "{md}"
    );
    assert!(table[0].contains("soft shadows") && table[0].contains("rays/s"));
    assert!(table[1].starts_with("|---|"));
    assert!(table[5].contains("| grid | yes | no | - |"), "{md}");

    let csv = bench(
        &dir,
        &["--matrix", "--structures", "none,bvh", "--format", "csv"],
    );
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 13, "{csv}");
    let width = lines[0].split(',').count();
    assert!(lines.iter().all(|l| l.split(',').count() == width), "{csv}");
    assert!(lines[1].starts_with("none,no,no,-,1,"), "{csv}");
    // Plain numbers: the rays column parses as an integer.
    let rays = lines[0].split(',').position(|h| h == "rays").unwrap();
    assert!(
        lines[1]
            .split(',')
            .nth(rays)
            .unwrap()
            .parse::<u64>()
            .is_ok()
    );
}

#[test]
fn the_plain_bench_keeps_one_row_per_structure_in_every_format() {
    let dir = scratch("bench-plain");
    let text = bench(&dir, &[]);
    for accel in ["none", "grid", "bvh"] {
        assert!(
            text.lines().any(|l| l.starts_with(accel)),
            "{accel}: {text}"
        );
    }
    assert!(text.contains("tests/ray") && text.contains("build ms"));

    let json = bench(&dir, &["--format", "json", "--structures", "bvh,grid"]);
    let rows: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["accel"], "bvh");
    assert_eq!(rows[1]["grid_multiplier"], 2.0);
    assert_eq!(rows[0]["samples_per_pixel"], 1);

    let csv = bench(&dir, &["--format", "csv"]);
    assert_eq!(csv.lines().count(), 4, "{csv}");
    let md = bench(&dir, &["--format", "md"]);
    assert_eq!(md.lines().filter(|l| l.starts_with('|')).count(), 5, "{md}");
}

#[test]
fn images_can_be_thumbnails() {
    let dir = scratch("bench-thumbnails");
    let scene = write(&dir, "scene.p3f", &spheres_on_a_floor(48, 48, "", ""));
    let images = dir.join("thumbs");
    workbench_ok(&[
        "bench",
        scene.to_str().unwrap(),
        "--runs",
        "1",
        "--structures",
        "bvh",
        "--width",
        "40",
        "--height",
        "20",
        "--images",
        images.to_str().unwrap(),
        "--thumbnail",
        "10",
    ]);
    let thumb = image::open(images.join("bvh.png")).unwrap().to_rgb8();
    assert_eq!(thumb.dimensions(), (10, 5));
}
