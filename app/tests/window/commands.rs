//! What the window's commands do, each seen in the renderer or on disk:
//! F5 reloads the file and keeps the user's settings, C puts the camera
//! back, saving writes the shown render (PNG) and the linear film (EXR), a
//! JPEG can be side B, and the slow brute-force banner switches to the BVH.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tracer::accel::AccelKind;
use tracer::generate::{GenerateOptions, GeneratorName, generate};
use workbench::gui::WorkbenchApp;
use workbench::load::SceneSource;

use crate::harness::{
    WINDOW, drag, is_done, one_window_at_a_time, small_window_sized, wait_for, wait_for_scene,
};
use crate::support::scenes::spheres_on_a_floor;
use crate::support::{scratch, write};

/// The window on `scene`, its structure built.
fn window_on(scene: SceneSource) -> Harness<'static, WorkbenchApp> {
    one_window_at_a_time();
    let mut harness = Harness::builder()
        .with_size(WINDOW)
        .build_eframe(|cc| WorkbenchApp::new(&cc.egui_ctx, None, Some(scene)));
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

#[test]
fn saving_writes_the_shown_render_and_the_linear_film() {
    let mut harness = small_window_sized(Harness::builder(), WINDOW);
    wait_for(&mut harness, "the final image", |app| {
        is_done(app) && app.is_display_current()
    });
    let dir = scratch("command-save");
    let (png, exr) = (dir.join("shown.png"), dir.join("film.exr"));
    let app = harness.state();
    app.save_png_to(&png).unwrap();
    app.save_exr_to(&exr).unwrap();
    let shown = app.shown().unwrap();
    let saved = image::open(&png).unwrap().to_rgba8();
    assert_eq!((saved.width(), saved.height()), (shown.width, shown.height));
    assert_eq!(
        saved.as_raw(),
        &shown.rgba,
        "the PNG is the render on screen"
    );
    let film = image::open(&exr).unwrap().to_rgb32f();
    let linear = app.engine().linear_image().unwrap();
    assert_eq!(film.as_raw(), linear.as_raw(), "the EXR is the linear film");
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
    // moves the banner: click once they are in and drawn.
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
