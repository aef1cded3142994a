//! Every flag of the command line does something a test can see in what
//! the run writes or prints: a flag that is parsed but never applied fails
//! here. [`every_flag_has_a_test_that_sees_its_effect`] reads clap's own
//! definition of each subcommand and fails on a flag no test names.

use std::path::Path;

use clap::CommandFactory;
use workbench::cli::Cli;

use crate::support::scenes::spheres_on_a_floor;
use crate::support::{Scratch, scratch, workbench, workbench_fails, workbench_ok, write};

/// Where each flag's effect is checked: (subcommand, flag, test). A flag of
/// the settings every subcommand shares (`--width`, ...) is checked for
/// `render` by effect and for the others by
/// `every_subcommand_applies_the_settings_flags`.
const CHECKED: &[(&str, &str, &str)] = &[
    (
        "",
        "scene",
        "real_window::the_window_shows_the_final_render_of_the_requested_scene",
    ),
    (
        "",
        "screenshot",
        "real_window::the_window_shows_the_final_render_of_the_requested_scene",
    ),
    (
        "",
        "screenshot-after",
        "screenshot_after_takes_a_delay_in_seconds",
    ),
    (
        "render",
        "scene",
        "render::render_writes_the_scene_as_a_png",
    ),
    (
        "render",
        "output",
        "render::render_writes_the_scene_as_a_png",
    ),
    (
        "render",
        "width",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "height",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "depth",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "aa",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "no-aa",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "spp",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "soft-shadows",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "light-size",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "dof",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "aperture",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "focal",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "ambient",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "accel",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "grid-m",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "seed",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "threads",
        "render_settings_flags_change_what_is_rendered",
    ),
    (
        "render",
        "srgb",
        "srgb_encodes_the_linear_film_with_the_srgb_curve",
    ),
    (
        "render",
        "progressive-out",
        "progressive_out_writes_every_pass",
    ),
    (
        "render",
        "stats",
        "render::overrides_change_the_size_and_stats_come_as_json",
    ),
    (
        "render",
        "view",
        "views::render_view_writes_a_heat_map_with_its_legend_and_numbers",
    ),
    (
        "render",
        "view-scale",
        "views::render_views_scale_log_and_colour_views",
    ),
    (
        "render",
        "log",
        "views::render_views_scale_log_and_colour_views",
    ),
    (
        "render",
        "overlay",
        "views::render_overlay_draws_the_structure_over_the_image",
    ),
    (
        "render",
        "pixel",
        "views::render_overlay_highlights_the_pixels_eye_ray_walk",
    ),
    (
        "render",
        "sample",
        "views::render_overlay_highlights_the_pixels_eye_ray_walk",
    ),
    ("bench", "scene", "bench_runs_structures_and_encoding_apply"),
    ("bench", "runs", "bench_runs_structures_and_encoding_apply"),
    (
        "bench",
        "structures",
        "bench_runs_structures_and_encoding_apply",
    ),
    ("bench", "accel", "bench_runs_structures_and_encoding_apply"),
    ("bench", "srgb", "bench_runs_structures_and_encoding_apply"),
    (
        "bench",
        "matrix",
        "compare::the_matrix_has_every_row_structures_agree_and_each_feature_shows",
    ),
    (
        "bench",
        "format",
        "compare::matrix_tables_in_markdown_and_csv",
    ),
    (
        "bench",
        "images",
        "compare::the_matrix_has_every_row_structures_agree_and_each_feature_shows",
    ),
    ("bench", "thumbnail", "compare::images_can_be_thumbnails"),
    (
        "bench",
        "rays",
        "bench_rays::json_counts_one_eye_ray_per_pixel_and_a_shadow_ray_per_faced_light",
    ),
    (
        "compare",
        "scene",
        "compare::different_settings_measure_positive",
    ),
    (
        "compare",
        "a",
        "compare::different_settings_measure_positive",
    ),
    (
        "compare",
        "b",
        "compare::different_settings_measure_positive",
    ),
    (
        "compare",
        "b-image",
        "meshes_and_images::a_reference_image_is_side_b",
    ),
    (
        "compare",
        "fit",
        "meshes_and_images::a_reference_image_is_side_b",
    ),
    (
        "compare",
        "output",
        "compare::different_settings_measure_positive",
    ),
    (
        "compare",
        "heatmap",
        "compare_heatmap_chooses_the_difference_panel",
    ),
    (
        "compare",
        "format",
        "compare::compare_prints_times_and_metrics_as_text",
    ),
    ("compare", "view", "views::compare_views_share_one_scale"),
    (
        "compare",
        "view-scale",
        "compare_heatmap_chooses_the_difference_panel",
    ),
    (
        "compare",
        "log",
        "compare_heatmap_chooses_the_difference_panel",
    ),
    (
        "compare",
        "srgb",
        "compare_heatmap_chooses_the_difference_panel",
    ),
    (
        "inspect",
        "scene",
        "views::inspect_prints_the_ray_tree_as_json_and_as_text",
    ),
    (
        "inspect",
        "pixel",
        "views::inspect_prints_the_ray_tree_as_json_and_as_text",
    ),
    (
        "inspect",
        "sample",
        "inspect_sample_picks_one_of_the_pixels_samples",
    ),
    (
        "inspect",
        "format",
        "views::inspect_prints_the_ray_tree_as_json_and_as_text",
    ),
    (
        "gen",
        "name",
        "gen_writes_a_scene_of_the_asked_level_and_seed",
    ),
    (
        "gen",
        "level",
        "gen_writes_a_scene_of_the_asked_level_and_seed",
    ),
    (
        "gen",
        "seed",
        "gen_writes_a_scene_of_the_asked_level_and_seed",
    ),
    (
        "gen",
        "output",
        "gen_writes_a_scene_of_the_asked_level_and_seed",
    ),
    ("gen", "size", "gen_sky_writes_six_faces_of_the_asked_size"),
    (
        "sweep",
        "scene",
        "sweep::a_grid_m_sweep_prints_a_csv_row_per_point_and_draws_the_chart",
    ),
    (
        "sweep",
        "param",
        "sweep::a_grid_m_sweep_prints_a_csv_row_per_point_and_draws_the_chart",
    ),
    (
        "sweep",
        "values",
        "sweep::a_grid_m_sweep_prints_a_csv_row_per_point_and_draws_the_chart",
    ),
    (
        "sweep",
        "generator",
        "sweep::the_level_study_grows_a_generated_scene",
    ),
    (
        "sweep",
        "structures",
        "sweep::the_level_study_grows_a_generated_scene",
    ),
    (
        "sweep",
        "runs",
        "sweep::a_grid_m_sweep_prints_a_csv_row_per_point_and_draws_the_chart",
    ),
    (
        "sweep",
        "format",
        "sweep::a_grid_m_sweep_prints_a_csv_row_per_point_and_draws_the_chart",
    ),
    (
        "sweep",
        "plot",
        "sweep::a_grid_m_sweep_prints_a_csv_row_per_point_and_draws_the_chart",
    ),
    (
        "sweep",
        "reference-spp",
        "sweep_reference_spp_accel_and_encoding_apply",
    ),
    (
        "sweep",
        "accel",
        "sweep_reference_spp_accel_and_encoding_apply",
    ),
    (
        "sweep",
        "srgb",
        "sweep_reference_spp_accel_and_encoding_apply",
    ),
    (
        "render",
        "set",
        "edits::set_gives_the_image_of_the_scene_edited_by_hand",
    ),
    (
        "render",
        "save-scene",
        "edits::a_saved_scene_renders_as_the_edited_one",
    ),
    (
        "compare",
        "set",
        "edits::compare_applies_edits_to_both_sides_and_per_side",
    ),
    (
        "inspect",
        "set",
        "edits::inspect_bench_sweep_and_observe_see_the_edits",
    ),
    (
        "bench",
        "set",
        "edits::inspect_bench_sweep_and_observe_see_the_edits",
    ),
    (
        "sweep",
        "set",
        "edits::inspect_bench_sweep_and_observe_see_the_edits",
    ),
    (
        "observe",
        "set",
        "edits::inspect_bench_sweep_and_observe_see_the_edits",
    ),
    (
        "observe",
        "scene",
        "observe::the_figure_draws_the_pixels_rays_from_the_camera",
    ),
    (
        "observe",
        "pixel",
        "observe::the_figure_draws_the_pixels_rays_from_the_camera",
    ),
    (
        "observe",
        "pixels",
        "observe::the_figure_draws_the_pixels_rays_from_the_camera",
    ),
    (
        "observe",
        "sample",
        "observe_sample_from_at_up_and_overlay_apply",
    ),
    (
        "observe",
        "from",
        "observe_sample_from_at_up_and_overlay_apply",
    ),
    (
        "observe",
        "at",
        "observe_sample_from_at_up_and_overlay_apply",
    ),
    (
        "observe",
        "up",
        "observe_sample_from_at_up_and_overlay_apply",
    ),
    (
        "observe",
        "size",
        "observe::the_figure_draws_the_pixels_rays_from_the_camera",
    ),
    (
        "observe",
        "overlay",
        "observe_sample_from_at_up_and_overlay_apply",
    ),
    (
        "observe",
        "output",
        "observe::the_figure_draws_the_pixels_rays_from_the_camera",
    ),
    (
        "observe",
        "format",
        "observe::the_figure_draws_the_pixels_rays_from_the_camera",
    ),
    (
        "observe",
        "srgb",
        "observe_sample_from_at_up_and_overlay_apply",
    ),
    (
        "",
        "observer",
        "real_window::the_window_opens_with_the_observer_on_when_asked",
    ),
];

