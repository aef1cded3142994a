//! Every flag of the command line does something a test can see in what
//! the run writes or prints: a flag that is parsed but never applied fails
//! here. [`every_flag_has_a_test_that_sees_its_effect`] reads clap's own
//! definition of each subcommand and fails on a flag no test names.

use std::path::Path;

use clap::{Args, CommandFactory};
use workbench::cli::{Cli, SettingsArgs};

use crate::support::scenes::spheres_on_a_floor;
use crate::support::{Scratch, scratch, workbench_fails, workbench_ok, write};

/// Where each flag's effect is checked: (subcommand, flag, test), the
/// subcommand by its path (`"lesson progress"`), the test naming the flag. The settings flags the subcommands share (`--width`,
/// ...: [`shared_flags`]) are checked on every subcommand that takes them
/// by [`settings_flags_change_what_each_subcommand_does`].
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
        "lesson",
        "real_window::the_window_opens_a_lesson_set_up",
    ),
    (
        "",
        "lesson-folder",
        "real_window::the_window_opens_a_lesson_folders_first_lesson_set_up",
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
    (
        "render",
        "sampling",
        "adaptive::render_spends_adaptive_samples_where_the_flags_say",
    ),
    (
        "render",
        "noise-threshold",
        "adaptive::render_spends_adaptive_samples_where_the_flags_say",
    ),
    (
        "render",
        "min-spp",
        "adaptive::render_spends_adaptive_samples_where_the_flags_say",
    ),
    (
        "render",
        "max-spp",
        "adaptive::render_spends_adaptive_samples_where_the_flags_say",
    ),
    (
        "bench",
        "to-error",
        "adaptive::bench_to_error_times_uniform_and_adaptive_at_one_error",
    ),
    (
        "bench",
        "reference-spp",
        "adaptive::bench_to_error_times_uniform_and_adaptive_at_one_error",
    ),
    (
        "bench",
        "target-mse",
        "adaptive::bench_to_error_times_uniform_and_adaptive_at_one_error",
    ),
    ("bench", "scene", "bench_runs_structures_and_encoding_apply"),
    (
        "report",
        "scene",
        "report::quick_reports_of_two_scenes_have_every_section_and_the_json_numbers",
    ),
    (
        "report",
        "output",
        "report::quick_reports_of_two_scenes_have_every_section_and_the_json_numbers",
    ),
    (
        "report",
        "json",
        "report::quick_reports_of_two_scenes_have_every_section_and_the_json_numbers",
    ),
    ("report", "runs", "report::report_flags_apply"),
    ("report", "quick", "report::report_flags_apply"),
    ("report", "pixel", "report::report_flags_apply"),
    ("report", "set", "report::report_flags_apply"),
    ("report", "srgb", "report::report_flags_apply"),
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
        "b-matches",
        "adaptive::compare_matches_adaptive_b_to_a",
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
        "compare::different_settings_measure_positive",
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
    (
        "lesson list",
        "format",
        "lesson_folders::an_index_chooses_the_folders_lessons",
    ),
    (
        "lesson list",
        "folder",
        "lesson_folders::a_folder_is_listed_in_chapter_order_and_checked_whole",
    ),
    (
        "lesson check",
        "lessons",
        "lessons::a_sound_lesson_passes_step_by_step",
    ),
    (
        "lesson check",
        "format",
        "lessons::lesson_check_speaks_json_for_a_teachers_ci",
    ),
    (
        "lesson new",
        "name",
        "lessons::a_new_lesson_passes_its_check_and_is_never_written_twice",
    ),
    (
        "lesson explain",
        "lesson",
        "lesson_explain::explain_says_the_state_a_step_starts_from",
    ),
    (
        "lesson explain",
        "step",
        "lesson_explain::explain_says_the_state_a_step_starts_from",
    ),
    (
        "lesson explain",
        "find",
        "lesson_explain::a_pixel_find_lists_passes_the_steps_check",
    ),
    (
        "lesson explain",
        "pixel",
        "lesson_explain::explain_with_a_pixel_says_whether_the_check_holds_there",
    ),
    (
        "lesson progress",
        "file",
        "lesson_progress::the_windows_saved_progress_is_written_as_json_csv_and_html",
    ),
    (
        "lesson progress",
        "merge",
        "lesson_progress::merged_files_make_one_row_per_student_and_a_column_per_lesson",
    ),
    (
        "lesson progress",
        "format",
        "lesson_progress::the_windows_saved_progress_is_written_as_json_csv_and_html",
    ),
    (
        "lesson progress",
        "output",
        "lesson_progress::the_windows_saved_progress_is_written_as_json_csv_and_html",
    ),
];

