//! A lesson's scene opened, its references checked, a step set up and a
//! step's failure worded, on lessons written here.

use std::path::PathBuf;

use super::*;
use crate::lessons::actions::Located;
use crate::lessons::format::{SceneFiles, parse_lesson};

/// Two spheres and one light, written in the lesson from its line 6;
/// two steps, the second with a setup, each checking `CHECKED`.
const LESSON: &str = r#"title = "Replayed"
chapter = 1

[scene]
p3f = """
v
from 0 0 10
at 0 0 0
up 0 1 0
angle 30
hither 0.01
resolution 16 16
l 0 10 5 1 1 1
f 0.8 0.8 0.8 1 0 0 0 0 1 0 1
s -1 0 0 0.5
s 1 0 0 0.5
"""

[[step]]
title = "Anti-aliasing"
text = "Turn it on."
check = { kind = "value", of = "aa", is = "on" }
solution = { settings = "--aa" }

[[step]]
title = "Samples"
text = "Take three."
setup = { settings = "--spp 2" }
check = { kind = "value", of = "CHECKED", is = 3 }
solution = { settings = "--spp 3" }
"#;

fn lesson(text: &str) -> Lesson {
    parse_lesson(text, "test", "test.toml", SceneFiles::Nowhere).unwrap()
}

fn replayed() -> Lesson {
    lesson(&LESSON.replace("CHECKED", "spp"))
}

/// `lesson`'s steps replayed, each checked before and after its solution.
fn walk(lesson: &Lesson) -> Vec<StepReplay> {
    replay(lesson, &mut |_, _| {}).unwrap()
}

/// The lesson's error from opening `lesson`'s scene.
fn scene_error(lesson: &Lesson) -> String {
    let Err(e) = open_scene(lesson) else {
        panic!("the scene opened");
    };
    format!("{e:#}")
}

#[test]
fn an_inline_scenes_error_names_the_lesson_files_line() {
    // Scene line 3 (`at 0 0 0`) is lesson line 8, the scene starting at 6.
    let broken = LESSON
        .replace("CHECKED", "spp")
        .replace("at 0 0 0", "at 0 0 zero");
    let e = scene_error(&lesson(&broken));
    assert_eq!(
        e,
        "test.toml:8:8: in the scene: in `v`: expected the camera target (at), found `zero`"
    );
}

#[test]
fn a_scene_files_whole_file_error_is_at_the_lessons_line() {
    let mut lesson = replayed();
    let at = |path: &str| {
        LessonScene::File(Located {
            value: PathBuf::from(path),
            line: 5,
            column: 7,
        })
    };
    // A file that cannot be read: a mistake of the whole file, at no
    // line of its own.
    lesson.scene = at("/no/such/folder/scene.p3f");
    let e = scene_error(&lesson);
    assert!(
        e.starts_with("test.toml:5:7: the scene /no/such/folder/scene.p3f: "),
        "{e}"
    );
    // A mistake inside the file keeps the file's own place.
    let bad = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/bad_scenes/camera_angle_180.p3f"
    );
    lesson.scene = at(bad);
    let e = scene_error(&lesson);
    assert!(e.starts_with("test.toml:5:7: the lesson's scene"), "{e}");
    assert!(e.contains("camera_angle_180.p3f:3:7"), "{e}");
}

#[test]
fn references_beyond_the_scene_are_errors_that_count_what_there_is() {
    for (of, said) in [
        (
            "object 2 kd",
            "no object 2: once this step is solved, the scene has objects 0 to 1",
        ),
        (
            "tree blocker 1",
            "no light 1: once this step is solved, the scene has light 0",
        ),
    ] {
        let text = LESSON.replace("CHECKED", of);
        let e = scene_error(&lesson(&text));
        assert!(e.contains(said), "{of}: {e}");
        assert!(e.starts_with("test.toml:29:"), "{of}: {e}");
    }
    let no_lights = LESSON.replace("l 0 10 5 1 1 1\n", "");
    let e = scene_error(&lesson(&no_lights.replace("CHECKED", "tree blocker 0")));
    assert!(
        e.contains("no light 0: once this step is solved, the scene has none"),
        "{e}"
    );
    // Within the scene, the scene opens.
    let fine = lesson(&LESSON.replace("CHECKED", "object 1 kd"));
    assert!(open_scene(&fine).is_ok());
}

#[test]
fn a_step_starts_from_its_setup_after_the_earlier_solutions() {
    let lesson = replayed();
    let (scene, world) = open_scene(&lesson).unwrap();
    let first = state_at_step(&lesson, &scene, &world, 0).unwrap();
    assert!(!first.a.settings.antialiasing);
    let second = state_at_step(&lesson, &scene, &world, 1).unwrap();
    // The first step's solution, then the second's setup; not its solution.
    assert!(second.a.settings.antialiasing);
    assert_eq!(second.a.settings.samples, 2);
}

#[test]
fn replay_checks_each_step_before_and_after_its_solution() {
    let walked = walk(&replayed());
    assert_eq!(walked.len(), 2);
    for step in &walked {
        assert!(!step.before.is_done() && step.after.is_done(), "{step:?}");
        assert_eq!(step.failure(), None);
    }
    // A setup that already solves the step: its check holds before.
    let solved = LESSON.replace("CHECKED", "spp").replace(
        "setup = { settings = \"--spp 2\" }",
        "setup = { settings = \"--spp 3\" }",
    );
    let walked = walk(&lesson(&solved));
    let failure = walked[1].failure().unwrap();
    assert!(
        failure.starts_with("the check already holds before the student acts ("),
        "{failure}"
    );
}

#[test]
fn a_wrong_answer_in_a_solution_shows_what_the_workbench_computes() {
    let text = LESSON
        .replace(
            r#"check = { kind = "value", of = "CHECKED", is = 3 }"#,
            r#"check = { kind = "answer", question = "Objects:", of = "objects" }"#,
        )
        .replace(
            r#"solution = { settings = "--spp 3" }"#,
            "solution = { answer = 3 }",
        );
    let walked = walk(&lesson(&text));
    assert_eq!(walked[0].computed, None);
    assert_eq!(walked[1].computed.as_deref(), Some("2"));
    let failure = walked[1].failure().unwrap();
    assert!(
        failure.ends_with(" (the workbench computes 2)"),
        "{failure}"
    );
}

#[test]
fn a_failure_says_which_side_of_the_step_is_wrong() {
    let step = |before: Verdict, after: Verdict, computed: Option<&str>| StepReplay {
        title: "t".into(),
        before,
        after,
        computed: computed.map(String::from),
    };
    let not_yet = || Verdict::NotYet("not yet".into());
    let done = || Verdict::Done("done".into());
    assert_eq!(step(not_yet(), done(), None).failure(), None);
    assert_eq!(
        step(done(), done(), None).failure().unwrap(),
        "the check already holds before the student acts (done)"
    );
    assert_eq!(
        step(not_yet(), Verdict::Wrong("wrong".into()), Some("0.5"))
            .failure()
            .unwrap(),
        "the solution does not pass the check: wrong (the workbench computes 0.5)"
    );
    assert_eq!(
        step(not_yet(), not_yet(), None).failure().unwrap(),
        "the solution does not pass the check: not yet"
    );
}
