//! Adaptive anti-aliasing from the command line: its flags on `render`,
//! `compare`, `bench` and `sweep`, what `render --stats json` says of the
//! samples, and `bench --to-error`.

use crate::lessons::lesson_file;
use crate::support::scenes::spheres_on_a_floor;
use crate::support::{Scratch, scratch, workbench_fails, workbench_ok, write};

/// Spheres over a floor, 32 x 24, one sample per pixel unless told.
fn scene(dir: &Scratch) -> String {
    let path = write(dir, "scene.p3f", &spheres_on_a_floor(32, 24, "", ""));
    path.to_str().unwrap().to_string()
}

/// `render --stats json` with `flags`: the statistics and the PNG's bytes.
fn render(dir: &Scratch, scene: &str, flags: &[&str]) -> (serde_json::Value, Vec<u8>) {
    let rendered = render_to(scene, &dir.join("out.png"), flags);
    (rendered.stats, rendered.png)
}

fn spp(stats: &serde_json::Value) -> (f64, u64) {
    let spp = &stats["samples_per_pixel"];
    (spp["mean"].as_f64().unwrap(), spp["max"].as_u64().unwrap())
}

#[test]
fn render_spends_adaptive_samples_where_the_flags_say() {
    let dir = scratch("adaptive-render");
    let scene = scene(&dir);
    let (uniform, uniform_png) = render(&dir, &scene, &["--aa", "--spp", "4"]);
    assert_eq!(spp(&uniform), (16.0, 16));
    assert!(uniform["adaptive"].is_null(), "{uniform}");

    // Adaptive turns anti-aliasing on: (2N)^2 = 64 at most, at least 4.
    let (adaptive, adaptive_png) = render(&dir, &scene, &["--spp", "4", "--sampling", "adaptive"]);
    let (mean, max) = spp(&adaptive);
    assert!(mean > 4.0 && mean < 64.0, "{adaptive}");
    assert!(max > 4 && max <= 64, "{adaptive}");
    assert_ne!(adaptive_png, uniform_png);
    let estimate = &adaptive["adaptive"];
    assert_eq!(estimate["active_pixels"], 0, "{adaptive}");
    let error = estimate["error_estimate"].as_f64().unwrap();
    assert!(error > 0.0 && error < 0.02, "{adaptive}");

    // A looser threshold takes fewer samples and leaves more error.
    let (loose, _) = render(&dir, &scene, &["--spp", "4", "--noise-threshold", "0.05"]);
    assert!(spp(&loose).0 < mean, "{loose}");
    assert!(loose["adaptive"]["error_estimate"].as_f64().unwrap() > error);
    // The minimum is every pixel's floor, the maximum every pixel's cap.
    let (floor, _) = render(&dir, &scene, &["--noise-threshold", "1", "--min-spp", "5"]);
    assert_eq!(spp(&floor), (5.0, 5));
    let (capped, _) = render(&dir, &scene, &["--noise-threshold", "0", "--max-spp", "9"]);
    assert_eq!(spp(&capped), (9.0, 9));
    // `--sampling uniform` wins over the adaptive knobs.
    let (back, back_png) = render(
        &dir,
        &scene,
        &[
            "--aa",
            "--spp",
            "4",
            "--noise-threshold",
            "0.05",
            "--sampling",
            "uniform",
        ],
    );
    assert_eq!(spp(&back), (16.0, 16));
    assert_eq!(back_png, uniform_png);
    // Out of range values are refused, naming the setting.
    let refused = workbench_fails(&["render", &scene, "--min-spp", "9", "--max-spp", "4"]);
    assert!(refused.contains("min spp"), "{refused}");
    let refused = workbench_fails(&["render", &scene, "--noise-threshold=-1"]);
    assert!(refused.contains("noise threshold"), "{refused}");
}

#[test]
fn a_scene_file_asks_for_adaptive_sampling_and_flags_override_it() {
    let dir = scratch("adaptive-scene");
    let text = spheres_on_a_floor(32, 24, "", "").replace("bclr", "spp 4\nadaptive 0.02\nbclr");
    let path = write(&dir, "adaptive.p3f", &text);
    let scene = path.to_str().unwrap();
    // The file's `adaptive` turns anti-aliasing on within N = 4's bounds.
    let (asked, _) = render(&dir, scene, &[]);
    let (mean, max) = spp(&asked);
    assert!((4.0..64.0).contains(&mean) && max <= 64, "{asked}");
    assert!(!asked["adaptive"].is_null(), "{asked}");
    // `--spp` moves the bounds with N ((2N)^2 = 16 at threshold 0);
    // `--sampling uniform` takes N x N.
    let (two, _) = render(&dir, scene, &["--spp", "2", "--noise-threshold", "0"]);
    assert_eq!(spp(&two), (16.0, 16), "{two}");
    let (uniform, _) = render(&dir, scene, &["--sampling", "uniform"]);
    assert_eq!(spp(&uniform), (16.0, 16));
    assert!(uniform["adaptive"].is_null(), "{uniform}");
}

