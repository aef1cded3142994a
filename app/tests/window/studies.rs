//! The Studies window driven as a user would, with `egui_kittest`: open it
//! by its key, type values, run, watch the progress, cancel, run again,
//! hover a point of the chart and apply points to the main view.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tracer::accel::AccelKind;
use workbench::gui::WorkbenchApp;

use crate::harness::{answer_dialogs, small_window_sized, wait_for, wait_for_scene};

type Window = Harness<'static, WorkbenchApp>;

/// The window on the bundled `balls_low` at an eighth of its size, with
/// the Studies window open.
fn studies_window() -> Window {
    let mut harness = small_window_sized(Harness::builder(), [1280.0, 900.0]);
    wait_for_scene(&mut harness);
    harness.key_press(egui::Key::P);
    harness.run_steps(3);
    assert!(harness.state().studies().open);
    harness
}

/// Replaces the values text, as typing over a selection does.
fn type_values(harness: &mut Window, text: &str) {
    harness
        .get_by_role_and_label(Role::TextInput, "values")
        .focus();
    harness.run_steps(2);
    harness.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::A);
    harness
        .get_by_role_and_label(Role::TextInput, "values")
        .type_text(text);
    harness.run_steps(2);
}

fn choose(harness: &mut Window, combo: &str, option: &str) {
    harness.get_by_role_and_label(Role::ComboBox, combo).click();
    harness.run_steps(2);
    harness.get_by_label(option).click();
    harness.run_steps(2);
}

#[test]
fn a_study_runs_shows_progress_cancels_and_applies_a_point() {
    let mut harness = studies_window();
    // A slow study first (brute force on thousands of spheres), to cancel.
    choose(&mut harness, "parameter", "level");
    type_values(&mut harness, "4..5");
    harness
        .get_by_role_and_label(Role::CheckBox, "grid")
        .click();
    harness.get_by_role_and_label(Role::CheckBox, "bvh").click();
    harness.run_steps(2);
    harness.get_by_role_and_label(Role::Button, "Run").click();
    harness.run_steps(2);
    assert!(harness.state().studies().is_running());
    wait_for(&mut harness, "progress", |app| {
        app.studies()
            .progress()
            .is_some_and(|(_, what)| what.contains("none"))
    });
    harness
        .get_by_role_and_label(Role::Button, "Cancel")
        .click();
    wait_for(&mut harness, "the cancel", |app| {
        !app.studies().is_running()
    });
    let studies = harness.state().studies();
    assert!(studies.points().count() < 2);
    assert!(
        studies.message().unwrap().contains("cancelled"),
        "{:?}",
        studies.message()
    );

    // Bad values are refused with the reason, and nothing runs.
    choose(&mut harness, "parameter", "grid-m");
    type_values(&mut harness, "1..x");
    harness.get_by_role_and_label(Role::Button, "Run").click();
    harness.run_steps(2);
    assert!(!harness.state().studies().is_running());
    let message = harness.state().studies().message().unwrap().to_string();
    assert!(message.contains("`x` in `1..x`"), "{message}");

    // A quick grid-m study to the end: one point per value, on the grid.
    type_values(&mut harness, "1,3,4");
    harness.get_by_role_and_label(Role::Button, "Run").click();
    wait_for(&mut harness, "the study", |app| {
        !app.studies().is_running() && app.studies().points().count() > 0
    });
    let m: Vec<f64> = harness
        .state()
        .studies()
        .points()
        .map(|p| p.value)
        .collect();
    assert_eq!(m, [1.0, 3.0, 4.0]);
    assert!(
        harness
            .state()
            .studies()
            .points()
            .all(|p| p.accel() == AccelKind::Grid)
    );
    harness.run_steps(2);

    // Hovering a point of the chart shows its numbers; clicking it shows
    // its settings in the main view. The points sit above the table's
    // header, where their times put them: look for one.
    let header = harness.get_by_label("accel").rect();
    let hint = "click to show it in the main view";
    let mut on_point = None;
    'scan: for up in (40..=260).step_by(10) {
        for x in (0..=800).step_by(10) {
            let pos = egui::pos2(x as f32, header.top() - up as f32);
            harness.hover_at(pos);
            harness.step();
            if harness.query_by_label(hint).is_some() {
                on_point = Some(pos);
                break 'scan;
            }
        }
    }
    let pos = on_point.expect("a point of the chart shows its numbers when hovered");
    for pressed in [true, false] {
        harness.event(egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        });
        harness.step();
    }
    wait_for(&mut harness, "the clicked point's settings", |app| {
        app.engine().settings().is_some_and(|s| {
            s.accel == AccelKind::Grid && [1.0, 3.0, 4.0].contains(&s.grid_multiplier)
        })
    });
    let clicked = harness.state().engine().settings().unwrap().grid_multiplier;

    // Apply on a row does the same: take a row of another value.
    let row = if clicked == 1.0 { 2 } else { 0 };
    let wanted = [1.0, 3.0, 4.0][row];
    harness
        .get_all_by_role_and_label(Role::Button, "Apply")
        .nth(row)
        .unwrap()
        .click();
    wait_for(&mut harness, "the row's settings", |app| {
        app.engine()
            .settings()
            .is_some_and(|s| s.grid_multiplier == wanted)
    });
}

#[test]
fn save_chart_asks_a_png_name_and_writes_the_study_chart() {
    let dir = crate::support::scratch("studies-save-chart");
    let mut harness = studies_window();
    let answers = answer_dialogs(&mut harness);
    assert!(
        harness.query_by_label("Save chart...").is_none(),
        "nothing to save before a study"
    );
    type_values(&mut harness, "1,2");
    harness.get_by_role_and_label(Role::Button, "Run").click();
    wait_for(&mut harness, "the study", |app| {
        !app.studies().is_running() && app.studies().points().count() == 2
    });
    harness.run_steps(2);
    let chart = dir.join("chart.png");
    answers.next(Some(&chart));
    harness
        .get_by_role_and_label(Role::Button, "Save chart...")
        .click();
    wait_for(&mut harness, "the saved chart", |_| chart.exists());
    let (filter, name, save) = answers.last();
    assert_eq!(
        (filter, name.as_deref(), save),
        (vec!["png"], Some("study-grid-m-balls_low.png"), true)
    );
    let image = image::open(&chart).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (800, 500));
    tracer::waiting::wait_until("the notice", || {
        harness.step();
        harness.query_by_label_contains("chart saved to").is_some()
    });
}
