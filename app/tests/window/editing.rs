//! Editing the scene in the window as a user would: E opens the editor, a
//! click on the image selects the object it shows, edits render at once
//! (a material edit on the structure already built), undo gives back the
//! very image, a saved scene opens to the same image, unsaved edits are
//! never thrown away without asking, and an edit in the window renders
//! what `--set` renders on the command line.

use std::sync::Arc;

use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use tracer::accel::SceneIndex;
use tracer::camera::Camera;
use tracer::render::{LensOverride, RenderSettings};
use tracer::scene::edit::{Edit, Effect, MaterialField, ObjectChange};
use tracer::scene::{Lens, Primitive};
use workbench::gui::{Pending, WorkbenchApp};
use workbench::load::{Loaded, SceneSource};

use crate::harness::{WINDOW, is_done, observer_done, ready_window, wait_for};
use crate::support::scratch;

/// The big sphere in the middle of `balls_low`.
const BIG_SPHERE: usize = 2;

/// Waits for the render on screen and returns its pixels.
fn finished(harness: &mut Harness<'static, WorkbenchApp>) -> Vec<u8> {
    wait_for(harness, "the render on screen", |app| {
        is_done(app) && app.is_display_current()
    });
    harness.state().shown().unwrap().rgba.clone()
}

fn glass(index: usize) -> Edit {
    Edit::Object {
        index,
        change: ObjectChange::Material(MaterialField::Transmittance(0.9)),
    }
}

fn big_sphere_centre(app: &WorkbenchApp) -> glam::Vec3 {
    match &app.engine().scene().unwrap().scene.objects[BIG_SPHERE].primitive {
        Primitive::Sphere { centre, .. } => *centre,
        other => panic!("not the sphere: {other:?}"),
    }
}

/// The window with the editor open on a finished render.
fn editing() -> (Harness<'static, WorkbenchApp>, Vec<u8>) {
    let mut harness = ready_window(WINDOW);
    let before = finished(&mut harness);
    harness.key_press(egui::Key::E);
    harness.run_steps(2);
    assert!(harness.state().editor().open, "E opens the editor");
    (harness, before)
}

/// Clicks the middle of the render, where the big sphere is.
fn click_the_middle(harness: &mut Harness<'static, WorkbenchApp>) {
    let image = harness
        .get_by_role_and_label(egui::accesskit::Role::Image, "Render")
        .rect();
    harness.hover_at(image.center());
    harness.step();
    harness.drag_at(image.center());
    harness.step();
    harness.drop_at(image.center());
    harness.run_steps(2);
}

#[test]
fn a_click_selects_the_object_the_image_shows() {
    let (mut harness, _) = editing();
    click_the_middle(&mut harness);
    assert_eq!(harness.state().editor().selected, Some(BIG_SPHERE));
    // Its material is shared by the ten spheres: the editor asks first.
    assert!(harness.query_by_label("All 10").is_some());
    harness.get_by_label("This object alone").click();
    harness.run_steps(2);
    assert!(
        harness.query_all_by_label("Kd").next().is_some(),
        "its material's sliders"
    );
    harness.key_press(egui::Key::Escape);
    harness.run_steps(2);
    assert_eq!(harness.state().editor().selected, None, "Esc clears it");
    assert!(harness.query_all_by_label("Kd").next().is_none());
}

#[test]
fn a_material_edit_keeps_the_structure_and_undo_gives_back_the_image() {
    let (mut harness, before) = editing();
    let index = harness.state().engine().index().unwrap();
    assert_eq!(
        harness.state_mut().edit(glass(BIG_SPHERE)),
        Ok(Effect::Shading)
    );
    let edited = finished(&mut harness);
    assert_ne!(edited, before, "glass looks different");
    let app = harness.state();
    assert!(
        Arc::ptr_eq(&index, &app.engine().index().unwrap()),
        "a material edit renders on the structure already built"
    );
    assert!(app.title().ends_with(" *"), "the title says: unsaved");
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.step();
    assert!(
        finished(&mut harness) == before,
        "undo: the very image again"
    );
    assert!(!harness.state().title().ends_with(" *"));
    // Ctrl+Shift+Z redoes (egui would also match it as Ctrl+Z).
    harness.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    harness.step();
    assert!(finished(&mut harness) == edited, "redo: the edit is back");
}

#[test]
fn a_light_added_from_the_editor_lights_the_scene_and_undo_removes_it() {
    let (mut harness, before) = editing();
    harness.get_by_label("Lights (3)").click();
    harness.run_steps(2);
    harness.get_by_label("Add a light at the camera").click();
    harness.run_steps(2);
    let lights = |app: &WorkbenchApp| app.engine().scene().unwrap().scene.lights.len();
    assert_eq!(lights(harness.state()), 4);
    assert_ne!(finished(&mut harness), before);
    harness.get_by_label("Undo edit").click();
    harness.run_steps(2);
    assert_eq!(lights(harness.state()), 3);
    assert!(finished(&mut harness) == before);
}