#[test]
fn adaptive_renders_are_the_same_on_any_thread_count() {
    let dir = scratch("adaptive-threads");
    let scene = scene(&dir);
    let flags = [
        "--sampling",
        "adaptive",
        "--soft-shadows",
        "--aperture",
        "3",
    ];
    let (one, one_png) = render(&dir, &scene, &[&flags[..], &["--threads", "1"]].concat());
    let (four, four_png) = render(&dir, &scene, &[&flags[..], &["--threads", "4"]].concat());
    assert_eq!(one_png, four_png);
    assert_eq!(one["samples_per_pixel"], four["samples_per_pixel"]);
    assert_eq!(one["adaptive"], four["adaptive"]);
}

#[test]
fn compare_puts_uniform_against_adaptive() {
    let dir = scratch("adaptive-compare");
    let scene = scene(&dir);
    let out = dir.join("compare.png");
    let b = "--sampling adaptive --noise-threshold 0.03";
    let json = workbench_ok(&compare_args(&scene, out.to_str().unwrap(), b, &[]));
    let json: serde_json::Value = serde_json::from_str(&json).unwrap();
    let text = json.to_string();
    assert!(text.contains("AA 3x3"), "{text}");
    assert!(text.contains("adaptive AA, threshold 0.03"), "{text}");
    // What the labels say is what was rendered: A takes 3 x 3 everywhere,
    // B refines some pixels past its floor of 4 and stops others below its
    // cap of (2N)^2 = 36.
    let pixels = 32 * 24;
    let taken = |side: &str| json[side]["samples_taken"].as_u64().expect("samples_taken");
    assert_eq!(taken("a"), 9 * pixels, "{text}");
    assert!(
        taken("b") > 4 * pixels && taken("b") < 36 * pixels,
        "{text}"
    );
    // A uniform B would take exactly A's 3 x 3 a pixel.
    assert_ne!(taken("b"), taken("a"), "{text}");
    assert!(json["mse"].as_f64().expect("mse") > 0.0, "{text}");
}

/// `compare` of `scene` as JSON at N = 3: A uniform with anti-aliasing,
/// B with the flags `b`, then `extra`.
fn compare_args<'a>(scene: &'a str, out: &'a str, b: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "compare", scene, "-o", out, "--format", "json", "--spp", "3", "--a", "--aa", "--b", b,
    ];
    args.extend_from_slice(extra);
    args
}

/// `compare --b-matches`: B stops at A's sample total (filled to within
/// a few pixels' samples, as its threshold asks for more); at A's time
/// (only the mechanism: B renders and reports its samples, no clock is
/// asserted); and a uniform B is refused, as it has no budget.
#[test]
fn compare_matches_adaptive_b_to_a() {
    let dir = scratch("adaptive-compare-matched");
    let scene = scene(&dir);
    let out = dir.join("compare.png");
    let out = out.to_str().unwrap();
    let args = |matches, b| compare_args(&scene, out, b, &["--b-matches", matches]);
    let run = |matches, b| -> serde_json::Value {
        serde_json::from_str(&workbench_ok(&args(matches, b))).unwrap()
    };
    let adaptive = "--sampling adaptive --noise-threshold 0.001";
    let equal = run("samples", adaptive);
    let taken = |side: &str| equal[side]["samples_taken"].as_u64().unwrap();
    assert_eq!(taken("a"), 9 * 32 * 24, "{equal}");
    assert!(
        taken("b") <= taken("a") && taken("b") * 10 >= taken("a") * 9,
        "{equal}"
    );
    assert!(
        equal
            .to_string()
            .contains(&format!("at most {} samples", taken("a"))),
        "B's label names its budget: {equal}"
    );
    // At A's time: B's label names a time budget, and B's first pass (one
    // sample a pixel: the schedule doubles 1, 2, 4 to the minimum) always
    // completes, however short A was; later ones only if A's time allows.
    let timed = run("time", adaptive);
    let label = timed["b"]["label"].as_str().expect("B's label");
    let budget = label
        .split("at most ")
        .nth(1)
        .and_then(|rest| rest.split([',', ')']).next())
        .unwrap_or_else(|| panic!("B's label names no budget: {label}"));
    let seconds = budget.strip_suffix(" s");
    assert!(
        seconds.is_some_and(|s| s.parse::<f64>().is_ok()),
        "B's budget is not a time: {label}"
    );
    let b_taken = timed["b"]["samples_taken"].as_u64().expect("samples_taken");
    assert!((32 * 24..=36 * 32 * 24).contains(&b_taken), "{timed}");
    assert!(workbench_fails(&args("samples", "--aa")).contains("needs B adaptive"));
}

