//! A student walking a lesson in the window: the lesson dropped on the
//! window and its first step set up, the check turning done when the
//! student acts, Next, a typed answer wrong then right, "Set up this step"
//! restoring a step, the progress surviving a restart, and Export
//! progress... saving it, with the student's name, for the teacher.

use std::sync::Arc;
use std::time::Duration;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use workbench::gui::WorkbenchApp;
use workbench::lessons::Verdict;
use workbench::lessons::format::LessonScene;
use workbench::lessons::progress::Progress;
use workbench::load::SceneSource;

use crate::harness::{DroppedPath, WINDOW, answer_dialogs, ready_window, small_window, wait_for};
use crate::persistence::{MemoryStorage, start};
use crate::support::Scratch;

/// Two steps on a small inline scene: anti-aliasing on (a value check),
/// then how many eye rays a pixel sends (a typed answer).
const LESSON: &str = r#"title = "Two steps"
chapter = 7

[scene]
p3f = """
v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 resolution 24 24
l 0 5 5 1 1 1
f 1 0 0 1 0 0 0 0 1 0 1
s 0 0 0 1
"""

[start]
settings = "--no-aa --spp 4"
pixel = [12, 12]

[[step]]
title = "Anti-aliasing"
text = "Turn **anti-aliasing** on: `colour = sum / N^2`."
check = { kind = "value", of = "aa", is = "on" }
solution = { settings = "--aa" }

[[step]]
title = "Eye rays"
text = "How many eye rays does each pixel send?"
check = { kind = "answer", question = "Eye rays per pixel:", of = "samples-per-pixel" }
solution = { answer = 16 }
"#;

type Window = Harness<'static, WorkbenchApp>;

fn verdict(app: &WorkbenchApp) -> Option<&Verdict> {
    app.lessons().verdict()
}

fn wait_for_verdict(harness: &mut Window, what: &str, wanted: fn(&Verdict) -> bool) {
    wait_for(harness, what, |app| {
        !app.lessons().is_checking() && verdict(app).is_some_and(wanted)
    });
}

fn answer(harness: &mut Window, text: &str) {
    harness.state_mut().lessons_mut().answer.clear();
    harness
        .get_by_role_and_label(Role::TextInput, "Eye rays per pixel:")
        .focus();
    harness.run_steps(2);
    harness
        .get_by_role_and_label(Role::TextInput, "Eye rays per pixel:")
        .type_text(text);
    harness.run_steps(2);
    assert_eq!(harness.state().lessons().answer, text, "the answer typed");
    harness.get_by_label("Check answer").click();
    harness.run_steps(2);
}

/// Drops the lesson file `path` on the window, as a teacher's lesson
/// opens: like a scene.
fn drop_lesson(harness: &mut Window, path: &std::path::Path) {
    harness
        .input_mut()
        .dropped_files
        .push(Arc::new(DroppedPath(path.to_path_buf())));
}

/// A window with lesson `text`, written as `name`.toml in a folder of its
/// own (kept while the window is used), dropped on it and its scene
/// loaded and planned.
fn open_lesson(name: &str, text: &str) -> (Scratch, Window) {
    let dir = Scratch::new(&format!("window-lesson-{name}"));
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    let mut harness = ready_window(WINDOW);
    drop_lesson(&mut harness, &path);
    let scene = format!("{name}.p3f");
    wait_for(&mut harness, "the lesson's scene", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == scene)
            && app.engine().settings().is_some()
    });
    (dir, harness)
}

