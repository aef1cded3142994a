//! What the window's commands do, each seen in the renderer or on disk:
//! F5 reloads the file and keeps the user's settings, C puts the camera
//! back, saving writes the shown render (PNG) and the linear film (EXR), a
//! JPEG can be side B, the slow brute-force banner switches to the BVH,
//! and a lesson picked in the Open dialog opens in the Lessons window.

use std::path::Path;
use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tracer::accel::AccelKind;
use tracer::generate::{GenerateOptions, GeneratorName, generate};
use workbench::gui::WorkbenchApp;
use workbench::load::SceneSource;

use crate::harness::{
    WINDOW, answer_dialogs, drag, is_done, small_window_sized, wait_for, wait_for_scene, window,
};
use crate::support::scenes::spheres_on_a_floor;
use crate::support::{scratch, write};

/// The window on `scene`, its structure built.
fn window_on(scene: SceneSource) -> Harness<'static, WorkbenchApp> {
    let mut harness = window(Harness::builder().with_size(WINDOW), None, Some(scene));
    wait_for_scene(&mut harness);
    harness
}

fn settings(harness: &Harness<'static, WorkbenchApp>) -> tracer::render::RenderSettings {
    harness.state().engine().settings().cloned().unwrap()
}

#[test]
fn f5_reads_the_file_again_and_keeps_the_users_settings() {
    let dir = scratch("command-reload");
    let path = write(&dir, "scene.p3f", &spheres_on_a_floor(32, 24, "", ""));
    let mut harness = window_on(SceneSource::File(path.clone()));
    let objects = |app: &WorkbenchApp| app.engine().scene().unwrap().world.counts.objects();
    assert_eq!(objects(harness.state()), 3);
    harness.key_press(egui::Key::A);
    harness.run_steps(2);
    assert!(settings(&harness).antialiasing, "the file has no spp");

    let more = spheres_on_a_floor(32, 24, "", "s 0 2 0.5 0.5");
    std::fs::write(&path, more).unwrap();
    harness.key_press(egui::Key::F5);
    wait_for(&mut harness, "the file read again", |app| objects(app) == 4);
    wait_for_scene(&mut harness);
    assert!(settings(&harness).antialiasing, "the user's choice stays");
}

#[test]
fn c_puts_the_camera_back_where_the_file_has_it() {
    let mut harness = small_window_sized(Harness::builder(), WINDOW);
    let finished = |harness: &mut Harness<'static, WorkbenchApp>| {
        wait_for(harness, "the render on screen", |app| {
            is_done(app) && app.is_display_current()
        });
        harness.state().shown().unwrap().rgba.clone()
    };
    let before = finished(&mut harness);
    drag(&mut harness, "Render");
    harness.step();
    assert!(settings(&harness).camera.is_some(), "the drag orbited");
    assert!(
        finished(&mut harness) != before,
        "the orbit moves the image"
    );
    harness.key_press(egui::Key::C);
    harness.run_steps(2);
    assert_eq!(settings(&harness).camera, None);
    assert!(finished(&mut harness) == before, "back to the file's view");
}

/// Waits until `path` holds a whole file (the dialog's thread writes it).
fn written(harness: &mut Harness<'static, WorkbenchApp>, path: &Path) {
    wait_for(harness, "the file written", |_| {
        image::open(path).is_ok()
            || tracer::scene::parse_scene_file(path, &Default::default()).is_ok()
    });
}