#[test]
fn a_drag_in_move_mode_moves_the_selected_object_not_the_camera() {
    let (mut harness, before) = editing();
    click_the_middle(&mut harness);
    harness
        .get_by_label("Drag moves the selected object")
        .click();
    harness.run_steps(2);
    assert!(harness.state().editor().move_mode);
    let start = big_sphere_centre(harness.state());
    crate::harness::drag(&mut harness, "Render");
    let moved = big_sphere_centre(harness.state());
    assert!((moved - start).length() > 1e-3, "{start} -> {moved}");
    let app = harness.state();
    assert_eq!(app.engine().settings().unwrap().camera, None, "no orbit");
    // In the image plane: as far from the camera as before.
    let eye = app.engine().scene().unwrap().scene.view.from;
    let at = app.engine().scene().unwrap().scene.view.at;
    let forward = (at - eye).normalize();
    assert!(((moved - eye).dot(forward) - (start - eye).dot(forward)).abs() < 1e-3);
    assert_ne!(finished(&mut harness), before);
}

#[test]
fn an_edit_in_the_window_renders_what_set_renders_headless() {
    let (mut harness, _) = editing();
    harness.state_mut().edit(glass(BIG_SPHERE)).unwrap();
    let shown = finished(&mut harness);
    let app = harness.state();
    let settings = app.engine().settings().cloned().unwrap();
    let source = SceneSource::Bundled("balls_low".into());
    let world = Loaded::read(source, &[glass(BIG_SPHERE).to_string()], &mut |_| {})
        .unwrap()
        .world;
    let index = Arc::new(SceneIndex::build(
        &world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    let (film, _) = tracer::render::render(world, index, settings, None).unwrap();
    assert!(
        shown == film.to_rgba8(app.controls().encoding()),
        "the window's edit and `--set '{}'` render alike",
        glass(BIG_SPHERE)
    );
}

/// A lens edit is the lens the side renders with, depth of field on, as
/// `--set 'camera aperture 8'` gives on the command line, where the
/// settings come from the edited scene.
#[test]
fn a_lens_edit_in_the_window_renders_what_set_renders_headless() {
    let (mut harness, before) = editing();
    let scene = harness.state().engine().scene().unwrap().scene.clone();
    let lens = Edit::parse_in("camera aperture 8", &scene).unwrap();
    harness.state_mut().edit(lens).unwrap();
    let shown = finished(&mut harness);
    assert!(shown != before, "the lens changes the image");
    let app = harness.state();
    let window = app.engine().settings().cloned().unwrap();
    let source = SceneSource::Bundled("balls_low".into());
    let loaded = Loaded::read(source, &["camera aperture 8".into()], &mut |_| {}).unwrap();
    let settings = RenderSettings {
        width: window.width,
        height: window.height,
        ..RenderSettings::from_scene(&loaded.scene)
    };
    let index = Arc::new(SceneIndex::build(
        &loaded.world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    let (film, _) = tracer::render::render(loaded.world, index, settings, None).unwrap();
    assert!(
        shown == film.to_rgba8(app.controls().encoding()),
        "the window's lens edit and `--set 'camera aperture 8'` render alike"
    );
}

/// Whether side A's finished render saw through the lens `(aperture,
/// focal)` of its scene's view (`None`: a pinhole).
fn renders_through(harness: &mut Harness<'static, WorkbenchApp>, lens: Option<(f32, f32)>) -> bool {
    harness.run_steps(2);
    finished(harness);
    let app = harness.state();
    let view = &app.engine().scene().unwrap().world.view;
    let settings = app.engine().settings().unwrap();
    let (aperture, focal) = lens.unwrap_or((0.0, 1.0));
    let expected = Camera::new(view, settings.width, settings.height, aperture, focal);
    settings.render_camera(view) == expected
}

/// Whose lens a side renders with: a scene's own, opened or edited, with
/// depth of field on when it is open; the user's (the panel's sliders)
/// until another scene opens or the scene's camera is edited, any field of
/// it; an undone camera edit gives the scene's lens back.
#[test]
fn the_scene_owns_the_lens_until_the_user_overrides_it() {
    let mut harness = ready_window(WINDOW);
    assert!(renders_through(&mut harness, None), "balls_low: a pinhole");
    let user = |harness: &mut Harness<'static, WorkbenchApp>| {
        let render = &mut harness.state_mut().controls_mut().render;
        render.depth_of_field = true;
        render.lens_override = LensOverride::all(Lens {
            aperture: 20.0,
            focal: 2.0,
        });
    };
    user(&mut harness);
    assert!(
        renders_through(&mut harness, Some((20.0, 2.0))),
        "the user's lens"
    );

    harness.state_mut().open(SceneSource::Bundled("dof".into()));
    wait_for(&mut harness, "the dof scene", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == "dof")
    });
    assert!(harness.state().controls().render.depth_of_field);
    assert!(
        renders_through(&mut harness, Some((24.0, 0.957))),
        "another scene opens with its own lens"
    );

    user(&mut harness);
    assert!(renders_through(&mut harness, Some((20.0, 2.0))));
    let scene = harness.state().engine().scene().unwrap().scene.clone();
    let angle = Edit::parse_in("camera angle 30", &scene).unwrap();
    harness.state_mut().edit(angle).unwrap();
    assert!(
        renders_through(&mut harness, Some((24.0, 0.957))),
        "a camera edit renders through the scene's lens again"
    );

    harness.state_mut().controls_mut().render.depth_of_field = false;
    assert!(renders_through(&mut harness, None), "depth of field off");
    let closed = Edit::parse_in("camera aperture 0", &scene).unwrap();
    harness.state_mut().edit(closed).unwrap();
    assert!(renders_through(&mut harness, None));
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    assert!(
        renders_through(&mut harness, Some((24.0, 0.957))),
        "undo: the scene's open lens, depth of field on again"
    );
    assert!(harness.state().controls().render.depth_of_field);
}

#[test]
fn a_saved_scene_opens_to_the_same_image() {
    let (mut harness, _) = editing();
    harness.state_mut().edit(glass(BIG_SPHERE)).unwrap();
    let edited = finished(&mut harness);
    let dir = scratch("editing-save");
    let path = dir.join("balls_low-edited.p3f");
    harness.state_mut().save_scene_to(&path).unwrap();
    harness.step();
    assert!(!harness.state().title().ends_with(" *"), "saved");
    assert!(harness.state().title().contains("balls_low-edited.p3f"));
    harness.key_press(egui::Key::F5);
    wait_for(&mut harness, "the saved file read", |app| {
        !app.engine().is_loading() && app.engine().index().is_some()
    });
    assert!(
        harness.state().editor().pending.is_none(),
        "nothing unsaved to ask about"
    );
    assert!(finished(&mut harness) == edited, "the file holds the edit");
}

#[test]
fn opening_another_scene_asks_before_unsaved_edits_are_lost() {
    let (mut harness, _) = editing();
    harness.state_mut().edit(glass(BIG_SPHERE)).unwrap();
    let other = SceneSource::Bundled("glass".into());
    harness.state_mut().open(other.clone());
    harness.run_steps(2);
    assert_eq!(
        harness.state().editor().pending,
        Some(Pending::Open(other.clone()))
    );
    assert!(!harness.state().engine().is_loading(), "nothing opened yet");
    harness.get_by_label("Cancel").click();
    harness.run_steps(2);
    assert!(harness.state().editor().pending.is_none());
    assert!(harness.state().title().ends_with(" *"), "the edit is kept");
    harness.state_mut().open(other.clone());
    harness.run_steps(2);
    harness.key_press(egui::Key::Escape);
    harness.run_steps(2);
    assert!(harness.state().editor().pending.is_none(), "Esc cancels");
    assert!(!harness.state().engine().is_loading());

    harness.state_mut().open(other);
    harness.run_steps(2);
    harness.get_by_label("Discard edits").click();
    wait_for(&mut harness, "the other scene", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source.label() == "glass")
    });
    assert!(!harness.state().title().ends_with(" *"));
}