#[test]
fn a_student_walks_a_lesson_and_the_progress_stays() {
    let (_dir, mut harness) = open_lesson("two_steps", LESSON);
    // Set up as the lesson starts: the lesson's own resolution, no
    // anti-aliasing, the pixel pinned.
    let settings = harness.state().engine().settings().cloned().unwrap();
    assert_eq!((settings.width, settings.height), (24, 24));
    assert!(!settings.antialiasing);
    assert_eq!(harness.state().inspector().pinned, Some((12, 12)));
    wait_for_verdict(&mut harness, "step 1 not yet done", |v| {
        matches!(v, Verdict::NotYet(_))
    });

    // The student acts: the check turns done and the step is recorded.
    harness
        .get_by_role_and_label(Role::CheckBox, "Anti-aliasing (A)")
        .click();
    wait_for_verdict(&mut harness, "step 1 done", Verdict::is_done);
    assert!(harness.state().lessons().done_steps().contains(&0));

    harness.get_by_label("Next").click();
    harness.run_steps(2);
    assert_eq!(harness.state().lessons().step(), 1);
    wait_for_verdict(&mut harness, "no answer yet", |v| {
        *v == Verdict::NotYet("no answer yet".into())
    });
    answer(&mut harness, "4");
    wait_for_verdict(&mut harness, "a wrong answer", |v| {
        matches!(v, Verdict::Wrong(_))
    });
    answer(&mut harness, "16");
    wait_for_verdict(&mut harness, "the right answer", Verdict::is_done);
    assert_eq!(
        harness.state().lessons().done_steps(),
        [0, 1].into_iter().collect()
    );

    // Back to step 1 and set it up again: anti-aliasing off as the step
    // starts; a done step stays done.
    harness.get_by_label("Back").click();
    harness.run_steps(2);
    harness.get_by_label("Set up this step").click();
    wait_for(&mut harness, "step 1 set up again", |app| {
        app.engine().settings().is_some_and(|s| !s.antialiasing)
    });
    wait_for_verdict(&mut harness, "step 1's check not holding", |v| {
        matches!(v, Verdict::NotYet(_))
    });
    assert!(harness.state().lessons().done_steps().contains(&0));

    // A restart keeps what was done, saved as soon as it changed.
    let saves_in = |harness: &Window| eframe::App::auto_save_interval(harness.state());
    assert_eq!(
        saves_in(&harness),
        Duration::ZERO,
        "steps done not saved yet"
    );
    let mut storage = MemoryStorage::default();
    eframe::App::save(harness.state_mut(), &mut storage);
    assert!(saves_in(&harness) > Duration::ZERO, "saved: the usual pace");
    drop(harness);
    let restarted = start(Some(&storage), None);
    let progress = &restarted.state().lessons().progress;
    assert_eq!(
        progress.done.get("two_steps"),
        Some(&[0, 1].into_iter().collect())
    );
}

/// Types `text` into the text box labelled `label`.
fn type_into(harness: &mut Window, label: &str, text: &str) {
    harness
        .get_by_role_and_label(Role::TextInput, label)
        .focus();
    harness.run_steps(2);
    harness
        .get_by_role_and_label(Role::TextInput, label)
        .type_text(text);
    harness.run_steps(2);
}

#[test]
fn export_progress_saves_the_steps_done_with_the_name_and_answer() {
    let (dir, mut harness) = open_lesson("to_export", LESSON);
    let answers = answer_dialogs(&mut harness);
    wait_for_verdict(&mut harness, "step 1 not yet done", |v| {
        matches!(v, Verdict::NotYet(_))
    });
    type_into(&mut harness, "Your name:", "Ada");
    harness
        .get_by_role_and_label(Role::CheckBox, "Anti-aliasing (A)")
        .click();
    wait_for_verdict(&mut harness, "step 1 done", Verdict::is_done);
    harness.get_by_label("Next").click();
    harness.run_steps(2);
    answer(&mut harness, "16");
    wait_for_verdict(&mut harness, "the right answer", Verdict::is_done);

    let exported = dir.join("handed-in.json");
    answers.next(Some(&exported));
    // Below the step's text: scrolled into the panel's view first.
    harness.get_by_label("Export progress...").scroll_to_me();
    harness.run_steps(2);
    harness.get_by_label("Export progress...").click();
    wait_for(&mut harness, "the progress written", |_| exported.exists());
    let (filter, offered, save) = answers.last();
    assert_eq!(filter, ["json"]);
    assert_eq!(offered.as_deref(), Some("Ada-progress.json"));
    assert!(save);

    let text = std::fs::read_to_string(&exported).unwrap();
    let progress = Progress::from_json(&text, &exported).unwrap();
    assert_eq!(progress.student.as_deref(), Some("Ada"));
    let lesson = progress.lessons.iter().find(|l| l.lesson == "to_export");
    let steps = &lesson.unwrap_or_else(|| panic!("{text}")).steps;
    let numbers: Vec<usize> = steps.iter().map(|s| s.step).collect();
    assert_eq!(numbers, [1, 2], "{text}");
    assert_eq!(steps[0].answer, None, "a step that asks nothing: {text}");
    assert_eq!(steps[1].answer.as_deref(), Some("16"), "{text}");
    assert!(steps.iter().all(|s| s.done_at.is_some()), "{text}");
}