#[test]
fn bench_to_error_times_uniform_and_adaptive_at_one_error() {
    let dir = scratch("adaptive-to-error");
    let scene = scene(&dir);
    let measure = |flags: &[&str]| -> serde_json::Value {
        let mut args = vec![
            "bench",
            &scene,
            "--to-error",
            "--runs",
            "2",
            "--format",
            "json",
        ];
        args.extend(flags);
        serde_json::from_str(&workbench_ok(&args)).unwrap()
    };
    let found = measure(&["--spp", "2", "--reference-spp", "6"]);
    let (uniform, adaptive) = (&found["uniform"], &found["adaptive"]);
    assert_eq!(found["reference_samples"], 6, "{found}");
    // The target is uniform 2 x 2's own error; adaptive reaches it.
    assert_eq!(uniform["samples"], 2);
    assert_eq!(uniform["mse"], found["target_mse"]);
    let number = |value: &serde_json::Value, what: &str| -> f64 {
        value
            .as_f64()
            .unwrap_or_else(|| panic!("{what} is not a number: {found}"))
    };
    assert!(
        number(&adaptive["mse"], "adaptive mse") <= number(&found["target_mse"], "target_mse"),
        "{found}"
    );
    assert!(
        number(&adaptive["flip"], "adaptive flip") <= number(&found["target_flip"], "target_flip"),
        "{found}"
    );
    assert!(adaptive["noise_threshold"].as_f64().unwrap() > 0.0);
    for side in [uniform, adaptive] {
        assert_eq!(side["seconds"].as_array().map(Vec::len), Some(2), "{found}");
    }
    assert!(found["time_ratio"].as_f64().unwrap() > 0.0);
    // Every render tried is listed, the last adaptive one reaching it.
    let attempts = found["attempts"].as_array().unwrap();
    assert!(attempts.len() >= 2, "{found}");

    // An MSE asked for: the cheapest uniform N that reaches it.
    let target = found["target_mse"].as_f64().unwrap() * 3.0;
    let easier = measure(&["--reference-spp", "6", "--target-mse", &target.to_string()]);
    assert!(
        easier["uniform"]["mse"].as_f64().unwrap() <= target,
        "{easier}"
    );
    assert!(
        easier["uniform"]["samples"].as_u64().unwrap() <= 2,
        "{easier}"
    );
    assert!(easier["target_flip"].is_null());
    // The threshold found is the largest that reaches it: every larger one
    // tried missed (searched upwards when the first already reaches it).
    let found_threshold = easier["adaptive"]["noise_threshold"].as_f64().unwrap();
    // Every attempt is a uniform N or an adaptive T: a label of another
    // form fails here rather than dropping out of the list checked.
    let tried = |found: &serde_json::Value| -> Vec<(f64, bool)> {
        let mut adaptive = Vec::new();
        for a in found["attempts"].as_array().unwrap() {
            let label = a["label"].as_str().expect("a label");
            let reached = a["reached"].as_bool().expect("reached");
            if let Some(t) = label.strip_prefix("adaptive T = ") {
                adaptive.push((t.parse().expect("a threshold"), reached));
            } else {
                assert!(label.starts_with("uniform N = "), "{label}: {found}");
            }
        }
        adaptive
    };
    // The first threshold and at least one more were tried.
    let easier_tried = tried(&easier);
    assert!(easier_tried.len() >= 2, "{easier}");
    for (t, reached) in easier_tried {
        assert!(t <= found_threshold * 1.0001 || !reached, "{easier}");
    }
    // A target any render meets: the largest threshold there is.
    let any = measure(&["--reference-spp", "6", "--target-mse", "1e9"]);
    assert_eq!(
        any["adaptive"]["noise_threshold"].as_f64(),
        Some(1.0),
        "{any}"
    );
    // Doubled from the first threshold up to the largest, each reaching it.
    let any_tried = tried(&any);
    assert!(any_tried.len() >= 2, "{any}");
    assert!(any_tried.iter().all(|&(_, reached)| reached), "{any}");

    let refused = workbench_fails(&[
        "bench",
        &scene,
        "--to-error",
        "--spp",
        "4",
        "--reference-spp",
        "4",
    ]);
    assert!(refused.contains("reference"), "{refused}");
    let text = workbench_ok(&[
        "bench",
        &scene,
        "--to-error",
        "--spp",
        "2",
        "--reference-spp",
        "4",
        "--runs",
        "1",
    ]);
    assert!(
        text.contains("adaptive reaches the error of uniform 2 x 2 in"),
        "{text}"
    );
    // The header says what was measured: anti-aliased renders.
    let header = text.lines().next().unwrap_or_default();
    assert!(
        header.contains("AA 2x2") && !header.contains("no AA"),
        "{header}"
    );
}

