//! `workbench lesson explain`: the state a step starts from with every
//! quantity a check reads there, and `--find`, whose pixels pass the
//! step's check when a lesson pins them.

use crate::support::{Scratch, workbench_fails, workbench_ok};

/// The bundled refraction lesson, as a teacher would copy it.
fn refraction_lesson() -> String {
    std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/lessons/refraction.toml"
    ))
    .unwrap()
}

/// The words of the line of `out` starting with `name`, after it.
fn value_of<'a>(out: &'a str, name: &str) -> &'a str {
    out.lines()
        .find_map(|l| {
            let rest = l.trim_start().strip_prefix(name)?;
            rest.starts_with("  ").then(|| rest.trim())
        })
        .unwrap_or_else(|| panic!("no `{name}` in\n{out}"))
}

#[test]
fn explain_says_the_state_a_step_starts_from() {
    let out = workbench_ok(&["lesson", "explain", "refraction", "--step", "3"]);
    assert!(
        out.contains("step 3/4 The cube traps light, as it starts"),
        "{out}"
    );
    assert!(out.contains("pinned pixel: (21, 21)"), "{out}");
    assert!(
        out.contains(
            "check: not yet: tree eye-object is 1, expected 2; tree tir is no, expected yes"
        ),
        "{out}"
    );
    assert!(out.contains("eye (depth 0): hit sphere #1"), "{out}");
    // The start's flags and the scene, read as checks read them.
    assert_eq!(value_of(&out, "depth"), "6");
    assert_eq!(value_of(&out, "aa"), "off");
    assert_eq!(value_of(&out, "objects"), "4");
    assert_eq!(value_of(&out, "object 2 kind"), "box");
    assert_eq!(value_of(&out, "tree eye-object"), "1");
    assert_eq!(value_of(&out, "tree tir"), "no");
    assert_eq!(value_of(&out, "tree blocker 0"), "none");
}

/// Every pixel `--find` lists that a teacher might pick (the first and the
/// one it suggests) passes the step's check once the lesson's solution
/// pins it: `lesson check` on the lesson so changed passes the step.
#[test]
fn a_pixel_find_lists_passes_the_steps_check() {
    let out = workbench_ok(&[
        "lesson",
        "explain",
        "refraction",
        "--step",
        "3",
        "--find",
        "eye-object=2",
        "--find",
        "tir=yes",
    ]);
    assert!(
        out.contains("where tree eye-object is 2 and tree tir is yes"),
        "{out}"
    );
    let (row, runs) = value_of_row(&out);
    let first_x: u32 = runs
        .split([',', '-'])
        .next()
        .unwrap()
        .trim()
        .parse()
        .unwrap();
    let suggested = out
        .split("nearest their middle: pixel = [")
        .nth(1)
        .and_then(|r| r.split(']').next())
        .unwrap_or_else(|| panic!("no suggestion in\n{out}"));
    let dir = Scratch::new("lesson-explain-find");
    for pixel in [format!("{first_x}, {row}"), suggested.to_string()] {
        let lesson = refraction_lesson();
        let changed = lesson.replace("pixel = [45, 27]", &format!("pixel = [{pixel}]"));
        assert_ne!(changed, lesson, "the step's solution pins [45, 27]");
        let path = dir.join("refraction.toml");
        std::fs::write(&path, changed).unwrap();
        let check = workbench_ok(&["lesson", "check", &path.display().to_string()]);
        assert!(
            check.contains("step 3/4 The cube traps light: pass"),
            "pixel [{pixel}]:\n{check}"
        );
    }
}

/// The first `row Y: X...` line of `--find`'s list.
fn value_of_row(out: &str) -> (u32, &str) {
    let line = out
        .lines()
        .find_map(|l| l.trim_start().strip_prefix("row "))
        .unwrap_or_else(|| panic!("no row in\n{out}"));
    let (row, runs) = line.split_once(':').unwrap();
    (row.parse().unwrap(), runs)
}

#[test]
fn explain_with_a_pixel_says_whether_the_check_holds_there() {
    let out = workbench_ok(&[
        "lesson",
        "explain",
        "refraction",
        "--step",
        "3",
        "--pixel",
        "45",
        "27",
    ]);
    assert!(
        out.contains("check: holds: tree eye-object is 2; tree tir is yes"),
        "{out}"
    );
    assert_eq!(value_of(&out, "tree eye-kind"), "box");
}

#[test]
fn explain_refuses_what_it_cannot_answer() {
    let err = workbench_fails(&["lesson", "explain", "refraction", "--step", "9"]);
    assert!(
        err.contains("refraction has steps 1 to 4, no step 9"),
        "{err}"
    );
    let err = workbench_fails(&["lesson", "explain", "refraction", "--find", "refracions=1"]);
    assert!(err.contains("no tree figure `refracions`"), "{err}");
    let err = workbench_fails(&["lesson", "explain", "refraction", "--find", "eye-object=99"]);
    assert!(
        err.contains("step 1: no pixel of the 64x48 image where tree eye-object is 99"),
        "{err}"
    );
    let err = workbench_fails(&["lesson", "explain", "refraction", "--pixel", "64", "0"]);
    assert!(
        err.contains("pixel (64, 0) is outside the 64x48 image"),
        "{err}"
    );
}

/// The ray tree names where each object of a lesson's inline scene is
/// written: at the lesson file's line, as a mistake in that scene is
/// reported, not at the line within the `p3f` text.
#[test]
fn an_inline_scenes_objects_are_named_at_the_lesson_files_lines() {
    let lesson = refraction_lesson();
    let line_of = |command: &str| {
        1 + lesson
            .lines()
            .position(|l| l.starts_with(command))
            .unwrap_or_else(|| panic!("no `{command}` in the lesson"))
    };
    let out = workbench_ok(&["lesson", "explain", "refraction", "--step", "3"]);
    let sphere = format!(
        "eye (depth 0): hit sphere #1 (line {}:1)",
        line_of("s -1.3 ")
    );
    assert!(out.contains(&sphere), "no `{sphere}` in\n{out}");
    let floor = format!("hit plane #0 (line {}:1)", line_of("pl "));
    assert!(out.contains(&floor), "no `{floor}` in\n{out}");
}