/// The kd of object 0's material in `scene`.
fn kd_of_object_0(scene: &tracer::scene::Scene) -> f32 {
    scene.materials[scene.objects[0].material as usize].kd
}

/// The window opens a step's scene from a file it writes, whose lines are
/// not the lesson's; the ray tree and the editor still name each object
/// at the line the teacher wrote it on.
#[test]
fn a_lessons_objects_keep_the_lines_the_lesson_wrote_them_on() {
    let sphere = LESSON
        .lines()
        .position(|l| l.starts_with("s 0 0 0 1"))
        .map(|i| (u32::try_from(i).unwrap() + 1, 1));
    let (_dir, harness) = open_lesson("lines", LESSON);
    let shown = harness.state().engine().scene().unwrap();
    assert_eq!(shown.world.object_positions.get(0), sphere);
}

/// A lesson's compare layout with B's own edits: once set up, B shows its
/// edited scene with its settings, A the scene as the lesson wrote it.
#[test]
fn a_lessons_side_b_gets_its_own_edits() {
    let dir = Scratch::new("window-lesson-b-edits");
    let path = dir.join("b_edits.toml");
    let text = LESSON.replace(
        "pixel = [12, 12]",
        "pixel = [12, 12]\ncompare = \"--spp 2\"\ncompare-edits = [\"object 0 kd 0.25\"]",
    );
    std::fs::write(&path, text).unwrap();
    let mut harness = ready_window(WINDOW);
    drop_lesson(&mut harness, &path);
    wait_for(&mut harness, "the lesson set up, B edited", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == "b_edits.p3f")
            && app
                .side_b()
                .and_then(|b| b.engine.scene())
                .is_some_and(|s| kd_of_object_0(&s.scene) == 0.25)
            && app.side_b().and_then(|b| b.settings()).is_some()
    });
    let app = harness.state();
    assert_eq!(kd_of_object_0(&app.engine().scene().unwrap().scene), 1.0);
    let b = app.side_b().unwrap().settings().unwrap();
    assert_eq!(b.samples, 2, "B keeps its own settings");
}

/// A check that renders (the samples the render took) gets its verdict
/// with "keep refining" on: the check renders the side to its end, where
/// the window's render has none.
#[test]
fn a_rendering_check_ends_while_the_window_keeps_refining() {
    let text = LESSON.replace(
        r#"check = { kind = "value", of = "aa", is = "on" }"#,
        r#"check = { kind = "value", of = "samples mean", is = ">= 16" }"#,
    );
    let (_dir, mut harness) = open_lesson("refining", &text);
    harness
        .get_by_role_and_label(Role::CheckBox, "Keep refining (K)")
        .click();
    harness
        .get_by_role_and_label(Role::CheckBox, "Anti-aliasing (A)")
        .click();
    wait_for(&mut harness, "the window refining", |app| {
        app.engine()
            .settings()
            .is_some_and(|s| s.keep_refining && s.antialiasing)
    });
    wait_for_verdict(&mut harness, "16 samples a pixel, counted", |v| {
        *v == Verdict::Done("samples mean is 16".into())
    });
}

/// `--lesson-folder`: a folder's lessons join the panel's list by chapter,
/// each after the bundled ones of its chapter, and the panel opens on the
/// folder's first lesson in that order.
#[test]
fn a_lesson_folder_joins_the_list_by_chapter() {
    let dir = Scratch::new("window-lesson-folder");
    std::fs::write(dir.join("mine_seven.toml"), LESSON).unwrap();
    let chapter_one = LESSON.replace("chapter = 7", "chapter = 1");
    std::fs::write(dir.join("mine_one.toml"), chapter_one).unwrap();
    let mut harness = ready_window(WINDOW);
    harness.state_mut().open_lesson_folder(&dir);
    let lessons = harness.state().lessons();
    assert!(lessons.open, "the panel opens");
    let names = lessons.names();
    let at = |name: &str| {
        (names.iter().position(|n| *n == name)).unwrap_or_else(|| panic!("{name}: {names:?}"))
    };
    let chapters: Vec<u32> = workbench::lessons::bundled::all()
        .unwrap()
        .iter()
        .map(|l| l.chapter)
        .collect();
    let bundled_up_to = |chapter: u32| chapters.iter().filter(|&&c| c <= chapter).count();
    assert_eq!(at("mine_one"), bundled_up_to(1), "{names:?}");
    assert_eq!(at("mine_seven"), bundled_up_to(7) + 1, "{names:?}");
    let shown = lessons.lesson().map(|l| l.name.as_str());
    assert_eq!(
        shown,
        Some("mine_one"),
        "the folder's first lesson is shown"
    );
}

