//! The window's views, driven as a user would with `egui_kittest`: the view
//! selector and its key, the scale shared by both sides of a comparison.

use egui::accesskit::Role;
use egui_kittest::kittest::Queryable;
use tracer::accel::{Tally, Visit};
use tracer::render::{TILE_SIZE, Tile, View};

use crate::harness::{drag_holding, is_done, ready_window, wait_for};

/// The window on balls_low, tall enough for the whole side panel.
/// Tall enough for the view section's legend and numbers.
const TALL: [f32; 2] = [1280.0, 1400.0];

#[test]
fn the_view_selector_makes_the_render_measure_the_chosen_view() {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the shaded render", is_done);
    // The plain render measures nothing.
    assert_eq!(
        harness.state().engine().view_value(View::Tests, 10, 10),
        None
    );

    harness.get_by_role_and_label(Role::Button, "tests").click();
    harness.run_steps(3);
    assert_eq!(harness.state().views().view, View::Tests);
    wait_for(&mut harness, "the render with views", |app| {
        is_done(app) && app.engine().view_value(View::Tests, 10, 10).is_some()
    });
    wait_for(&mut harness, "the summary", |app| {
        app.views().summary(0).is_some()
    });
    // The panel draws before the frame's new numbers arrive: one more frame.
    harness.run_steps(2);
    let summary = *harness.state().views().summary(0).unwrap();
    assert!(
        summary.mean > 0.0 && summary.max >= summary.p99,
        "{summary:?}"
    );
    // The panel shows the numbers and the scale's choices.
    harness.get_by_label_contains("mean");
    harness.get_by_role_and_label(Role::Button, "p99").click();
    harness.run_steps(3);
    assert_eq!(
        harness.state().views().scale,
        tracer::render::HeatScale::P99
    );

    // V cycles through every view and back to the shaded image.
    for expected in View::ALL.iter().skip(2).chain(&View::ALL[..1]) {
        harness.key_press(egui::Key::V);
        harness.run_steps(2);
        assert_eq!(harness.state().views().view, *expected);
    }
}

#[test]
fn both_sides_of_a_comparison_read_on_one_scale() {
    let mut harness = ready_window(TALL);
    harness.key_press(egui::Key::B);
    harness.run_steps(3);
    harness.key_press(egui::Key::G);
    harness.get_by_role_and_label(Role::Button, "tests").click();
    wait_for(&mut harness, "both sides' views", |app| {
        is_done(app) && app.views().summary(0).is_some() && app.views().summary(1).is_some()
    });
    harness.run_steps(2);
    let app = harness.state();
    let (a, b) = (
        app.views().summary(0).unwrap(),
        app.views().summary(1).unwrap(),
    );
    // One scale: the larger maximum of the two sides.
    let top = app.views().heat().unwrap().top;
    assert_eq!(top, a.max.max(b.max));
    harness.get_by_label_contains("A: mean");
    harness.get_by_label_contains("B: mean");
}

fn shadow_rays(tree: &tracer::render::RayTree) -> usize {
    tree.nodes
        .iter()
        .filter(|n| n.kind == tracer::render::RayKind::Shadow)
        .count()
}

#[test]
fn a_clicked_pixel_shows_its_ray_tree_and_follows_the_settings() {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the render", is_done);
    // A click on the image pins the pixel under it (the centre here).
    harness.get_by_role_and_label(Role::Image, "Render").click();
    wait_for(&mut harness, "the tree", |app| {
        matches!(app.inspector().tree(0), Some(Ok(_)))
    });
    harness.run_steps(2);
    let pinned = harness.state().inspector().pinned.expect("a pinned pixel");
    let settings = harness.state().engine().settings().unwrap().clone();
    assert!(pinned.0 < settings.width && pinned.1 < settings.height);
    harness.get_by_label_contains("eye (depth 0)");
    harness.get_by_label_contains("contributions add up to");
    // The paths are drawn over the image: at least the eye ray.
    assert!(harness.state().inspector().paths_drawn >= 1);
    let Some(Ok(tree)) = harness.state().inspector().tree(0) else {
        unreachable!()
    };
    let colour = tree.colour;
    assert!((tree.contributions() - colour).abs().max_element() < 1e-4);

    // Another pixel, and soft shadows: the tree is recorded again.
    harness.state_mut().inspect((20, 30));
    harness.key_press(egui::Key::S);
    wait_for(&mut harness, "the new tree", |app| {
        let soft = app.engine().settings().is_some_and(|s| s.soft_shadows);
        soft && matches!(app.inspector().tree(0), Some(Ok(t)) if (t.x, t.y) == (20, 30) && shadow_rays(t) > 0)
    });
    let Some(Ok(tree)) = harness.state().inspector().tree(0) else {
        unreachable!()
    };
    assert!((tree.contributions() - tree.colour).abs().max_element() < 1e-4);
    assert_ne!(tree.colour, colour, "another pixel, other settings");

    // Compare mode inspects the same pixel on both sides.
    harness.key_press(egui::Key::B);
    wait_for(
        &mut harness,
        "B's tree",
        |app| matches!(app.inspector().tree(1), Some(Ok(t)) if (t.x, t.y) == (20, 30)),
    );
    harness.run_steps(2);
    let eyes = harness.get_all_by_label_contains("eye (depth 0)").count();
    assert_eq!(eyes, 2, "A's tree and B's");
}