#[test]
fn open_save_png_save_exr_and_save_scene_go_through_the_file_dialog() {
    let dir = scratch("command-dialogs");
    let scene = write(&dir, "scene.p3f", &spheres_on_a_floor(32, 24, "", ""));
    let mut harness = small_window_sized(Harness::builder(), WINDOW);
    let answers = answer_dialogs(&mut harness);
    wait_for_scene(&mut harness);

    // Cancelled: nothing changes, a notice says so.
    answers.next(None);
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::O);
    wait_for(&mut harness, "the notice", |_| {
        answers.paths.lock().unwrap().is_empty()
    });
    harness.run_steps(2);
    assert!(harness.query_by_label_contains("nothing opened").is_some());
    let (filter, _, save) = answers.last();
    assert_eq!(
        (filter, save),
        (vec!["p3f", "nff", "obj", "ply", "toml"], false)
    );

    answers.next(Some(&scene));
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::O);
    wait_for(&mut harness, "the picked scene", |app| {
        app.engine().scene().map(|s| &s.source) == Some(&SceneSource::File(scene.clone()))
    });
    wait_for(&mut harness, "its final image", |app| {
        is_done(app) && app.is_display_current()
    });

    let (png, exr) = (dir.join("shown.png"), dir.join("film.exr"));
    answers.next(Some(&png));
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::S);
    written(&mut harness, &png);
    assert_eq!(
        answers.last(),
        (vec!["png"], Some("scene.png".into()), true)
    );
    let shown = harness.state().shown().unwrap().clone();
    let saved = image::open(&png).unwrap().to_rgba8();
    assert_eq!((saved.width(), saved.height()), (shown.width, shown.height));
    assert_eq!(
        saved.as_raw(),
        &shown.rgba,
        "the PNG is the render on screen"
    );

    answers.next(Some(&exr));
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::E);
    written(&mut harness, &exr);
    assert_eq!(
        answers.last(),
        (vec!["exr"], Some("scene.exr".into()), true)
    );
    let film = image::open(&exr).unwrap().to_rgb32f();
    let linear = harness.state().engine().linear_image().unwrap();
    assert_eq!(film.as_raw(), linear.as_raw(), "the EXR is the linear film");

    // An edit, saved as a scene: the file holds it, the title no longer
    // says the scene is modified.
    harness
        .state_mut()
        .edit("object 1 kd 0.25".parse().unwrap())
        .unwrap();
    harness.run_steps(2);
    assert!(
        harness.state().title().ends_with(" *"),
        "{}",
        harness.state().title()
    );
    let edited = dir.join("edited.p3f");
    answers.next(Some(&edited));
    harness.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::S,
    );
    wait_for(&mut harness, "the scene saved", |app| {
        !app.title().ends_with(" *")
    });
    assert_eq!(
        answers.last(),
        (vec!["p3f"], Some("scene-edited.p3f".into()), true)
    );
    let saved = tracer::scene::parse_scene_file(&edited, &Default::default()).unwrap();
    let shown = &harness.state().engine().scene().unwrap().scene;
    assert_eq!(
        tracer::scene::write_p3f(&saved),
        tracer::scene::write_p3f(shown),
        "the file holds the edited scene"
    );
}

/// K keeps refining, 1 shows one image pixel per screen pixel and F fits
/// it again, H opens and closes the help, W swaps the sides.
#[test]
fn k_1_f_help_and_w_do_what_they_say() {
    let mut harness = small_window_sized(Harness::builder(), WINDOW);
    wait_for_scene(&mut harness);
    harness.key_press(egui::Key::K);
    harness.run_steps(2);
    assert!(settings(&harness).keep_refining);
    harness.key_press(egui::Key::K);
    harness.run_steps(2);
    assert!(!settings(&harness).keep_refining);

    harness.key_press(egui::Key::Num1);
    harness.run_steps(2);
    assert_eq!(harness.state().zoom_scale(), Some(1.0));
    harness.key_press(egui::Key::F);
    harness.run_steps(2);
    assert_eq!(harness.state().zoom_scale(), None, "fit");

    let help = "Keyboard shortcuts and mouse";
    assert!(harness.query_by_label(help).is_none());
    harness.key_press(egui::Key::H);
    harness.run_steps(2);
    assert!(harness.query_by_label(help).is_some());
    harness.key_press(egui::Key::H);
    harness.run_steps(2);
    assert!(harness.query_by_label(help).is_none());

    // W without B says what it needs; with B (soft shadows on B) it swaps.
    harness.key_press(egui::Key::W);
    harness.run_steps(2);
    assert!(
        harness
            .query_by_label_contains("turn compare mode on first")
            .is_some()
    );
    harness.key_press(egui::Key::B);
    harness.run_steps(2);
    harness.key_press(egui::Key::S);
    harness.run_steps(2);
    let soft = |app: &WorkbenchApp| {
        (
            app.controls().render.soft_shadows,
            app.side_b().unwrap().controls.render.soft_shadows,
        )
    };
    assert_eq!(soft(harness.state()), (false, true));
    harness.key_press(egui::Key::W);
    harness.run_steps(2);
    assert_eq!(soft(harness.state()), (true, false));
}