/// The settings flags the subcommands share: `SettingsArgs` as clap
/// defines it (but `--set`, whose edits `edits.rs` checks per subcommand),
/// and `--threads`.
fn shared_flags() -> Vec<String> {
    let settings = SettingsArgs::augment_args(clap::Command::new("settings"));
    let mut flags: Vec<String> = settings
        .get_arguments()
        .filter_map(|a| a.get_long())
        .filter(|&f| f != "set")
        .map(str::to_string)
        .collect();
    flags.push("threads".into());
    flags
}

/// The subcommands that take the shared `--flag`: all of the settings
/// flags (`gen --seed` is the generator's own), or `--threads`.
fn taking(flag: &str) -> Vec<String> {
    let shared = shared_flags();
    let needed: Vec<&str> = match flag {
        "threads" => vec!["threads"],
        _ => shared
            .iter()
            .map(String::as_str)
            .filter(|&f| f != "threads")
            .collect(),
    };
    Cli::command()
        .get_subcommands()
        .filter(|c| {
            needed
                .iter()
                .all(|&f| c.get_arguments().any(|a| a.get_long() == Some(f)))
        })
        .map(|c| c.get_name().to_string())
        .collect()
}

/// The settings flags `report` refuses: it varies the structure, shadows,
/// anti-aliasing and depth of field itself and samples uniformly, so these
/// would change nothing. Each must fail naming itself.
const REPORT_REFUSES: &[&str] = &[
    "accel",
    "aa",
    "no-aa",
    "soft-shadows",
    "no-shadows",
    "dof",
    "sampling",
    "noise-threshold",
    "min-spp",
    "max-spp",
];

/// `flags` without those `report` refuses (and their values): the report
/// sets them itself for each experiment.
fn report_takes<'a>(flags: &[&'a str]) -> Vec<&'a str> {
    let mut kept = Vec::new();
    let mut refusing = false;
    for &word in flags {
        if let Some(flag) = word.strip_prefix("--") {
            refusing = REPORT_REFUSES.contains(&flag);
        }
        if !refusing {
            kept.push(word);
        }
    }
    kept
}

/// The inline PNG images of a report page, as their base64 text.
fn page_images(page: &str) -> Vec<Vec<u8>> {
    page.split("src=\"data:image/png;base64,")
        .skip(1)
        .map(|rest| rest.as_bytes()[..rest.find('"').unwrap()].to_vec())
        .collect()
}

/// The sources of this test binary, where the named tests must exist.
const SOURCES: &[&str] = &[
    include_str!("flags.rs"),
    include_str!("adaptive.rs"),
    include_str!("render.rs"),
    include_str!("views.rs"),
    include_str!("compare.rs"),
    include_str!("edits.rs"),
    include_str!("meshes_and_images.rs"),
    include_str!("sweep.rs"),
    include_str!("bench_rays.rs"),
    include_str!("observe.rs"),
    include_str!("report.rs"),
    include_str!("../window/real_window.rs"),
    include_str!("lessons.rs"),
    include_str!("lesson_explain.rs"),
    include_str!("lesson_folders.rs"),
    include_str!("lesson_progress.rs"),
];