/// While the camera moves the engine renders a quarter-size preview; the
/// tree of a pixel pinned beyond the preview's size is still recorded, at
/// full resolution, and follows the camera.
#[test]
fn the_ray_tree_follows_the_camera_through_the_preview() {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the render", is_done);
    let full = harness.state().engine().settings().unwrap().clone();
    let corner = (full.width - 2, full.height - 2);
    harness.state_mut().inspect(corner);
    wait_for(
        &mut harness,
        "the corner's tree",
        |app| matches!(app.inspector().tree(0), Some(Ok(t)) if (t.x, t.y) == corner),
    );
    let Some(Ok(before)) = harness.state().inspector().tree(0) else {
        unreachable!()
    };
    let eye_before = before.nodes[0].dir;

    let at = drag_holding(&mut harness, "Render");
    let preview = harness.state().engine().settings().unwrap().width;
    assert!(
        preview < full.width && corner.0 >= preview,
        "a preview renders while dragging"
    );
    let Some(Ok(moving)) = harness.state().inspector().tree(0) else {
        panic!(
            "the tree during the preview: {:?}",
            harness.state().inspector().tree(0)
        )
    };
    assert_eq!((moving.x, moving.y), corner);
    assert_ne!(
        moving.nodes[0].dir, eye_before,
        "the eye ray turned with the camera"
    );
    harness.drop_at(at);
}

#[test]
fn the_structure_overlay_toggle_draws_the_bvh_and_the_grid() {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the render", is_done);
    assert_eq!(harness.state().overlay().segments(), 0);
    harness
        .get_by_role_and_label(Role::CheckBox, "Structure overlay")
        .click();
    wait_for(&mut harness, "the root box", |app| {
        app.overlay().segments() == 12
    });
    harness
        .get_by_role_and_label(Role::CheckBox, "leaves")
        .click();
    wait_for(&mut harness, "the leaves", |app| {
        app.overlay().segments() > 12
    });
    // The grid: its box and lattice, once its structure is built.
    harness.key_press(egui::Key::G);
    wait_for(&mut harness, "the grid's lattice", |app| {
        is_done(app) && app.overlay().segments() > 24
    });
    harness
        .get_by_role_and_label(Role::CheckBox, "Structure overlay")
        .click();
    harness.run_steps(2);
    assert_eq!(harness.state().overlay().segments(), 0);
}

#[test]
fn an_inspected_pixel_draws_the_cells_its_eye_ray_walked() {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the render", is_done);
    let settings = harness.state().engine().settings().unwrap().clone();
    // The centre of balls_low: the eye ray meets the balls.
    harness
        .state_mut()
        .inspect((settings.width / 2, settings.height / 2));
    harness
        .get_by_role_and_label(Role::CheckBox, "Structure overlay")
        .click();
    // The BVH: the eye ray's descent, the root's box first.
    wait_for(&mut harness, "the BVH descent", |app| {
        app.overlay().visits_drawn > 0
    });
    let bvh = harness.state().inspector().eye_visits().to_vec();
    assert!(matches!(bvh[0], Visit::Node { depth: 0, .. }), "{bvh:?}");
    harness.get_by_label_contains("BVH nodes and tested");
    // The grid: its walk, once the grid is built and the tree recorded.
    harness.key_press(egui::Key::G);
    wait_for(&mut harness, "the grid walk", |app| {
        is_done(app)
            && matches!(
                app.inspector().eye_visits().first(),
                Some(Visit::Cell { .. })
            )
            && app.overlay().visits_drawn == app.inspector().eye_visits().len()
    });
    harness.get_by_label_contains("eye ray walked");
    // Off with the overlay.
    harness
        .get_by_role_and_label(Role::CheckBox, "Structure overlay")
        .click();
    harness.run_steps(2);
    assert_eq!(harness.state().overlay().visits_drawn, 0);
}

