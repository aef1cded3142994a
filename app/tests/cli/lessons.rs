//! `workbench lesson list` and `workbench lesson check`: the bundled
//! lessons all pass; a lesson whose solution does not satisfy its check,
//! or whose check holds before the student acts, fails; a malformed file
//! gets a located error.

use crate::support::{Scratch, workbench, workbench_fails, workbench_ok};

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

/// A one-step lesson (anti-aliasing on with N >= 4) written as `name` in
/// `dir`, solved by the `render` flags `solution`: its path.
pub(crate) fn lesson_file(dir: &Scratch, name: &str, solution: &str) -> String {
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
        // A check of no kind the workbench knows: at the kind's value.
        (
            TEMPLATE.replace("kind = \"all\"", "kind = \"every\""),
            ":18:18: no check kind `every`; expected one of value, answer, measure, all",
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

/// The class folder the web page's CI check opens by its index
/// (`?folder=app/tests/class/lessons.index`) passes on the desktop, its
/// lessons in chapter order, reading their scene file beside them or a
/// bundled scene (which the page fetches from `scenes/`).
#[test]
fn the_class_folder_of_the_page_check_passes() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/class");
    let out = workbench_ok(&["lesson", "check", dir]);
    assert!(out.contains("all 3 steps pass"), "{out}");
    let eye = out.find("eye_rays (chapter 1)").expect(&out);
    let aa = out.find("anti_aliasing (chapter 2)").expect(&out);
    assert!(eye < aa, "{out}");
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

/// Where `needle` first appears in `text`: `:line:column` (1-based,
/// columns in characters), as the messages write it.
fn place(text: &str, needle: &str) -> String {
    let offset = text.find(needle).expect("the needle is in the text");
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before[before.rfind('\n').map_or(0, |i| i + 1)..]
        .chars()
        .count()
        + 1;
    format!(":{line}:{column}")
}

/// `lesson check` on `text` written as `name` in `dir`: it fails, and its
/// output.
fn check_fails(dir: &Scratch, name: &str, text: &str) -> (String, String) {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    let file = path.display().to_string();
    let run = workbench(&["lesson", "check", &file]);
    assert!(!run.status.success(), "{name} passed");
    (file, String::from_utf8_lossy(&run.stdout).into_owned())
}

/// A mistake inside a check is reported at its own value, and every
/// mistake of the file at once, before anything is replayed.
#[test]
fn every_mistake_in_a_check_is_reported_at_its_value() {
    let dir = Scratch::new("lesson-check-typos");
    let text = TEMPLATE
        .replace("of = \"aa\"", "of = \"tree refracions\"")
        .replace("is = \">= 4\"", "is = \"at least 4\"")
        .replace("{solution}", "--aa --spp 4");
    let (file, out) = check_fails(&dir, "typos.toml", &text);
    let typo = format!(
        "error: {file}{}: no tree figure `refracions`",
        place(&text, "\"tree refracions\"")
    );
    let words = format!(
        "error: {file}{}: `spp` is a number: `at least 4` can never match it",
        place(&text, "\"at least 4\"")
    );
    assert!(out.contains(&typo), "expected {typo:?} in {out}");
    assert!(out.contains(&words), "expected {words:?} in {out}");
    assert!(!out.contains("step 1/1"), "{out}");
}

/// An object the scene does not have is the lesson's mistake, at the
/// number, before the steps are replayed; not a failing solution.
#[test]
fn an_object_the_scene_lacks_is_refused_at_its_number() {
    let dir = Scratch::new("lesson-no-object");
    let text = TEMPLATE
        .replace("of = \"aa\", is = \"on\"", "of = \"object 99 kd\", is = 1")
        .replace("{solution}", "--aa --spp 4");
    let (file, out) = check_fails(&dir, "object.toml", &text);
    let expected = format!(
        "error: {file}{}: no object 99: once this step is solved, the scene has object 0",
        place(&text, "99")
    );
    assert!(out.contains(&expected), "expected {expected:?} in {out}");
    assert!(!out.contains("FAIL"), "{out}");
}

/// A scene file that is not there is reported at the lesson's `file =`
/// value with the path it was looked for at; a lesson file that is not
/// there, with no line or column.
#[test]
fn missing_files_are_reported_where_they_are_named() {
    let dir = Scratch::new("lesson-missing-files");
    let start = TEMPLATE.find("p3f = ").unwrap();
    let end = TEMPLATE.find("\"\"\"\n\n[start]").unwrap() + 3;
    let text = format!(
        "{}file = \"scenes/gone.p3f\"{}",
        &TEMPLATE[..start],
        &TEMPLATE[end..]
    )
    .replace("{solution}", "--aa --spp 4");
    let (file, out) = check_fails(&dir, "scene.toml", &text);
    let resolved = dir.join("scenes/gone.p3f");
    let expected = format!(
        "error: {file}{}: no scene file {}",
        place(&text, "\"scenes/gone.p3f\""),
        resolved.display()
    );
    assert!(out.contains(&expected), "expected {expected:?} in {out}");

    let absent = dir.join("absent.toml").display().to_string();
    let run = workbench(&["lesson", "check", &absent]);
    assert!(!run.status.success());
    let out = String::from_utf8_lossy(&run.stdout);
    assert!(
        out.contains(&format!("error: {absent}: cannot read the lesson")),
        "{out}"
    );
}

/// An `all` check that fails says every part that fails, and yes/no
/// quantities are said in yes and no.
#[test]
fn a_failing_all_says_every_part_in_the_formats_words() {
    let dir = Scratch::new("lesson-all-parts");
    let text = TEMPLATE
        .replace(
            "{ kind = \"value\", of = \"aa\", is = \"on\" },",
            "{ kind = \"value\", of = \"aa\", is = \"on\" },\n    { kind = \"value\", of = \"observer\", is = \"yes\" },",
        )
        .replace("{solution}", "--spp 3");
    let (_, out) = check_fails(&dir, "all.toml", &text);
    assert!(
        out.contains(
            "FAIL: the solution does not pass the check: aa is off, expected on; \
             observer is no, expected yes; spp is 3, expected >= 4"
        ),
        "{out}"
    );
}

/// A wrong recorded answer shows the teacher the value the workbench
/// computed; the verdict itself (what a student sees) does not.
#[test]
fn a_wrong_recorded_answer_shows_the_computed_value() {
    let dir = Scratch::new("lesson-wrong-answer");
    let text = TEMPLATE.replace(
        r#"check = { kind = "all", checks = [
    { kind = "value", of = "aa", is = "on" },
    { kind = "value", of = "spp", is = ">= 4" },
] }
solution = { settings = "{solution}" }"#,
        r#"check = { kind = "answer", question = "Objects in the scene:", of = "objects" }
solution = { answer = 3 }"#,
    );
    let (_, out) = check_fails(&dir, "answer.toml", &text);
    assert!(
        out.contains(
            "FAIL: the solution does not pass the check: 3 is not right \
             (the workbench computes 1)"
        ),
        "{out}"
    );
}