/// A page's link (`?lesson=shadows`): the window opens that bundled
/// lesson in the Lessons panel with its first step's scene set up.
#[test]
fn a_link_opens_a_bundled_lesson_set_up() {
    let mut harness = ready_window(WINDOW);
    harness.state_mut().open_link("?lesson=shadows");
    let lessons = harness.state().lessons();
    assert!(lessons.open, "the panel opens");
    let shown = lessons.lesson().map(|l| l.name.as_str());
    assert_eq!(shown, Some("shadows"));
    wait_for(&mut harness, "the lesson's scene set up", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == "shadows.p3f")
    });
    assert_eq!(harness.state().error(), None);
}

/// A second scene asked for while the first is still being fetched (a
/// link, or a pick in the page's scene list): the last asked for opens,
/// and what the first fetch gives (here: no such file) is dropped, not
/// said.
#[test]
fn the_last_scene_asked_for_wins_over_one_being_fetched() {
    let dir = Scratch::new("last-scene-wins");
    let wanted = dir.join("wanted.p3f");
    let scene = workbench::bundled::find("balls_low").unwrap();
    std::fs::write(&wanted, scene.text).unwrap();
    let mut harness = small_window(Harness::builder());
    let first = dir.join("missing.p3f");
    harness
        .state_mut()
        .open_link(&format!("?scene={}", first.display()));
    harness
        .state_mut()
        .open_link(&format!("?scene={}", wanted.display()));
    let label = wanted.display().to_string();
    wait_for(&mut harness, "the scene asked for last", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == label)
    });
    assert_eq!(harness.state().error(), None);
}

/// A link naming no bundled lesson or scene, or asking for what the page
/// does not read, says so with the names there are, and opens nothing;
/// the error outlasts a scene loaded after it.
#[test]
fn a_link_to_nothing_bundled_says_what_there_is() {
    for (query, said, one_there_is) in [
        (
            "?lesson=shadow",
            "no bundled lesson is called \"shadow\": the lessons are",
            "shadows",
        ),
        (
            "?scene=nope",
            "no bundled scene is called \"nope\": the scenes are",
            "balls_low",
        ),
        (
            "?lessons=shadows",
            "the link's `lessons` is not a setting",
            "a link reads lesson, folder, step, scene",
        ),
    ] {
        let mut harness = small_window(Harness::builder());
        let opened = harness.state().lessons().lesson().map(|l| l.name.clone());
        harness.state_mut().open_link(query);
        // The page's first scene may load before or after the link is
        // read: a scene loaded after it must leave its error shown.
        harness
            .state_mut()
            .open(SceneSource::Bundled("glass".into()));
        wait_for(&mut harness, "the next scene", |app| {
            app.engine()
                .scene()
                .is_some_and(|s| s.source.label() == "glass")
        });
        let error = harness.state().error().unwrap_or_default().to_string();
        assert!(error.contains(said), "{query}: {error}");
        assert!(error.contains(one_there_is), "{query}: {error}");
        let now = harness.state().lessons().lesson().map(|l| l.name.clone());
        assert_eq!(now, opened, "{query} changed the lesson shown");
        assert!(!harness.state().lessons().open, "{query} opened the panel");
    }
}

/// The Lessons panel sits beside the image, not over it: the step's text
/// and buttons and the image's area do not overlap, at the window's
/// default size.
#[test]
fn the_lessons_panel_leaves_the_image_uncovered() {
    let (_dir, mut harness) = open_lesson("beside", LESSON);
    harness.run_steps(2);
    let image = harness.get_by_role_and_label(Role::Image, "Render").rect();
    for label in [
        "Set up this step",
        "Next",
        "Show a hint",
        "Export progress...",
    ] {
        let Some(widget) = harness.query_by_label(label) else {
            continue;
        };
        let rect = widget.rect();
        assert!(
            !image.intersects(rect),
            "{label} at {rect:?} covers the image's area {image:?}"
        );
    }
    let next = harness.get_by_label("Next").rect();
    assert!(
        next.min.x >= image.max.x,
        "{next:?} is not right of {image:?}"
    );
    assert!(image.width() > 300.0, "the image got {image:?}");
}