#[test]
fn a_cost_view_in_compare_mode_compares_values_not_colours() {
    let mut harness = ready_window(TALL);
    harness.key_press(egui::Key::B);
    harness.run_steps(3);
    // B traces the grid, A the BVH.
    harness.key_press(egui::Key::G);
    harness.get_by_role_and_label(Role::Button, "tests").click();
    harness
        .get_by_role_and_label(Role::Button, "Difference")
        .click();
    wait_for(&mut harness, "the values' difference", |app| {
        // The views' summaries are refitted at most every REFIT_INTERVAL:
        // wait for the fit over both finished images, not an earlier pass
        // (a first pass already has a count in every pixel).
        is_done(app)
            && app.comparison().is_some_and(|c| {
                c.difference().is_some()
                    && c.value_difference().is_some()
                    && app
                        .views()
                        .is_fitted_to(app.engine(), app.side_b().map(|b| &b.engine))
            })
    });
    // The numbers as they were when the condition held: later frames may
    // refit the views' summaries.
    let app = harness.state();
    let (view, d) = app.comparison().unwrap().value_difference().unwrap();
    let d = d.clone();
    let (a, b) = (
        *app.views().summary(0).unwrap(),
        *app.views().summary(1).unwrap(),
    );
    harness.run_steps(2);
    assert_eq!(view, View::Tests);
    // Every pixel has a count: the means are the sides' own.
    assert_eq!(d.stats.pixels, a.pixels);
    assert!(
        (d.stats.mean_a - a.mean).abs() <= 1e-3 * a.mean,
        "{d:?} {a:?}"
    );
    assert!(
        (d.stats.mean_b - b.mean).abs() <= 1e-3 * b.mean,
        "{d:?} {b:?}"
    );
    assert_ne!(
        d.stats.mean_a, d.stats.mean_b,
        "the BVH and the grid test differently"
    );
    assert!(d.values.iter().flatten().any(|&v| v != 0.0));
    // The numbers are the values', not MSE, PSNR and FLIP of heat-map colours.
    harness.get_by_label_contains("Mean |A − B|");
    harness.get_by_label_contains("Ratio A/B");
    harness.get_by_label_contains("red where A is higher");
    assert!(harness.query_by_label("MSE").is_none());
    assert!(harness.query_by_label("FLIP").is_none());
}

/// Adaptive sampling from the side panel: the samples view shows flat
/// pixels at the minimum and edges refined up to the maximum, and the
/// statistics panel says how many pixels are done.
#[test]
fn the_samples_view_shows_where_adaptive_sampling_spent_them() {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the first render", is_done);
    // balls_low asks for 2 x 2 anti-aliasing: adaptive spends its samples.
    harness.get_by_label("adaptive").click();
    wait_for(&mut harness, "the adaptive render", |app| {
        app.engine()
            .settings()
            .is_some_and(|s| s.adaptive().is_some())
    });
    let adaptive = *harness
        .state()
        .engine()
        .settings()
        .and_then(|s| s.adaptive())
        .expect("adaptive sampling is on");
    harness
        .get_by_role_and_label(Role::Button, "samples")
        .click();
    wait_for(&mut harness, "the adaptive render with views", |app| {
        is_done(app)
            && app.views().view == View::Samples
            && app
                .engine()
                .settings()
                .is_some_and(|s| s.adaptive().is_some())
            && app.engine().view_values(View::Samples).is_some()
    });
    let samples: Vec<f32> = harness
        .state()
        .engine()
        .view_values(View::Samples)
        .unwrap()
        .into_iter()
        .map(|v| v.expect("every pixel sampled"))
        .collect();
    let (min_spp, max_spp) = (adaptive.min_spp as f32, adaptive.max_spp as f32);
    assert!(samples.iter().all(|&n| (min_spp..=max_spp).contains(&n)));
    assert!(
        samples.contains(&min_spp),
        "no pixel stopped at the minimum"
    );
    assert!(
        samples.iter().any(|&n| n > min_spp),
        "no pixel refined past the minimum"
    );
    harness.run_steps(2);
    harness.get_by_label("Pixels done");
    harness.get_by_label("100.0%");
}

