//! `workbench lesson list` and `workbench lesson check`: the bundled
//! lessons all pass; a lesson whose solution does not satisfy its check,
//! or whose check holds before the student acts, fails; a malformed file
//! gets a located error.

use crate::support::{Scratch, workbench, workbench_ok};

/// A one-step lesson on an inline scene, `{check}` and `{solution}` filled
/// in by each test.
const TEMPLATE: &str = r#"title = "Anti-aliasing"
chapter = 7

[scene]
p3f = """
v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 resolution 16 16
l 0 5 5 1 1 1
f 1 0 0 1 0 0 0 0 1 0 1
s 0 0 0 1
"""

[start]
settings = "--no-aa --spp 2"

[[step]]
title = "Four by four"
text = "Turn anti-aliasing on with N = 4."
check = { kind = "all", checks = [
    { kind = "value", of = "aa", is = "on" },
    { kind = "value", of = "spp", is = ">= 4" },
] }
solution = { settings = "{solution}" }
"#;

fn lesson_file(dir: &Scratch, name: &str, solution: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, TEMPLATE.replace("{solution}", solution)).unwrap();
    path.display().to_string()
}

#[test]
fn a_sound_lesson_passes_step_by_step() {
    let dir = Scratch::new("lesson-sound");
    let file = lesson_file(&dir, "aa.toml", "--aa --spp 4");
    let out = workbench_ok(&["lesson", "check", &file]);
    assert!(out.contains("aa (chapter 7): Anti-aliasing"), "{out}");
    assert!(out.contains("step 1/1 Four by four: pass"), "{out}");
    assert!(out.contains("all 1 steps pass"), "{out}");
}

#[test]
fn a_solution_that_does_not_satisfy_its_check_fails() {
    let dir = Scratch::new("lesson-bad-solution");
    let file = lesson_file(&dir, "aa.toml", "--aa --spp 3");
    let run = workbench(&["lesson", "check", &file]);
    assert!(!run.status.success());
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(
        out.contains("step 1/1 Four by four: FAIL: the solution does not pass the check: spp is 3, expected >= 4"),
        "{out}"
    );
}

#[test]
fn a_check_that_holds_before_the_student_acts_fails() {
    let dir = Scratch::new("lesson-already-done");
    let text = TEMPLATE
        .replace("--no-aa --spp 2", "--aa --spp 4")
        .replace("{solution}", "--aa --spp 8");
    let path = dir.join("done.toml");
    std::fs::write(&path, text).unwrap();
    let run = workbench(&["lesson", "check", &path.display().to_string()]);
    assert!(!run.status.success());
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(
        out.contains("FAIL: the check already holds before the student acts (aa is on; spp is 4)"),
        "{out}"
    );
}

#[test]
fn a_malformed_lesson_gets_a_located_error() {
    let dir = Scratch::new("lesson-malformed");
    let cases = [
        // A check of no kind the workbench knows: line 21, where it starts.
        (
            TEMPLATE.replace("kind = \"all\"", "kind = \"every\""),
            ":18:18: unknown variant `every`, expected one of `value`, `answer`, `measure`, `all`",
        ),
        // A quantity that names nothing.
        (
            TEMPLATE.replace("of = \"spp\"", "of = \"sp\""),
            "no setting `sp`",
        ),
        // Broken P3F inside the lesson: the lesson's own line 7.
        (
            TEMPLATE.replace("l 0 5 5 1 1 1", "l 0 5 five"),
            ":7:1: in the scene: in `l`: expected 3 or 6 numbers, found 2",
        ),
        // An edit the scene refuses, located at its string.
        (
            TEMPLATE.replace(
                "settings = \"--no-aa --spp 2\"",
                "edits = [\"object 4 ior 1.5\"]",
            ),
            ":13:10",
        ),
    ];
    for (i, (text, expected)) in cases.iter().enumerate() {
        let path = dir.join(format!("bad{i}.toml"));
        std::fs::write(&path, text.replace("{solution}", "--aa --spp 4")).unwrap();
        let run = workbench(&["lesson", "check", &path.display().to_string()]);
        assert!(!run.status.success(), "case {i}");
        let out = String::from_utf8_lossy(&run.stdout);
        assert!(out.contains(&format!("bad{i}.toml")), "case {i}: {out}");
        assert!(
            out.contains(expected),
            "case {i}: expected {expected:?} in {out}"
        );
    }
}