#[test]
fn in_compare_mode_b_edits_its_own_scene_and_its_label_says_so() {
    let mut harness = ready_window(WINDOW);
    let before = finished(&mut harness);
    harness.key_press(egui::Key::B);
    harness.run_steps(2);
    harness.state_mut().edit(glass(BIG_SPHERE)).unwrap();
    wait_for(&mut harness, "both sides", |app| {
        is_done(app) && app.is_display_current()
    });
    let app = harness.state();
    let material = |scene: &tracer::scene::Scene| {
        scene.materials[scene.objects[BIG_SPHERE].material as usize].transmittance
    };
    let b = &app.side_b().unwrap().engine.scene().unwrap().scene;
    assert_eq!(material(b), 0.9, "B is edited");
    assert_eq!(material(&app.engine().scene().unwrap().scene), 0.0);
    assert!(app.shown().unwrap().rgba == before, "A's image stays");
    let labels: Vec<String> = harness
        .get_all_by_role(egui::accesskit::Role::Label)
        .filter_map(|n| n.accesskit_node().label().or(n.accesskit_node().value()))
        .collect();
    assert!(
        labels
            .iter()
            .any(|l| l == &format!("B: sphere #{BIG_SPHERE} t 0.9")),
        "B's label names its edit: {labels:?}"
    );
    assert!(labels.iter().any(|l| l == "A: same settings"));
}

