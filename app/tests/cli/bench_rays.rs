//! `workbench bench --rays`: the structure alone on the Embree ray set,
//! end to end through the real binary and its JSON.

use crate::support::{scratch, workbench_fails, workbench_ok, write};
use serde_json::Value;

/// A floor filling the view from straight above, a light over it and one
/// under it (which no point of the floor faces).
const FLOOR: &str = "\
v
from 0 0 10
at 0 0 0
up 0 1 0
angle 40
resolution 40 30
l 0 0 20
l 0 0 -5
f 0.6 0.6 0.6 1 0 0 1 0 0 0 1
p 4
-100 -100 0  100 -100 0  100 100 0  -100 100 0
";

fn bench_json(scene: &str, extra: &[&str]) -> Value {
    let mut args = vec!["bench", scene, "--rays", "--format", "json", "--runs", "2"];
    args.extend_from_slice(extra);
    let stdout = workbench_ok(&args);
    serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("{e}: {stdout}"))
}

fn count(v: &Value, kind: &str, key: &str) -> u64 {
    v[kind][key]
        .as_u64()
        .unwrap_or_else(|| panic!("{kind}.{key} in {v}"))
}

fn number(v: &Value, kind: &str, key: &str) -> f64 {
    v[kind][key]
        .as_f64()
        .unwrap_or_else(|| panic!("{kind}.{key} in {v}"))
}

/// Every pixel sees the floor: one eye ray per pixel, all hit; one shadow
/// ray per hit (to the light above), none blocked; the rate is rays over
/// the median time, and the work per ray is counted.
#[test]
fn json_counts_one_eye_ray_per_pixel_and_a_shadow_ray_per_faced_light() {
    let dir = scratch("bench-rays");
    let scene = write(&dir, "floor.p3f", FLOOR);
    let v = bench_json(scene.to_str().unwrap(), &["--threads", "1"]);
    assert_eq!(v["structure"], "bvh", "{v}");
    assert_eq!(v["threads"], 1, "{v}");
    assert_eq!(count(&v, "eye", "rays"), 40 * 30);
    assert_eq!(count(&v, "eye", "hits"), 40 * 30);
    assert_eq!(count(&v, "shadow", "rays"), 40 * 30);
    assert_eq!(count(&v, "shadow", "hits"), 0);
    for kind in ["eye", "shadow"] {
        let rate = number(&v, kind, "rays_per_second");
        let expected = number(&v, kind, "rays") / number(&v, kind, "seconds");
        assert!((rate - expected).abs() <= 1e-6 * expected, "{kind}: {v}");
    }
    assert!(number(&v, "eye", "tests_per_ray") >= 1.0, "{v}");

    // --width and --height set the ray set's size.
    let v = bench_json(scene.to_str().unwrap(), &["--width", "17", "--height", "5"]);
    assert_eq!(count(&v, "eye", "rays"), 17 * 5);
    assert_eq!(count(&v, "shadow", "rays"), 17 * 5);
}

/// A sphere on the floor, lit from the side, shadows part of it: every
/// structure casts the same rays and finds the same hits and blocked rays.
#[test]
fn every_structure_finds_the_same_hits_and_shadows() {
    let dir = scratch("bench-rays-structures");
    let text = format!("{}s 0.5 0 1 1\n", FLOOR.replace("l 0 0 20", "l 8 0 20"));
    let scene = write(&dir, "sphere.p3f", &text);
    let scene = scene.to_str().unwrap();
    let results: Vec<Value> = ["none", "grid", "bvh"]
        .iter()
        .map(|s| bench_json(scene, &["--structure", s]))
        .collect();
    let blocked = count(&results[2], "shadow", "hits");
    assert!(blocked > 0, "the sphere's shadow: {}", results[2]);
    assert!(
        count(&results[2], "shadow", "rays") < 40 * 30,
        "its far side faces neither light"
    );
    for v in &results {
        for key in ["rays", "hits"] {
            for kind in ["eye", "shadow"] {
                assert_eq!(
                    count(v, kind, key),
                    count(&results[2], kind, key),
                    "{kind}.{key}: {v}"
                );
            }
        }
    }
    assert_eq!(
        results[0]["eye"]["nodes_per_ray"], 0.0,
        "brute force visits no node"
    );
}

#[test]
fn rays_refuse_two_structures_and_table_formats() {
    let dir = scratch("bench-rays-refused");
    let scene = write(&dir, "floor.p3f", FLOOR);
    let scene = scene.to_str().unwrap();
    let stderr = workbench_fails(&["bench", scene, "--rays", "--structure", "grid,bvh"]);
    assert!(stderr.contains("one structure"), "{stderr}");
    let stderr = workbench_fails(&["bench", scene, "--rays", "--format", "csv"]);
    assert!(stderr.contains("text or json"), "{stderr}");
}

/// The text table says what was measured (scene, size, structure,
/// threads, runs) and one row per kind of ray with the counts of the
/// JSON: 1200 eye rays that all hit, 1200 shadow rays none blocked.
#[test]
fn the_text_table_has_a_row_per_kind_with_its_counts() {
    let dir = scratch("bench-rays-text");
    let scene = write(&dir, "floor.p3f", FLOOR);
    let scene = scene.to_str().unwrap();
    let args = [
        "bench",
        scene,
        "--rays",
        "--runs",
        "2",
        "--structures",
        "bvh",
        "--threads",
        "1",
    ];
    let text = workbench_ok(&args);
    let mut lines = text.lines();
    let heading = lines.next().unwrap();
    assert!(
        heading.starts_with(&format!("{scene}: 40x30, bvh (built in "))
            && heading.ends_with(", 1 thread(s), median of 2 run(s) after a warm-up"),
        "{text}"
    );
    let header: Vec<&str> = lines
        .find(|l| l.starts_with("kind"))
        .unwrap()
        .split_whitespace()
        .collect();
    assert_eq!(
        header,
        [
            "kind",
            "rays",
            "hits",
            "ms",
            "min..max",
            "ms",
            "M",
            "rays/s",
            "nodes/ray",
            "tests/ray"
        ]
    );
    let row = |kind: &str| -> Vec<String> {
        text.lines()
            .find(|l| l.starts_with(kind))
            .unwrap_or_else(|| panic!("no {kind} row in {text}"))
            .split_whitespace()
            .map(str::to_string)
            .collect()
    };
    let (eye, shadow) = (row("eye"), row("shadow"));
    assert_eq!((&eye[1][..], &eye[2][..]), ("1200", "1200"), "{text}");
    assert_eq!((&shadow[1][..], &shadow[2][..]), ("1200", "0"), "{text}");
    // A rate and work per ray: numbers, the rate positive.
    for row in [&eye, &shadow] {
        let numbers: Vec<f64> = [&row[3], &row[5], &row[6], &row[7]]
            .iter()
            .map(|v| v.parse().unwrap_or_else(|_| panic!("{v} in {text}")))
            .collect();
        assert!(numbers[2] > 0.0, "{text}");
    }
}