/// A lesson given where a scene is expected is named for what it is, with
/// the commands that open it, whichever headless command was run.
#[test]
fn a_lesson_given_as_a_scene_says_how_to_open_it() {
    let lesson = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../assets/lessons/shadows.toml"
    );
    for command in [
        &["render", lesson, "-o", "never.png"][..],
        &["inspect", lesson, "--pixel", "1", "1"],
    ] {
        let err = workbench_fails(command);
        assert!(
            err.contains(&format!("{lesson} is a lesson, not a scene: open it in the window with `workbench --lesson {lesson}`")),
            "{err}"
        );
        assert!(
            err.contains(&format!("`workbench lesson check {lesson}`")),
            "{err}"
        );
    }
}

/// `lesson new` writes a starting file that passes `lesson check` as
/// written, titled from its name, and never writes over a file.
#[test]
fn a_new_lesson_passes_its_check_and_is_never_written_twice() {
    let dir = Scratch::new("lesson-new");
    let name = dir.join("light_and_shadow").display().to_string();
    let out = workbench_ok(&["lesson", "new", &name]);
    let file = format!("{name}.toml");
    assert!(out.contains(&format!("wrote {file}")), "{out}");
    let check = workbench_ok(&["lesson", "check", &file]);
    assert!(
        check.contains("light_and_shadow (chapter 1): Light and shadow"),
        "{check}"
    );
    assert!(check.contains("all 2 steps pass"), "{check}");
    std::fs::write(&file, "kept").unwrap();
    let err = workbench_fails(&["lesson", "new", &file]);
    assert!(
        err.contains(&format!("{file} exists already: nothing written")),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "kept");
}

/// `lesson check --format json`: each lesson's steps with pass or what
/// failed, and each mistake with its file, line and column.
#[test]
fn lesson_check_speaks_json_for_a_teachers_ci() {
    let dir = Scratch::new("lesson-check-json");
    let good = lesson_file(&dir, "good.toml", "--aa --spp 4");
    let short = lesson_file(&dir, "short.toml", "--aa --spp 3");
    let text = (TEMPLATE.replace("\"spp\"", "\"spq\"")).replace("{solution}", "--aa --spp 4");
    let (broken, _) = check_fails(&dir, "broken.toml", &text);
    let run = workbench(&[
        "lesson", "check", &good, &short, &broken, "--format", "json",
    ]);
    assert!(!run.status.success());
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    assert_eq!(
        (json["steps"].as_u64(), json["failures"].as_u64()),
        (Some(2), Some(2)),
        "{json}"
    );
    let lessons = json["lessons"].as_array().unwrap();
    assert_eq!(lessons[0]["steps"][0]["pass"], true, "{json}");
    assert_eq!(lessons[1]["steps"][0]["pass"], false, "{json}");
    let failure = lessons[1]["steps"][0]["failure"].as_str().unwrap();
    assert!(failure.contains("spp is 3, expected >= 4"), "{failure}");
    let error = &lessons[2]["errors"][0];
    let at = format!(":{}:{}", error["line"], error["column"]);
    assert_eq!(at, place(&text, "\"spq\""), "{json}");
    assert!(
        error["message"]
            .as_str()
            .unwrap()
            .contains("no setting `spq`"),
        "{json}"
    );
}

/// A lesson written for a later format is refused at its `format-version`,
/// that error alone, before any key the later format may have renamed.
#[test]
fn a_later_format_version_is_refused_at_its_value() {
    let dir = Scratch::new("lesson-format-version");
    let text = TEMPLATE.replace("{solution}", "--aa --spp 4");
    let later = format!("format-version = 2\nrenamed-key = 1\n{text}");
    let (file, out) = check_fails(&dir, "later.toml", &later);
    assert!(
        out.contains(&format!(
            "error: {file}:1:18: format-version 2 is newer than this workbench reads (up to 1)"
        )),
        "{out}"
    );
    assert!(!out.contains("renamed-key"), "{out}");
}