#[test]
fn sweep_noise_threshold_gives_samples_and_error() {
    let dir = scratch("adaptive-sweep");
    let scene = scene(&dir);
    let json = workbench_ok(&[
        "sweep",
        &scene,
        "--param",
        "noise-threshold",
        "--values",
        "0.005,0.08",
        "--runs",
        "1",
        "--spp",
        "2",
        "--max-spp",
        "36",
        "--format",
        "json",
    ]);
    let points: serde_json::Value = serde_json::from_str(&json).unwrap();
    let points = points.as_array().unwrap();
    assert_eq!(points.len(), 2);
    let (tight, loose) = (&points[0], &points[1]);
    let number = |point: &serde_json::Value, key: &str| -> f64 {
        point[key]
            .as_f64()
            .unwrap_or_else(|| panic!("{key} is not a number: {json}"))
    };
    // The loose threshold still refines some pixels past the floor of 4,
    // so "more samples when tighter" is not met by the floor alone.
    assert!(number(loose, "spp_mean") > 4.0, "{json}");
    assert!(
        number(tight, "spp_mean") > number(loose, "spp_mean"),
        "{json}"
    );
    assert!(tight["spp_max"].as_u64().unwrap() <= 36, "{json}");
    assert!(number(tight, "mse") < number(loose, "mse"), "{json}");
}

/// What a `render` run produced: the PNG's bytes, and the statistics that
/// do not depend on time.
struct Rendered {
    png: Vec<u8>,
    stats: serde_json::Value,
}

/// `render --stats json` of `scene` into `out` with `flags`.
fn render_to(scene: &str, out: &std::path::Path, flags: &[&str]) -> Rendered {
    let mut args = vec![
        "render",
        scene,
        "-o",
        out.to_str().unwrap(),
        "--stats",
        "json",
    ];
    args.extend(flags);
    let mut stats: serde_json::Value = serde_json::from_str(&workbench_ok(&args)).unwrap();
    for timing in [
        "build_seconds",
        "pass_seconds",
        "render_seconds",
        "rays_per_second",
    ] {
        stats.as_object_mut().unwrap().remove(timing);
    }
    Rendered {
        png: std::fs::read(out).unwrap(),
        stats,
    }
}

/// The noise threshold's valid range has one home (`tracer::scene::
/// NOISE_THRESHOLD`): a scene file's `adaptive`, `--noise-threshold` and a
/// lesson's settings accept its ends and refuse just beyond them (the
/// window's slider is held inside it by a unit test).
#[test]
fn every_entry_point_takes_the_same_noise_thresholds() {
    let dir = scratch("threshold-range");
    let scene = scene(&dir);
    let (low, high) = tracer::scene::NOISE_THRESHOLD.into_inner();
    let out = dir.join("out.png");
    let out = out.to_str().unwrap();
    for (threshold, valid) in [
        (low, true),
        (high, true),
        (low - 0.5, false),
        (high + 0.5, false),
    ] {
        let text = spheres_on_a_floor(32, 24, "", "")
            .replace("bclr", &format!("spp 2\nadaptive {threshold}\nbclr"));
        let file = write(&dir, "file.p3f", &text);
        let file = file.to_str().unwrap();
        let flag = format!("--noise-threshold={threshold}");
        let solution = format!("--spp 4 --sampling adaptive {flag}");
        let lesson = lesson_file(&dir, "threshold.toml", &solution);
        let runs = [
            ("scene file", vec!["render", file, "-o", out]),
            (
                "flag",
                vec!["render", &scene, "-o", out, "--spp", "2", &flag],
            ),
            ("lesson", vec!["lesson", "check", &lesson]),
        ];
        for (entry, args) in runs {
            let run = crate::support::workbench(&args);
            let said = String::from_utf8_lossy(&run.stderr).into_owned()
                + &String::from_utf8_lossy(&run.stdout);
            assert_eq!(
                run.status.success(),
                valid,
                "{entry} at {threshold}: {said}"
            );
            if !valid {
                assert!(said.contains("noise threshold"), "{entry}: {said}");
                assert!(said.contains(&format!("{high}")), "{entry}: {said}");
            }
        }
    }
}
