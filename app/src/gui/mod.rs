//! The window: an egui/eframe app (wgpu renderer) around the progressive
//! renderer. `engine` is the only part that talks to the tracer.

mod app;
mod commands;
mod controls;
mod engine;
mod scene_picker;
mod state;
mod stats_panel;
mod viewport;

use std::path::PathBuf;

pub use app::WorkbenchApp;
pub use commands::Command;
pub use engine::{Activity, Engine};
pub use state::{AccelChoice, Controls, Persisted};

use crate::load::SceneSource;

/// Opens the window on `scene` (or the last scene, or the bundled default)
/// and runs until it is closed.
pub fn run(scene: Option<PathBuf>) -> anyhow::Result<()> {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("Whitted Workbench")
            .with_inner_size([1280.0, 820.0])
            .with_min_inner_size([640.0, 400.0])
            .with_drag_and_drop(true),
        renderer: eframe::Renderer::Wgpu,
        persist_window: true,
        ..eframe::NativeOptions::default()
    };
    let initial = scene.map(SceneSource::File);
    eframe::run_native(
        "Whitted Workbench",
        options,
        Box::new(move |cc| {
            Ok(Box::new(WorkbenchApp::new(
                &cc.egui_ctx,
                cc.storage,
                initial,
            )))
        }),
    )
    .map_err(|e| {
        anyhow::anyhow!(
            "cannot open the window: {e}\n(no display? the headless commands still work: \
             see `workbench --help`)"
        )
    })
}