#[test]
fn every_flag_has_a_test_that_sees_its_effect() {
    let shared = shared_flags();
    let mut missing = Vec::new();
    for (name, command) in commands() {
        let name = name.as_str();
        for arg in command.get_arguments() {
            let flag = arg.get_long().unwrap_or(arg.get_id().as_str());
            if ["help", "version"].contains(&flag) {
                continue;
            }
            let shared = !name.is_empty() && shared.iter().any(|s| s == flag);
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
        let (source, body) = SOURCES
            .iter()
            .find_map(|s| Some((*s, test_body(s, function)?)))
            .unwrap_or_else(|| panic!("{command} --{flag}: no test {test}"));
        // The flag as the test passes it (`--flag`, `--flag=`, or `-o`),
        // in its body or in a helper of its file that it calls; a
        // positional argument is in every run.
        let arg = subcommand_arg(command, flag);
        let passes = |text: &str| match (arg.get_long(), arg.get_short()) {
            (Some(long), short) => {
                text.contains(&format!("\"--{long}"))
                    || short.is_some_and(|c| text.contains(&format!("\"-{c}\"")))
            }
            (None, _) => true,
        };
        let helpers = source
            .split("\nfn ")
            .skip(1)
            .filter_map(|item| item.split('(').next())
            .filter(|helper| body.contains(&format!("{helper}(")))
            .filter_map(|helper| test_body(source, helper));
        let named = passes(body) || helpers.into_iter().any(passes);
        assert!(named, "{command} --{flag}: {test} never passes it");
    }
}

/// Every command with its path (`""` for the top level, `"lesson
/// progress"`), subcommands of subcommands included.
fn commands() -> Vec<(String, clap::Command)> {
    fn walk(command: &clap::Command, path: &str, found: &mut Vec<(String, clap::Command)>) {
        found.push((path.to_string(), command.clone()));
        for sub in command.get_subcommands() {
            let name = format!("{path} {}", sub.get_name());
            walk(sub, name.trim(), found);
        }
    }
    let mut found = Vec::new();
    walk(&Cli::command(), "", &mut found);
    found
}

/// The text of test `function` in `source`: from its `fn` to the first
/// line closing a top-level item.
fn test_body<'a>(source: &'a str, function: &str) -> Option<&'a str> {
    let start = source.find(&format!("fn {function}("))?;
    let rest = &source[start..];
    let end = rest.find("\n}\n").map_or(rest.len(), |e| e + 3);
    Some(&rest[..end])
}