#[test]
fn the_eye_rays_grid_walk_steps_one_cell_at_a_time_with_its_tests() {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the render", is_done);
    let settings = harness.state().engine().settings().unwrap().clone();
    harness
        .get_by_role_and_label(Role::CheckBox, "Structure overlay")
        .click();
    harness.key_press(egui::Key::G);
    // Down the middle column, the first pixel whose eye ray walks three
    // cells or more: one to step through.
    let mut visits = Vec::new();
    for y in (1..8).map(|k| settings.height * k / 8) {
        harness.state_mut().inspect((settings.width / 2, y));
        wait_for(&mut harness, "the whole grid walk", |app| {
            let tree = app.inspector().tree(0);
            is_done(app)
                && tree.and_then(|t| t.as_ref().ok()).is_some_and(|t| {
                    (t.x, t.y) == (settings.width / 2, y)
                        && matches!(t.eye_visits.first(), None | Some(Visit::Cell { .. }))
                })
                && app.overlay().visits_drawn == app.inspector().eye_visits().len()
        });
        visits = harness.state().inspector().eye_visits().to_vec();
        if visits.len() >= 3 {
            break;
        }
    }
    let n = visits.len();
    assert!(n >= 3, "a walk worth stepping through: {visits:?}");
    let brute = harness.state().engine().scene().unwrap().world.shapes.len();
    harness.get_by_label(&format!("all {n} visits"));

    // Next twice: the first two cells drawn, the second the current one.
    harness
        .get_by_role_and_label(Role::Button, "Next visit")
        .click();
    harness.run_steps(2);
    harness
        .get_by_role_and_label(Role::Button, "Next visit")
        .click();
    wait_for(&mut harness, "two cells drawn", |app| {
        app.overlay().visits_drawn == 2
    });
    harness.get_by_label(&format!("step 2 of {n}"));
    let so_far = Tally::of(&visits[..2]).primitives;
    harness.get_by_label(&format!(
        "so far: {so_far} primitives tested; brute force tests {brute}"
    ));

    // All again: every cell, and the query's own count.
    harness.get_by_role_and_label(Role::Button, "All").click();
    wait_for(&mut harness, "every cell drawn", |app| {
        app.overlay().visits_drawn == n
    });
    let tree = match harness.state().inspector().tree(0) {
        Some(Ok(tree)) => tree.clone(),
        other => panic!("no tree: {other:?}"),
    };
    let all = tree.eye_counters.intersection_tests;
    assert!(all >= Tally::of(&visits).primitives);
    harness.get_by_label_contains(&format!("in all: {all} primitives"));
    harness.get_by_label_contains(&format!("brute force tests {brute}"));
}

/// The active pixels' overlay: an adaptive render held after the pass that
/// first lets flat pixels stop (the third: 1, 2, then 4 samples, the
/// minimum at N = 2) tints the pixels still refining, only some of them;
/// once the render is done, none.
#[test]
fn the_active_overlay_shows_the_pixels_still_refining() {
    let mut harness = ready_window(TALL);
    wait_for(&mut harness, "the first render", is_done);
    let settings = harness.state().engine().settings().unwrap().clone();
    let pixels = (settings.width * settings.height) as usize;
    let tiles = Tile::grid(settings.width, settings.height, TILE_SIZE).len() as u64;
    // Every tile takes samples in the first three passes: the last one's
    // last tile holds the render, with the mask decided after it.
    harness
        .state_mut()
        .pause_renders_after_tiles(Some(3 * tiles));
    harness.get_by_label("adaptive").click();
    harness.run_steps(2);
    harness.get_by_label("Show active pixels").click();
    wait_for(
        &mut harness,
        "the render held after its third pass",
        |app| {
            let drawn = app.active_overlay().active_drawn();
            app.engine().is_paused() && drawn > 0 && drawn < pixels
        },
    );
    harness.state_mut().pause_renders_after_tiles(None);
    harness.key_press(egui::Key::Space);
    wait_for(&mut harness, "the adaptive render done", |app| {
        is_done(app)
            && app
                .engine()
                .settings()
                .is_some_and(|s| s.adaptive().is_some())
            && app.active_overlay().active_drawn() == 0
    });
    assert!(harness.state().active_overlay().on);
}
