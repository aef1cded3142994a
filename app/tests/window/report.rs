//! Export report... driven as a user would, with `egui_kittest`: the file
//! chosen (the dialog answered, there being no desktop), the progress
//! shown in its window, Cancel leaving no file; and an export that runs to
//! the end and writes the page.

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use workbench::gui::WorkbenchApp;

use crate::harness::{ready_window, wait_for};
use crate::support::scratch;

type Window = Harness<'static, WorkbenchApp>;

/// Files in `dir` (the page and any temporary file beside it).
fn files(dir: &std::path::Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect()
}

fn export(harness: &mut Window, path: std::path::PathBuf) {
    harness.state_mut().export_report_to(path);
    wait_for(harness, "the report's progress", |app| {
        app.report_export().progress().is_some()
    });
}

#[test]
fn export_report_shows_its_progress_and_cancel_writes_nothing() {
    let dir = scratch("window-report-cancel");
    let path = dir.join("report.html");
    let mut harness = ready_window([1280.0, 820.0]);
    export(&mut harness, path.clone());
    harness.run_steps(2);
    // The window shows what is measured, with a progress bar and Cancel.
    assert!(harness.state().report_export().is_running());
    harness.get_by_role(Role::ProgressIndicator);
    harness.get_by_label_contains("Measuring for");
    harness
        .get_by_role_and_label(Role::Button, "Cancel")
        .click();
    wait_for(&mut harness, "the cancel", |app| {
        !app.report_export().is_running()
    });
    let message = harness.state().report_export().message.clone();
    assert!(
        message.as_deref().is_some_and(|m| m.contains("cancelled")),
        "{message:?}"
    );
    harness.run_steps(2);
    harness.get_by_label_contains("nothing written");
    assert!(files(&dir).is_empty(), "{:?}", files(&dir));
}

#[test]
fn export_report_writes_the_page_of_the_scene_on_screen() {
    let dir = scratch("window-report-end");
    let path = dir.join("report.html");
    let mut harness = ready_window([1280.0, 820.0]);
    export(&mut harness, path.clone());
    wait_for(&mut harness, "the report", |app| {
        !app.report_export().is_running()
    });
    let message = harness.state().report_export().message.clone();
    assert!(
        message.as_deref().is_some_and(|m| m.contains("written to")),
        "{message:?}"
    );
    let page = std::fs::read_to_string(&path).unwrap();
    // The scene on screen, at the window's size (balls_low at 1/8).
    assert!(page.contains("Lab report: balls_low"), "the scene's name");
    assert!(page.contains("64 x 64"), "the window's resolution");
    assert_eq!(page.matches("<section id=").count(), 7);
    assert_eq!(files(&dir), ["report.html"]);
}
