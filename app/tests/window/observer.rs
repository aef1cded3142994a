//! The observer view driven as a user would: O shows the scene from
//! outside, drags move the observer (and never the render), a pinned
//! pixel's rays fly through it generation by generation, compare mode
//! shows both sides' trees, its filter hides misses and grows the
//! trees one bounce at a time, and the eye ray's walk is drawn as far as
//! the ray tree's step.

use std::time::Duration;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tracer::accel::Visit;
use workbench::gui::WorkbenchApp;

use crate::harness::{drag, is_done, observer_done, ready_window, wait_for};

/// Tall enough for the side panel's observer section.
const TALL: [f32; 2] = [1280.0, 1500.0];

/// The window with the observer on and its first render on screen.
fn observing() -> Harness<'static, WorkbenchApp> {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the render", is_done);
    harness.key_press(egui::Key::O);
    wait_for(&mut harness, "the observer's render", observer_done);
    harness
}

#[test]
fn o_shows_the_scene_from_outside_and_moving_it_never_restarts_the_render() {
    let mut harness = observing();
    let app = harness.state();
    assert!(app.observer().on);
    let framed = app.observer().pose().expect("framed on the scene");
    let scene_eye = app.engine().scene().unwrap().scene.view.from;
    assert!(
        (framed.from - scene_eye).length() > 1e-3,
        "outside the camera"
    );
    assert!(
        app.observer().segments_drawn > 0,
        "the camera and lights drawn"
    );
    let jobs = app.engine().version().0;
    drag(&mut harness, "Observer");
    let moved = harness.state().observer().pose().unwrap();
    assert_ne!(moved, framed, "the drag orbits the observer");
    wait_for(&mut harness, "the observer's render from there", |app| {
        observer_done(app) && app.observer().engine().settings().unwrap().camera == Some(moved)
    });
    let app = harness.state();
    assert_eq!(app.engine().version().0, jobs, "the main render went on");
    assert_eq!(app.engine().settings().unwrap().camera, None);
    // The main image's own drag still moves the scene camera.
    drag(&mut harness, "Render");
    assert!(
        harness
            .state()
            .engine()
            .settings()
            .unwrap()
            .camera
            .is_some()
    );
    assert_eq!(harness.state().observer().pose(), Some(moved));
}

#[test]
fn a_pinned_pixels_rays_grow_generation_by_generation() {
    let mut harness = observing();
    harness.state_mut().inspect((32, 40));
    wait_for(&mut harness, "the pixel's tree in the observer", |app| {
        !app.observer().trees().is_empty()
    });
    let tree = &harness.state().observer().trees()[0].1;
    let rays = tree.nodes.len();
    assert!(rays >= 2, "an eye ray and its shadow rays");
    let phases = harness.state().observer().phases();
    harness.run_steps(2);
    let all = harness.state().observer().segments_drawn;
    harness.get_by_label("Step").click();
    harness.run_steps(2);
    assert_eq!(harness.state().observer().animation.phase(), Some(1));
    let first = harness.state().observer().segments_drawn;
    assert!(
        first < all,
        "the first step draws fewer rays ({first} of {all})"
    );
    for _ in 1..phases {
        harness.get_by_label("Step").click();
        harness.run_steps(2);
    }
    assert_eq!(harness.state().observer().animation.phase(), None);
    assert_eq!(
        harness.state().observer().segments_drawn,
        all,
        "at rest: all"
    );
    harness.get_by_label("Play").click();
    harness.run_steps(2);
    let animation = &harness.state().observer().animation;
    assert!(animation.is_playing());
    assert_eq!(
        animation.phase(),
        Some(0),
        "the window's clock stands still"
    );
    // One phase a second: past the first, then past the last, at rest.
    harness.state().clock().advance(Duration::from_millis(1500));
    harness.step();
    assert_eq!(harness.state().observer().animation.phase(), Some(1));
    harness
        .state()
        .clock()
        .advance(Duration::from_secs(u64::from(phases)));
    harness.step();
    let animation = &harness.state().observer().animation;
    assert!(!animation.is_playing() && animation.phase().is_none());
    // A row of pixels: their trees too.
    harness.state_mut().observer_pattern_row(40);
    wait_for(&mut harness, "the row's trees", |app| {
        app.observer().trees().len() > 8
    });
}