#[test]
fn dragging_a_material_slider_changes_that_field_alone() {
    let (mut harness, _) = editing();
    click_the_middle(&mut harness);
    harness.get_by_label("This object alone").click();
    harness.run_steps(2);
    let slider = harness
        .get_by_role_and_label(egui::accesskit::Role::Slider, "T (transmittance)")
        .rect();
    // From the left end (T = 0) most of the way right, frame by frame: the
    // first change gives the object a material of its own and shows ior.
    let mut at = slider.left_center() + egui::vec2(2.0, 0.0);
    harness.drag_at(at);
    harness.step();
    for _ in 0..6 {
        at.x += slider.width() / 8.0;
        harness.hover_at(at);
        harness.step();
    }
    harness.drop_at(at);
    harness.run_steps(2);
    let scene = &harness.state().engine().scene().unwrap().scene;
    let material = scene.materials[scene.objects[BIG_SPHERE].material as usize];
    assert!(material.transmittance > 0.5, "{material:?}");
    assert_eq!(material.ior, 1.0, "the drag stays on T: {material:?}");
}

/// Where the observer view draws `point`, on screen.
fn in_observer(harness: &Harness<'static, WorkbenchApp>, point: glam::Vec3) -> egui::Pos2 {
    let app = harness.state();
    let world = &app.engine().scene().unwrap().world;
    let camera = app.observer().camera(world).expect("the observer's camera");
    let rect = harness
        .get_by_role_and_label(egui::accesskit::Role::Image, "Observer")
        .rect();
    let p = camera
        .project(point.into())
        .expect("in front of the observer");
    let size = egui::vec2(camera.width() as f32, camera.height() as f32);
    rect.min + egui::vec2(p.x, p.y) / size * rect.size()
}

fn light_position(app: &WorkbenchApp, index: usize) -> glam::Vec3 {
    app.engine().scene().unwrap().scene.lights[index].position()
}

#[test]
fn in_the_observer_a_click_selects_and_a_drag_on_a_light_moves_that_light() {
    // Wide enough that the editor's window, at the right, leaves the
    // middle of the observer's image free.
    let mut harness = ready_window([1800.0, 900.0]);
    finished(&mut harness);
    harness.key_press(egui::Key::E);
    harness.key_press(egui::Key::O);
    wait_for(&mut harness, "the observer's render", observer_done);
    // A click where the observer shows the big sphere's centre selects it.
    let sphere = in_observer(&harness, big_sphere_centre(harness.state()));
    harness.hover_at(sphere);
    harness.step();
    harness.drag_at(sphere);
    harness.step();
    harness.drop_at(sphere);
    harness.run_steps(2);
    assert_eq!(harness.state().editor().selected, Some(BIG_SPHERE));

    // A drag from light 0's marker moves light 0, not the observer.
    let pose = harness.state().observer().pose();
    let before = light_position(harness.state(), 0);
    let mut at = in_observer(&harness, before);
    harness.hover_at(at);
    harness.step();
    harness.drag_at(at);
    harness.step();
    for _ in 0..4 {
        at += egui::vec2(10.0, 6.0);
        harness.hover_at(at);
        harness.step();
    }
    harness.drop_at(at);
    harness.run_steps(2);
    let app = harness.state();
    let after = light_position(app, 0);
    assert!((after - before).length() > 1e-3, "{before} -> {after}");
    assert_eq!(app.observer().pose(), pose, "the observer stayed");
    assert_eq!(app.editor().light, Some(0));
    // It lands where the pointer let go, and the whole drag is one step.
    let landed = in_observer(&harness, after);
    assert!(landed.distance(at) < 2.0, "{landed:?} vs {at:?}");
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    harness.run_steps(2);
    assert_eq!(light_position(harness.state(), 0), before);

    // In move mode a drag elsewhere moves the selected sphere.
    harness.state_mut().editor_mut().move_mode = true;
    let before = big_sphere_centre(harness.state());
    let mut at = in_observer(&harness, before);
    harness.drag_at(at);
    harness.step();
    for _ in 0..3 {
        at += egui::vec2(-8.0, 5.0);
        harness.hover_at(at);
        harness.step();
    }
    harness.drop_at(at);
    harness.run_steps(2);
    let after = big_sphere_centre(harness.state());
    assert!((after - before).length() > 1e-3, "{before} -> {after}");
    assert!(in_observer(&harness, after).distance(at) < 2.0);
    assert_eq!(
        harness.state().observer().pose(),
        pose,
        "the observer stayed"
    );
}