/// The settings flags `render` shares with the other subcommands.
const SHARED: &[&str] = &[
    "width",
    "height",
    "depth",
    "aa",
    "no-aa",
    "spp",
    "soft-shadows",
    "light-size",
    "dof",
    "aperture",
    "focal",
    "ambient",
    "accel",
    "grid-m",
    "seed",
    "threads",
];

/// The sources of this test binary, where the named tests must exist.
const SOURCES: &[&str] = &[
    include_str!("flags.rs"),
    include_str!("render.rs"),
    include_str!("views.rs"),
    include_str!("compare.rs"),
    include_str!("edits.rs"),
    include_str!("meshes_and_images.rs"),
    include_str!("sweep.rs"),
    include_str!("bench_rays.rs"),
    include_str!("observe.rs"),
    include_str!("../window/real_window.rs"),
];

#[test]
fn every_flag_has_a_test_that_sees_its_effect() {
    let cli = Cli::command();
    let mut subcommands: Vec<&clap::Command> = vec![&cli];
    subcommands.extend(cli.get_subcommands());
    let mut missing = Vec::new();
    for command in subcommands {
        let name = if std::ptr::eq(command, &cli) {
            ""
        } else {
            command.get_name()
        };
        for arg in command.get_arguments() {
            let flag = arg.get_long().unwrap_or(arg.get_id().as_str());
            if ["help", "version"].contains(&flag) {
                continue;
            }
            let shared = name != "render" && SHARED.contains(&flag);
            let checked = CHECKED.iter().any(|&(c, f, _)| (c, f) == (name, flag));
            if !shared && !checked {
                missing.push(format!("{name} --{flag}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "flags without an effect test: {missing:?}"
    );
    for &(command, flag, test) in CHECKED {
        let function = test.rsplit("::").next().unwrap();
        assert!(
            SOURCES
                .iter()
                .any(|s| s.contains(&format!("fn {function}("))),
            "{command} --{flag}: no test {test}"
        );
    }
}

/// A scene with every kind of ray and no `spp`: one sample per pixel.
fn scene(dir: &Scratch) -> String {
    let path = write(dir, "scene.p3f", &spheres_on_a_floor(24, 16, "", ""));
    path.to_str().unwrap().to_string()
}

/// [`scene`] and where a run writes `name` beside it.
fn scene_and_output(dir: &Scratch, name: &str) -> (String, String) {
    let out = dir.join(name);
    (scene(dir), out.to_str().unwrap().to_string())
}

/// What a `render` run produced: the PNG's bytes, and the statistics that
/// do not depend on time.
#[derive(Debug, PartialEq)]
struct Rendered {
    png: Vec<u8>,
    stats: serde_json::Value,
}

fn render(scene: &str, out: &Path, flags: &[&str]) -> Rendered {
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

#[test]
fn render_settings_flags_change_what_is_rendered() {
    let dir = scratch("flags-render");
    let plain = scene(&dir);
    let with_spp = write(&dir, "spp.p3f", &spheres_on_a_floor(24, 16, "", "spp 2"));
    let with_spp = with_spp.to_str().unwrap();
    let out = dir.join("out.png");
    // (scene, the flags before, the flags added, what must differ).
    enum Differs {
        Image,
        /// The same image, other statistics.
        StatsOnly,
        /// Nothing: the flag must not change the result.
        Nothing,
    }
    let cases: &[(&str, &[&str], &[&str], Differs)] = &[
        (&plain, &[], &["--width", "20"], Differs::Image),
        (&plain, &[], &["--height", "20"], Differs::Image),
        (&plain, &[], &["--depth", "0"], Differs::Image),
        (&plain, &[], &["--aa"], Differs::Image),
        (with_spp, &[], &["--no-aa"], Differs::Image),
        (&plain, &["--aa"], &["--spp", "3"], Differs::Image),
        (&plain, &[], &["--soft-shadows"], Differs::Image),
        (
            &plain,
            &["--soft-shadows"],
            &["--light-size", "2"],
            Differs::Image,
        ),
        (&plain, &[], &["--aperture", "6"], Differs::Image),
        (
            &plain,
            &["--aperture", "6"],
            &["--focal", "2"],
            Differs::Image,
        ),
        // With the scene's aperture of 0 the lens is a point: the samples
        // spread over it, the image stays.
        (&plain, &[], &["--dof"], Differs::StatsOnly),
        (&plain, &[], &["--ambient", "0.5"], Differs::Image),
        (&plain, &[], &["--accel", "none"], Differs::StatsOnly),
        (
            &plain,
            &["--accel", "grid"],
            &["--grid-m", "4"],
            Differs::StatsOnly,
        ),
        (&plain, &["--aa"], &["--seed", "7"], Differs::Image),
        (&plain, &["--aa"], &["--threads", "1"], Differs::Nothing),
    ];
    for (scene, before, added, differs) in cases {
        let base = render(scene, &out, before);
        let flags: Vec<&str> = before.iter().chain(added.iter()).copied().collect();
        let changed = render(scene, &out, &flags);
        let what = format!("{before:?} + {added:?}");
        match differs {
            Differs::Image => assert_ne!(base.png, changed.png, "{what}: same image"),
            Differs::StatsOnly => {
                assert_eq!(base.png, changed.png, "{what}: another image");
                assert_ne!(base.stats, changed.stats, "{what}: same statistics");
            }
            Differs::Nothing => assert_eq!(base, changed, "{what}"),
        }
    }
    // A light of size 0 is the point light: soft shadows change nothing.
    let hard = render(&plain, &out, &[]);
    let point = render(&plain, &out, &["--soft-shadows", "--light-size", "0"]);
    assert_eq!(hard.png, point.png);
}

/// sRGB output is the linear film (as the EXR holds it) through the sRGB
/// curve, each 8-bit value within one level.
#[test]
fn srgb_encodes_the_linear_film_with_the_srgb_curve() {
    let dir = scratch("flags-srgb");
    let scene = scene(&dir);
    let (exr, png) = (dir.join("linear.exr"), dir.join("srgb.png"));
    workbench_ok(&["render", &scene, "-o", exr.to_str().unwrap()]);
    workbench_ok(&["render", &scene, "-o", png.to_str().unwrap(), "--srgb"]);
    let film = image::open(&exr).unwrap().to_rgb32f();
    let encoded = image::open(&png).unwrap().to_rgb8();
    let srgb = |v: f32| {
        let v = v.clamp(0.0, 1.0);
        let e = if v <= 0.003_130_8 {
            12.92 * v
        } else {
            1.055 * v.powf(1.0 / 2.4) - 0.055
        };
        e * 255.0
    };
    for (linear, got) in film.pixels().zip(encoded.pixels()) {
        for c in 0..3 {
            let expected = srgb(linear.0[c]);
            assert!(
                (f32::from(got.0[c]) - expected).abs() <= 1.0,
                "{} for linear {} (sRGB {expected})",
                got.0[c],
                linear.0[c]
            );
        }
    }
}

#[test]
fn progressive_out_writes_every_pass() {
    let dir = scratch("flags-progressive");
    let scene = scene(&dir);
    let (passes, out) = (dir.join("passes"), dir.join("final.png"));
    workbench_ok(&[
        "render",
        &scene,
        "-o",
        out.to_str().unwrap(),
        "--aa",
        "--spp",
        "2",
        "--progressive-out",
        passes.to_str().unwrap(),
    ]);
    let mut written: Vec<String> = std::fs::read_dir(&passes)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    assert_eq!(
        written,
        [
            "pass_0001.png",
            "pass_0002.png",
            "pass_0003.png",
            "pass_0004.png"
        ]
    );
    let first = std::fs::read(passes.join("pass_0001.png")).unwrap();
    let last = std::fs::read(passes.join("pass_0004.png")).unwrap();
    assert_eq!(
        last,
        std::fs::read(&out).unwrap(),
        "the last pass is the image"
    );
    assert_ne!(first, last, "each pass adds samples");
}

#[test]
fn every_subcommand_applies_the_settings_flags() {
    let dir = scratch("flags-shared");
    let (scene, out) = scene_and_output(&dir, "out.png");
    let out = out.as_str();
    let size = ["--width", "17", "--height", "9"];
    let runs: [Vec<&str>; 5] = [
        vec!["render", &scene, "-o", out],
        vec!["bench", &scene, "--runs", "1", "--structures", "bvh"],
        vec!["compare", &scene, "-o", out],
        vec!["inspect", &scene, "--pixel", "16", "8"],
        vec![
            "sweep", &scene, "--param", "depth", "--values", "1", "--runs", "1",
        ],
    ];
    for mut args in runs {
        args.extend(size);
        let run = workbench(&args);
        let printed = format!(
            "{}{}",
            String::from_utf8_lossy(&run.stdout),
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(run.status.success(), "{args:?}: {printed}");
        if args[0] == "inspect" {
            // The pixel exists only in a 17 x 9 image (the scene is 24 x 16).
            let outside = workbench(&["inspect", &scene, "--pixel", "17", "8", "--width", "17"]);
            assert!(
                !outside.status.success(),
                "pixel 17 of a 17 pixel wide image"
            );
        } else {
            assert!(printed.contains("17x9"), "{args:?}: {printed}");
        }
    }
}

#[test]
fn bench_runs_structures_and_encoding_apply() {
    let dir = scratch("flags-bench");
    let scene = scene(&dir);
    let bench = |flags: &[&str]| {
        let mut args = vec!["bench", &scene, "--format", "csv"];
        args.extend(flags);
        workbench_ok(&args)
    };
    let rows = |csv: &str| -> Vec<String> {
        csv.lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap().to_string())
            .collect()
    };
    assert_eq!(rows(&bench(&["--runs", "1"])), ["none", "grid", "bvh"]);
    assert_eq!(
        rows(&bench(&["--runs", "1", "--structures", "grid"])),
        ["grid"]
    );
    // `--accel` picks the one structure to time, as `--structures` does.
    assert_eq!(rows(&bench(&["--runs", "1", "--accel", "none"])), ["none"]);
    let refused = workbench_fails(&["bench", &scene, "--accel", "grid", "--structures", "bvh"]);
    assert!(refused.contains("--accel"), "{refused}");
    let json = workbench_ok(&[
        "bench",
        &scene,
        "--runs",
        "2",
        "--structures",
        "bvh",
        "--format",
        "json",
    ]);
    let json: serde_json::Value = serde_json::from_str(&json).unwrap();
    let frames = json[0]["seconds"].as_array().map(Vec::len);
    assert_eq!(frames, Some(2), "{json}");

    let (linear, srgb) = (dir.join("linear"), dir.join("srgb"));
    for (folder, encoding) in [(&linear, None), (&srgb, Some("--srgb"))] {
        let mut flags = vec!["--runs", "1", "--structures", "bvh", "--images"];
        flags.push(folder.to_str().unwrap());
        flags.extend(encoding);
        bench(&flags);
    }
    let image = |dir: &Path| std::fs::read(dir.join("bvh.png")).unwrap();
    assert_ne!(image(&linear), image(&srgb));
}

#[test]
fn compare_heatmap_chooses_the_difference_panel() {
    let dir = scratch("flags-compare");
    let scene = scene(&dir);
    let out = dir.join("out.png");
    let compare = |flags: &[&str]| {
        let mut args = vec![
            "compare",
            &scene,
            "-o",
            out.to_str().unwrap(),
            "--b",
            "--aa",
        ];
        args.extend(flags);
        workbench_ok(&args);
        image::open(&out).unwrap().to_rgb8()
    };
    let flip = compare(&["--heatmap", "flip"]);
    let abs = compare(&["--heatmap", "abs"]);
    let width = flip.width() / 3;
    let panel = |img: &image::RgbImage, i: u32| {
        image::imageops::crop_imm(img, i * width, 0, width, 16).to_image()
    };
    assert_eq!(panel(&flip, 0), panel(&abs, 0), "A is the same");
    assert_ne!(
        panel(&flip, 2),
        panel(&abs, 2),
        "the difference panel is not"
    );
    let srgb = compare(&["--srgb"]);
    assert_ne!(
        panel(&flip, 0),
        panel(&srgb, 0),
        "--srgb encodes both sides"
    );

    // With --view, the shared scale's top and the log curve.
    let view = |flags: &[&str]| {
        let mut args = vec!["--view", "tests"];
        args.extend(flags);
        compare(&args)
    };
    let max = view(&[]);
    assert_ne!(max, view(&["--view-scale", "1"]));
    assert_ne!(max, view(&["--log"]));
}

#[test]
fn inspect_sample_picks_one_of_the_pixels_samples() {
    let dir = scratch("flags-inspect");
    let scene = scene(&dir);
    let inspect = |sample: &str| {
        workbench_ok(&[
            "inspect", &scene, "--pixel", "12", "8", "--aa", "--sample", sample, "--format", "json",
        ])
    };
    let (first, second) = (inspect("0"), inspect("1"));
    let eye = |json: &str| {
        let tree: serde_json::Value = serde_json::from_str(json).unwrap();
        tree["nodes"][0]["direction"].clone()
    };
    assert_ne!(eye(&first), eye(&second), "another jittered eye ray");
    assert_eq!(first, inspect("0"));
}

#[test]
fn gen_writes_a_scene_of_the_asked_level_and_seed() {
    let dir = scratch("flags-gen");
    let file = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let spheres = |path: &str| {
        std::fs::read_to_string(path)
            .unwrap()
            .lines()
            .filter(|l| l.starts_with("s "))
            .count()
    };
    let (one, two) = (file("one.p3f"), file("two.p3f"));
    workbench_ok(&["gen", "balls", "--level", "1", "-o", &one]);
    workbench_ok(&["gen", "balls", "--level", "2", "-o", &two]);
    assert_eq!((spheres(&one), spheres(&two)), (10, 91));
    // Written to standard output without -o, the same text.
    let printed = workbench_ok(&["gen", "balls", "--level", "1"]);
    assert_eq!(printed, std::fs::read_to_string(&one).unwrap());
    // The seed moves what the generator places at random.
    let (a, b) = (file("a.p3f"), file("b.p3f"));
    workbench_ok(&["gen", "mount", "--level", "1", "--seed", "1", "-o", &a]);
    workbench_ok(&["gen", "mount", "--level", "1", "--seed", "2", "-o", &b]);
    let body = |p: &str| {
        let text = std::fs::read_to_string(p).unwrap();
        text.lines().skip(1).collect::<Vec<_>>().join("\n")
    };
    assert_ne!(body(&a), body(&b));
    // The rendered scene is the generated one.
    let out = file("one.png");
    let summary = workbench_ok(&["render", &one, "-o", &out, "--width", "8", "--height", "8"]);
    assert!(summary.contains("10 spheres"), "{summary}");
    // A sky has no level or seed, a scene no face size: refused, not ignored.
    for wrong in [
        vec!["gen", "sky", "-o", &out, "--level", "2"],
        vec!["gen", "sky", "-o", &out, "--seed", "2"],
        vec!["gen", "balls", "--size", "64"],
        vec!["gen", "balls", "--seed", "3"],
    ] {
        let stderr = workbench_fails(&wrong);
        assert!(stderr.contains("does not apply"), "{wrong:?}: {stderr}");
    }
}

#[test]
fn gen_sky_writes_six_faces_of_the_asked_size() {
    let dir = scratch("flags-sky");
    let sky = dir.join("sky");
    workbench_ok(&["gen", "sky", "-o", sky.to_str().unwrap(), "--size", "16"]);
    for face in ["back", "bottom", "front", "left", "right", "top"] {
        let image = image::open(sky.join(format!("{face}.png"))).unwrap();
        assert_eq!((image.width(), image.height()), (16, 16), "{face}");
    }
    let top = image::open(sky.join("top.png")).unwrap().to_rgb8();
    let bottom = image::open(sky.join("bottom.png")).unwrap().to_rgb8();
    assert_ne!(top, bottom, "sky above, ground below");
}

#[test]
fn sweep_reference_spp_accel_and_encoding_apply() {
    let dir = scratch("flags-sweep");
    let scene = scene(&dir);
    let sweep = |flags: &[&str]| {
        let mut args = vec!["sweep", &scene, "--runs", "1", "--format", "csv"];
        args.extend(flags);
        workbench_ok(&args)
    };
    let spp = ["--param", "spp", "--values", "1,2", "--structures", "bvh"];
    let errors = |csv: &str| -> Vec<String> {
        // The image error columns: MSE, PSNR, FLIP, after the timings.
        csv.lines()
            .skip(1)
            .map(|l| l.split(',').rev().take(3).collect::<Vec<_>>().join(","))
            .collect()
    };
    let three = sweep(&[&spp[..], &["--reference-spp", "3"]].concat());
    let four = sweep(&[&spp[..], &["--reference-spp", "4"]].concat());
    assert_ne!(errors(&three), errors(&four), "another reference");
    let srgb = sweep(&[&spp[..], &["--reference-spp", "3", "--srgb"]].concat());
    assert_ne!(
        errors(&three),
        errors(&srgb),
        "errors of the encoded images"
    );
    // Without --structures the study times the structure --accel names.
    let accel = sweep(&["--param", "depth", "--values", "1", "--accel", "none"]);
    let structures: Vec<&str> = accel
        .lines()
        .skip(1)
        .map(|l| &l[..l.find(',').unwrap()])
        .collect();
    assert_eq!(structures, ["none"]);
}

#[test]
fn screenshot_after_takes_a_delay_in_seconds() {
    for delay in ["-1", "nan", "1e30"] {
        let after = format!("--screenshot-after={delay}");
        let stderr = workbench_fails(&["--screenshot", "shot.png", &after]);
        assert!(
            stderr.contains("not a delay in seconds"),
            "{delay}: {stderr}"
        );
    }
    let stderr = workbench_fails(&["--screenshot-after", "2"]);
    assert!(stderr.contains("--screenshot"), "{stderr}");
}

#[test]
fn observe_sample_from_at_up_and_overlay_apply() {
    let dir = scratch("flags-observe");
    let (scene, out) = scene_and_output(&dir, "figure.png");
    let out = out.as_str();
    let observe = |flags: &[&str]| {
        let mut args = vec![
            "observe", &scene, "-o", out, "--size", "64", "48", "--format", "json",
        ];
        args.extend(flags);
        let json: serde_json::Value = serde_json::from_str(&workbench_ok(&args)).unwrap();
        (json, std::fs::read(out).unwrap())
    };
    let pixel = ["--pixel", "12", "8", "--aa"];
    let (first, png) = observe(&pixel);
    let (second, _) = observe(&[&pixel[..], &["--sample", "1"]].concat());
    let eye = |json: &serde_json::Value| {
        json["segments"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["kind"] == "eye")
            .unwrap()["to"]
            .clone()
    };
    assert_ne!(eye(&first), eye(&second), "another sample's eye ray");
    let placed = [
        &pixel[..],
        &["--from", "0", "-12", "6", "--at", "0", "0", "0.5"],
    ]
    .concat();
    let (placed_json, placed_png) = observe(&placed);
    assert_eq!(placed_json["observer"]["from"][1], -12.0);
    assert_ne!(placed_png, png);
    let upside = [&placed[..], &["--up", "0", "0", "-1"]].concat();
    let (upside_json, upside_png) = observe(&upside);
    assert_eq!(upside_json["observer"]["up"][2], -1.0);
    assert_ne!(upside_png, placed_png);
    let (_, srgb) = observe(&[&placed[..], &["--srgb"]].concat());
    assert_ne!(srgb, placed_png);
    let (grid, _) = observe(&[&placed[..], &["--accel", "grid", "--overlay", "grid"]].concat());
    let parts = |json: &serde_json::Value, part: &str| {
        json["segments"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|s| s["part"] == part)
            .count()
    };
    assert!(parts(&grid, "structure") > 12 && parts(&grid, "visit") > 0);
    assert_eq!(parts(&placed_json, "structure"), 0);
    let refused = workbench_fails(&[
        "observe",
        &scene,
        "-o",
        out,
        "--pixel",
        "1",
        "1",
        "--overlay",
        "grid",
    ]);
    assert!(refused.contains("--accel grid"), "{refused}");
}