#[test]
fn compare_mode_draws_both_sides_trees() {
    let mut harness = observing();
    harness.key_press(egui::Key::B);
    harness.run_steps(2);
    harness.key_press(egui::Key::S);
    harness.state_mut().inspect((32, 40));
    wait_for(&mut harness, "A's and B's trees", |app| {
        let sides: Vec<u8> = app.observer().trees().iter().map(|(s, _)| *s).collect();
        sides.contains(&0) && sides.contains(&1)
    });
    let trees = harness.state().observer().trees();
    let shadows = |side: u8| {
        trees
            .iter()
            .filter(|(s, _)| *s == side)
            .map(|(_, t)| {
                t.nodes
                    .iter()
                    .filter(|n| n.kind == tracer::render::RayKind::Shadow)
                    .count()
            })
            .sum::<usize>()
    };
    assert!(
        shadows(1) >= shadows(0),
        "B's soft shadows sample the light"
    );
}

/// The observer's own view is traced with a BVH whatever structure side A
/// renders with (the scene's `accel 0` over a large mesh took minutes):
/// here A uses the grid, and the observer builds and keeps its own BVH.
#[test]
fn the_observer_traces_its_view_with_a_bvh_whatever_a_uses() {
    let mut harness = ready_window(TALL);
    harness.state_mut().controls_mut().render.accel = tracer::accel::AccelKind::Grid;
    wait_for(&mut harness, "A's render on the grid", |app| {
        is_done(app) && app.engine().settings().unwrap().accel == tracer::accel::AccelKind::Grid
    });
    harness.key_press(egui::Key::O);
    wait_for(&mut harness, "the observer's render", observer_done);
    let observer = harness.state().observer().engine();
    assert_eq!(
        observer.settings().unwrap().accel,
        tracer::accel::AccelKind::Bvh
    );
    assert_eq!(
        observer.index().unwrap().kind(),
        tracer::accel::AccelKind::Bvh
    );
}

#[test]
fn the_filter_hides_misses_and_grows_the_trees_one_bounce_at_a_time() {
    let mut harness = observing();
    harness.state_mut().observer_pattern_row(40);
    wait_for(&mut harness, "the row's trees", |app| {
        app.observer().trees().len() > 8
    });
    harness.run_steps(2);
    let nodes = |app: &WorkbenchApp| -> Vec<tracer::render::RayNode> {
        let trees = app.observer().trees();
        trees.iter().flat_map(|(_, t)| t.nodes.clone()).collect()
    };
    let all_nodes = nodes(harness.state());
    let misses = all_nodes
        .iter()
        .filter(|n| matches!(n.outcome, tracer::render::Outcome::Background))
        .count();
    let deeper = all_nodes.iter().filter(|n| n.depth > 0).count();
    assert!(
        misses > 0 && deeper > 0,
        "{misses} misses, {deeper} bounces"
    );
    let all = harness.state().observer().segments_drawn;

    harness.get_by_label("Hide misses").click();
    harness.run_steps(2);
    assert!(harness.state().observer().filter.hide_misses);
    let hidden = harness.state().observer().segments_drawn;
    assert!(hidden < all, "misses hidden: {hidden} of {all}");
    harness.get_by_label("Hide misses").click();
    harness.run_steps(2);
    assert_eq!(harness.state().observer().segments_drawn, all);

    harness.get_by_label("Bounces up to").click();
    harness.run_steps(2);
    assert_eq!(harness.state().observer().filter.max_depth, Some(0));
    let first = harness.state().observer().segments_drawn;
    assert!(first < all, "the eye rays' generation: {first} of {all}");
    harness.get_by_label("Grow").click();
    harness.run_steps(2);
    assert_eq!(harness.state().observer().filter.max_depth, Some(1));
    let grown = harness.state().observer().segments_drawn;
    assert!(grown > first, "one bounce more: {grown} after {first}");
}

#[test]
fn stepping_the_eye_rays_walk_draws_it_in_the_observer_up_to_the_step() {
    let mut harness = observing();
    harness
        .get_by_role_and_label(Role::CheckBox, "Structure overlay")
        .click();
    harness.key_press(egui::Key::G);
    harness.state_mut().inspect((32, 40));
    wait_for(&mut harness, "the grid walk in the observer", |app| {
        is_done(app)
            && observer_done(app)
            && app.observer().trees().first().is_some_and(|(_, tree)| {
                matches!(tree.eye_visits.first(), Some(Visit::Cell { .. }))
            })
            && app.inspector().eye_visits().len() >= 2
    });
    harness.run_steps(2);
    let all = harness.state().observer().segments_drawn;
    harness
        .get_by_role_and_label(Role::Button, "Next visit")
        .click();
    harness.run_steps(2);
    let first = harness.state().observer().segments_drawn;
    assert!(
        first < all,
        "the first cell alone draws fewer boxes ({first} of {all})"
    );
    harness.get_by_role_and_label(Role::Button, "All").click();
    harness.run_steps(2);
    assert_eq!(harness.state().observer().segments_drawn, all);
}