/// Argument `id` (its long name, or its id when positional) of
/// `subcommand` ("" for the window's own flags).
fn subcommand_arg(subcommand: &str, id: &str) -> clap::Arg {
    let (_, command) = commands()
        .into_iter()
        .find(|(name, _)| name == subcommand)
        .unwrap_or_else(|| panic!("no subcommand {subcommand:?}"));
    command
        .get_arguments()
        .find(|a| a.get_long() == Some(id) || a.get_id() == id)
        .cloned()
        .unwrap_or_else(|| panic!("{subcommand} has no argument {id}"))
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

/// What a run gives that does not depend on time: the files it wrote,
/// and what it printed as JSON with every timing taken out (a report: the
/// images of its page and its `--json` timing table).
#[derive(Debug, PartialEq)]
struct Outcome {
    files: Vec<Vec<u8>>,
    printed: serde_json::Value,
}

/// Runs `subcommand` on `scene` with `flags`, writing into `dir`, each
/// subcommand as it prints everything it measures as JSON. A sweep studies
/// the error of N x N samples against a reference, or the depth when
/// `flag` is among those its N sets.
fn outcome(subcommand: &str, flag: &str, scene: &str, dir: &Path, flags: &[&str]) -> Outcome {
    let (out, images) = (dir.join("out.png"), dir.join("images"));
    let (page, table) = (dir.join("out.html"), dir.join("out.json"));
    for file in [&out, &page, &table] {
        let _ = std::fs::remove_file(file);
    }
    let _ = std::fs::remove_dir_all(&images);
    let (out, images) = (out.to_str().unwrap(), images.to_str().unwrap());
    let (page, table) = (page.to_str().unwrap(), table.to_str().unwrap());
    let pixel = ["--pixel", "12", "8"];
    let own: Vec<&str> = match subcommand {
        "render" => vec!["-o", out, "--stats", "json"],
        "compare" => vec!["-o", out, "--format", "json"],
        "inspect" => [&pixel[..], &["--format", "json"]].concat(),
        "observe" => [
            &pixel[..],
            &["-o", out, "--size", "64", "48", "--format", "json"],
        ]
        .concat(),
        "bench" => vec!["--runs", "1", "--format", "json", "--images", images],
        "sweep" if ["spp", "aa", "no-aa"].contains(&flag) => vec![
            "--param", "depth", "--values", "1,2", "--runs", "1", "--format", "json",
        ],
        "sweep" => vec![
            "--param",
            "spp",
            "--values",
            "1,2",
            "--reference-spp",
            "3",
            "--runs",
            "1",
            "--format",
            "json",
        ],
        "report" => [
            &["-o", page, "--json", table, "--quick", "--runs", "1"][..],
            &pixel,
        ]
        .concat(),
        other => panic!("`{other}` takes the settings flags: say here how to run it"),
    };
    let args: Vec<&str> = [&[subcommand, scene][..], &own, flags].concat();
    let said = workbench_ok(&args);
    let json = match subcommand {
        "report" => std::fs::read_to_string(table).unwrap(),
        _ => said,
    };
    let mut printed: serde_json::Value =
        serde_json::from_str(&json).unwrap_or_else(|e| panic!("{args:?} printed no JSON: {e}"));
    drop_timings(&mut printed);
    let mut files = Vec::new();
    if let Ok(image) = std::fs::read(out) {
        files.push(image);
    }
    if let Ok(page) = std::fs::read_to_string(page) {
        files.extend(page_images(&page));
    }
    if let Ok(entries) = std::fs::read_dir(images) {
        let mut paths: Vec<_> = entries.map(|e| e.unwrap().path()).collect();
        paths.sort();
        files.extend(paths.iter().map(|p| std::fs::read(p).unwrap()));
    }
    Outcome { files, printed }
}

/// Takes out every value that depends on time: seconds, rates, ratios of
/// times, and which structure was fastest.
fn drop_timings(value: &mut serde_json::Value) {
    match value {
        serde_json::Value::Object(map) => {
            map.retain(|key, _| !(key.contains("second") || key.contains("time") || key == "best"));
            map.values_mut().for_each(drop_timings);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(drop_timings),
        _ => {}
    }
}

/// Each settings flag, through each subcommand that takes it (clap says
/// which), changes what the run gives: its image or, for a flag that
/// only changes the work, what it counts. A subcommand that parses a
/// flag and never applies it fails here. `report` refuses the flags it
/// varies itself ([`REPORT_REFUSES`]), and they must fail, writing nothing.
#[test]
fn settings_flags_change_what_each_subcommand_does() {
    let dir = scratch("flags-shared");
    let plain = scene(&dir);
    let with_spp = write(&dir, "spp.p3f", &spheres_on_a_floor(24, 16, "", "spp 2"));
    let with_spp = with_spp.to_str().unwrap();
    // (scene, the flags before, the flags added): the added flags change
    // the outcome, but `--threads`, which must change nothing.
    let cases: &[(&str, &[&str], &[&str])] = &[
        (&plain, &[], &["--width", "20"]),
        (&plain, &[], &["--height", "20"]),
        (&plain, &[], &["--depth", "0"]),
        (&plain, &[], &["--aa"]),
        (with_spp, &["--aa"], &["--no-aa"]),
        (&plain, &["--aa"], &["--spp", "3"]),
        (&plain, &["--aa"], &["--sampling", "adaptive"]),
        (
            &plain,
            &["--aa", "--sampling", "adaptive"],
            &["--noise-threshold", "0.5"],
        ),
        (
            &plain,
            &["--aa", "--sampling", "adaptive"],
            &["--min-spp", "12"],
        ),
        (
            &plain,
            &["--aa", "--sampling", "adaptive"],
            &["--max-spp", "9"],
        ),
        (&plain, &[], &["--soft-shadows"]),
        (&plain, &[], &["--no-shadows"]),
        (&plain, &["--soft-shadows"], &["--light-size", "2"]),
        // With the scene's aperture of 0 the lens is a point: the samples
        // spread over it, the image stays, the counts change.
        (&plain, &[], &["--dof"]),
        (&plain, &[], &["--aperture", "6"]),
        (&plain, &["--aperture", "6"], &["--focal", "2"]),
        (&plain, &[], &["--ambient", "0.5"]),
        (&plain, &[], &["--accel", "none"]),
        (&plain, &["--accel", "grid"], &["--grid-m", "4"]),
        (&plain, &["--aa"], &["--seed", "7"]),
        (&plain, &["--aa"], &["--threads", "1"]),
    ];
    let case_flag = |added: &[&str]| added[0].trim_start_matches("--").to_string();
    for flag in shared_flags() {
        assert!(
            cases.iter().any(|(_, _, added)| case_flag(added) == flag),
            "--{flag}: no case"
        );
    }
    // Where a flag, applied, shows in nothing a run gives (these must
    // indeed change nothing, so the list only shrinks).
    let unseen: &[(&str, &str, &str)] = &[
        (
            "inspect",
            "dof",
            "a pinhole lens (aperture 0): sample 0's rays stay",
        ),
        ("observe", "dof", "a pinhole lens: the rays drawn stay"),
        (
            "inspect",
            "noise-threshold",
            "inspect records one of a pixel's samples: the threshold decides how many it takes, not what each is",
        ),
        (
            "inspect",
            "min-spp",
            "inspect records one of a pixel's samples: the minimum decides how many it takes, not what each is",
        ),
        (
            "sweep",
            "dof",
            "the spp study renders N x N samples with a pinhole lens or without",
        ),
        (
            "sweep",
            "min-spp",
            "the spp study gives adaptive sampling each point's N's bounds, N^2 / 4 to (2N)^2",
        ),
        (
            "sweep",
            "max-spp",
            "the spp study gives adaptive sampling each point's N's bounds, N^2 / 4 to (2N)^2",
        ),
        (
            "compare",
            "accel",
            "compare counts rays, not the structure's work",
        ),
        (
            "compare",
            "grid-m",
            "compare counts rays, not the structure's work",
        ),
        (
            "observe",
            "accel",
            "the figure's own view is traced with a BVH; the rays drawn hit the same",
        ),
        (
            "observe",
            "grid-m",
            "the figure's own view is traced with a BVH; the rays drawn hit the same",
        ),
    ];
    let mut wrong = Vec::new();
    for (scene, before, added) in cases {
        let flag = case_flag(added);
        let flags: Vec<&str> = before.iter().chain(added.iter()).copied().collect();
        for subcommand in taking(&flag) {
            let (before, flags) = if subcommand == "report" {
                if REPORT_REFUSES.contains(&flag.as_str()) {
                    let out = dir.join("refused.html");
                    let args =
                        [&["report", scene, "-o", out.to_str().unwrap()][..], added].concat();
                    let said = workbench_fails(&args);
                    if !said.contains(&format!("report does not take --{flag}")) || out.exists() {
                        wrong.push(format!("report {added:?} is not refused: {said}"));
                    }
                    continue;
                }
                (report_takes(before), report_takes(&flags))
            } else {
                (before.to_vec(), flags.clone())
            };
            let base = outcome(&subcommand, &flag, scene, &dir, &before);
            let changed = outcome(&subcommand, &flag, scene, &dir, &flags);
            let same = base == changed;
            let unchanged = flag == "threads"
                || unseen
                    .iter()
                    .any(|&(c, f, _)| (c, f) == (subcommand.as_str(), flag.as_str()));
            if same != unchanged {
                let what = if same {
                    "changes nothing"
                } else {
                    "changes the outcome"
                };
                wrong.push(format!("{subcommand} {before:?} + {added:?} {what}"));
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // A light of size 0 is the point light: soft shadows change nothing.
    let hard = outcome("render", "", &plain, &dir, &[]);
    let point_light = ["--soft-shadows", "--light-size", "0"];
    let point = outcome("render", "light-size", &plain, &dir, &point_light);
    assert_eq!(hard.files, point.files);
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