#[test]
fn an_unknown_lesson_name_lists_the_lessons() {
    let run = workbench(&["lesson", "check", "no-such-lesson"]);
    assert!(!run.status.success());
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(
        out.contains("no bundled lesson called `no-such-lesson`"),
        "{out}"
    );
    assert!(out.contains("camera"), "{out}");
}

#[test]
fn the_bundled_lessons_are_listed_in_the_courses_order() {
    let out = workbench_ok(&["lesson", "list", "--format", "json"]);
    let rows: serde_json::Value = serde_json::from_str(&out).unwrap();
    let rows = rows.as_array().unwrap();
    assert!(rows.len() >= 12, "{} lessons", rows.len());
    let chapters: Vec<u64> = rows
        .iter()
        .map(|r| r["chapter"].as_u64().unwrap())
        .collect();
    assert!(chapters.is_sorted(), "{chapters:?}");
    for chapter in 1..=12 {
        assert!(
            chapters.contains(&chapter),
            "no lesson for chapter {chapter}"
        );
    }
    for row in rows {
        let steps = row["steps"].as_array().unwrap().len();
        assert!((3..=6).contains(&steps), "{}: {steps} steps", row["name"]);
    }
}

/// Every bundled lesson replays: each step fails before its solution and
/// passes after it.
#[test]
fn every_bundled_lesson_passes_its_check() {
    let out = workbench_ok(&["lesson", "check"]);
    assert!(!out.contains("FAIL"), "{out}");
    assert!(out.contains("steps pass"), "{out}");
}

/// The complete example of `docs/LESSONS.md` is a lesson that passes: the
/// teachers' page cannot drift from the format.
#[test]
fn the_documented_example_passes() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/LESSONS.md"))
        .unwrap();
    let start = doc
        .find("```toml\n# Chapters")
        .expect("the complete example")
        + "```toml\n".len();
    let example = &doc[start..start + doc[start..].find("```\n").unwrap()];
    let dir = Scratch::new("lesson-documented");
    let path = dir.join("shadows.toml");
    std::fs::write(&path, example).unwrap();
    let out = workbench_ok(&["lesson", "check", &path.display().to_string()]);
    assert!(out.contains("all 3 steps pass"), "{out}");
}

/// Side B's own edits: `compare-edits` changes B's scene and leaves A's
/// as it was (the check reads both); without compare mode it is a located
/// error.
#[test]
fn compare_edits_change_side_b_alone() {
    let dir = Scratch::new("lesson-compare-edits");
    let text = TEMPLATE
        .replace(
            "settings = \"--no-aa --spp 2\"",
            "settings = \"--no-aa --spp 2\"\ncompare = \"--aa\"",
        )
        .replace(
            r#"check = { kind = "all", checks = [
    { kind = "value", of = "aa", is = "on" },
    { kind = "value", of = "spp", is = ">= 4" },
] }
solution = { settings = "{solution}" }"#,
            r#"check = { kind = "all", checks = [
    { kind = "value", of = "object 0 kd", side = "b", is = 0.25 },
    { kind = "value", of = "object 0 kd", is = 1 },
    { kind = "value", of = "aa", side = "b", is = "on" },
] }
solution = { compare-edits = ["object 0 kd 0.25"] }"#,
        );
    let path = dir.join("b.toml");
    std::fs::write(&path, &text).unwrap();
    let out = workbench_ok(&["lesson", "check", &path.display().to_string()]);
    assert!(out.contains("step 1/1 Four by four: pass"), "{out}");

    let without_b = text.replace("compare = \"--aa\"", "");
    std::fs::write(&path, &without_b).unwrap();
    let line = 1 + without_b
        .lines()
        .position(|l| l.starts_with("solution = { compare-edits"))
        .unwrap();
    let run = workbench(&["lesson", "check", &path.display().to_string()]);
    assert!(!run.status.success());
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(
        out.contains(&format!("b.toml:{line}:")) && out.contains("compare mode is off"),
        "{out}"
    );
}