/// `workbench --lesson NAME` opens a bundled lesson as `lesson check
/// NAME` finds it; a name that is neither a lesson nor a file is said,
/// with the lessons there are.
#[test]
fn the_lesson_argument_takes_a_bundled_name() {
    let mut harness = ready_window(WINDOW);
    harness
        .state_mut()
        .open_lesson_argument(std::path::Path::new("shadows"));
    wait_for(&mut harness, "the shadows lesson's scene", |app| {
        app.lessons().lesson().is_some_and(|l| l.name == "shadows")
            && app
                .engine()
                .scene()
                .is_some_and(|s| s.source.label() == "shadows.p3f")
    });
    assert!(harness.state().lessons().open);

    harness
        .state_mut()
        .open_lesson_argument(std::path::Path::new("shadowz"));
    harness.run_steps(2);
    let error = harness.state().error().unwrap_or_default().to_string();
    assert!(
        error.contains("no bundled lesson called `shadowz` and no such file")
            && error.contains("soft_shadows"),
        "{error}"
    );
}

/// A link's render flags reach the render, its `width=` included (the
/// window sizes its image by the resolution scale, which the width sets).
#[test]
fn a_links_settings_and_width_reach_the_render() {
    let mut harness = ready_window(WINDOW);
    harness
        .state_mut()
        .open_link("?scene=glass&width=96&spp=2&no-aa");
    wait_for(&mut harness, "the linked scene's settings", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == "glass")
            && app.engine().settings().is_some_and(|s| s.samples == 2)
    });
    let settings = harness.state().engine().settings().cloned().unwrap();
    assert_eq!(settings.width, 96, "{settings:?}");
    assert!(!settings.antialiasing);
    assert_eq!(harness.state().error(), None);
}

/// A class's folder linked by its index (`?folder=class/lessons.index`),
/// as a static host serves one: the lessons it names are fetched, each
/// with the scene file it names beside it, listed by chapter and the
/// first set up on its own scene; a lesson whose scene is missing is said
/// with the scene's URL, the others still listed.
#[test]
fn a_linked_folder_fetches_its_lessons_and_their_scene_files() {
    let dir = Scratch::new("window-linked-folder");
    let scene = LESSON.split("p3f = \"\"\"\n").nth(1).unwrap();
    let scene = scene.split("\"\"\"").next().unwrap();
    std::fs::write(dir.join("ball.p3f"), scene).unwrap();
    let with_file = |chapter: &str, file: &str| {
        let start = LESSON.find("[scene]").unwrap();
        let end = LESSON.find("[start]").unwrap();
        let scene = format!("[scene]\nfile = \"{file}\"\n\n");
        let text = format!("{}{scene}{}", &LESSON[..start], &LESSON[end..]);
        text.replace("chapter = 7", &format!("chapter = {chapter}"))
    };
    std::fs::write(dir.join("late.toml"), with_file("9", "ball.p3f")).unwrap();
    std::fs::write(dir.join("early.toml"), with_file("1", "ball.p3f")).unwrap();
    std::fs::write(dir.join("lost.toml"), with_file("2", "nowhere.p3f")).unwrap();
    let index = "# the class\nlate.toml\nearly.toml\n\nlost.toml\n";
    std::fs::write(dir.join("lessons.index"), index).unwrap();
    let mut harness = ready_window(WINDOW);
    let index = dir.join("lessons.index").display().to_string();
    harness.state_mut().open_link(&format!("?folder={index}"));
    let ball = dir.join("ball.p3f").display().to_string();
    wait_for(&mut harness, "the folder's first lesson set up", |app| {
        app.lessons().lesson().is_some_and(|l| l.name == "early")
            && app
                .engine()
                .scene()
                .is_some_and(|s| s.source.label() == "early.p3f")
    });
    let names = harness.state().lessons().names();
    assert!(
        names.contains(&"late") && !names.contains(&"lost"),
        "{names:?}"
    );
    let lesson = harness.state().lessons().lesson().unwrap();
    assert!(matches!(&lesson.scene, LessonScene::Fetched { url, .. } if url.value == ball));
    let error = harness.state().error().unwrap_or_default().to_string();
    let nowhere = dir.join("nowhere.p3f").display().to_string();
    assert!(
        error.contains(&format!("cannot read its scene {nowhere}")),
        "{error}"
    );
}