#[test]
fn a_jpeg_can_be_side_b() {
    let mut harness = small_window_sized(Harness::builder(), WINDOW);
    wait_for(&mut harness, "the final image", |app| {
        is_done(app) && app.is_display_current()
    });
    let dir = scratch("command-jpeg");
    let jpeg = dir.join("reference.jpg");
    let shown = harness.state().shown().unwrap().to_image().unwrap();
    shown.save(&jpeg).unwrap();
    harness.key_press(egui::Key::B);
    harness.run_steps(2);
    harness.state_mut().compare_with_image(&jpeg);
    wait_for(&mut harness, "A measured against the JPEG", |app| {
        app.comparison().is_some_and(|c| c.metrics().is_some())
    });
    let compare = harness.state().comparison().unwrap();
    assert_eq!(
        compare.reference().unwrap().label(),
        "B: image reference.jpg"
    );
    let metrics = compare.metrics().unwrap().as_ref().unwrap();
    // JPEG is lossy: close to A, not equal.
    assert!(metrics.mse > 0.0 && metrics.psnr > 25.0, "{metrics:?}");
}

#[test]
fn the_slow_brute_force_banner_switches_to_the_bvh() {
    let dir = scratch("command-banner");
    let mut scene = generate(GeneratorName::Balls, &GenerateOptions { level: 4, seed: 0 }).unwrap();
    scene.accel = Some(0);
    let path = write(&dir, "balls4.p3f", &tracer::scene::write_p3f(&scene));
    let mut harness = window_on(SceneSource::File(path));
    assert_eq!(
        settings(&harness).accel,
        AccelKind::None,
        "the file's choice"
    );
    // The scene list's counts widen the side panel when they arrive, which
    // moves the banner: click once they are in and drawn. Counting starts
    // now: by default it waits for the first render, this test's brute
    // force over thousands of spheres, which on a loaded machine outlasted
    // the wait (the window's clock is stopped, so the deadline never came).
    harness.state_mut().set_catalog_delay(Duration::ZERO);
    wait_for(&mut harness, "the scene list's counts", |app| {
        app.is_catalog_complete()
    });
    harness.run_steps(2);
    harness.get_by_label("Switch to BVH").click();
    harness.run_steps(2);
    assert_eq!(settings(&harness).accel, AccelKind::Bvh);
    harness.run_steps(2);
    assert!(harness.query_by_label("Switch to BVH").is_none());
}

#[test]
fn a_lesson_picked_in_the_open_dialog_opens_as_a_lesson() {
    let dir = scratch("command-open-lesson");
    let lesson = write(
        &dir,
        "picked.toml",
        r#"title = "Picked"
chapter = 7

[scene]
p3f = """
v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 resolution 20 16
l 0 5 5 1 1 1
f 1 0 0 1 0 0 0 0 1 0 1
s 0 0 0 1
"""

[[step]]
title = "Anti-aliasing"
text = "Turn it on."
check = { kind = "value", of = "aa", is = "on" }
solution = { settings = "--aa" }
"#,
    );
    let mut harness = small_window_sized(Harness::builder(), WINDOW);
    let answers = answer_dialogs(&mut harness);
    wait_for_scene(&mut harness);
    assert!(!harness.state().lessons().open);

    answers.next(Some(&lesson));
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::O);
    wait_for(&mut harness, "the lesson's scene, set up", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == "picked.p3f")
            && app.engine().settings().is_some()
    });
    let app = harness.state();
    assert!(app.lessons().open, "the Lessons window opens");
    assert_eq!(
        app.lessons().lesson().map(|l| l.title.as_str()),
        Some("Picked")
    );
    let settings = app.engine().settings().unwrap();
    assert_eq!((settings.width, settings.height), (20, 16));
}

/// The Lessons window's "Lesson folder..." asks for a folder and adds its
/// lessons to the list.
#[test]
fn lesson_folder_in_the_lessons_window_adds_a_folders_lessons() {
    let dir = scratch("command-lesson-folder");
    let text = r#"title = "From a folder"
chapter = 7

[scene]
bundled = "glass"

[[step]]
title = "Anti-aliasing"
text = "Turn it on."
check = { kind = "value", of = "aa", is = "on" }
solution = { settings = "--aa" }
"#;
    write(&dir, "from_a_folder.toml", text);
    let mut harness = small_window_sized(Harness::builder(), WINDOW);
    let answers = answer_dialogs(&mut harness);
    wait_for_scene(&mut harness);
    harness.state_mut().lessons_mut().open = true;
    harness.run_steps(2);
    answers.next(Some(&dir));
    harness.get_by_label("Lesson folder...").click();
    wait_for(&mut harness, "the folder's lesson listed", |app| {
        app.lessons().names().contains(&"from_a_folder")
    });
    let asked = answers.asked.lock().unwrap();
    assert!(
        asked.iter().any(|q| q.pick_folder),
        "a folder was asked for"
    );
}
