//! Choosing a scene: the bundled ones, files in `scenes/` on disk, recent
//! files, and a native open dialog.

use std::path::{Path, PathBuf};

use egui::Ui;

use crate::bundled;
use crate::load::SceneSource;

use super::commands::Command;
use super::controls::command_button;

/// Scene files in `dir` (not recursive), sorted.
pub fn scene_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| is_scene_file(p))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

/// Whether `path` looks like a scene file.
pub fn is_scene_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("p3f") || e.eq_ignore_ascii_case("nff"))
}

/// Draws the picker; returns the scene the user chose, if any.
pub fn show(
    ui: &mut Ui,
    current: Option<&SceneSource>,
    disk_scenes: &[PathBuf],
    recent: &[PathBuf],
    commands: &mut Vec<Command>,
) -> Option<SceneSource> {
    let mut chosen = None;
    ui.heading("Scene");
    ui.horizontal(|ui| {
        command_button(ui, Command::Open, commands);
        command_button(ui, Command::Reload, commands);
    });
    egui::ScrollArea::vertical()
        .id_salt("scene_list")
        .max_height(220.0)
        .show(ui, |ui| {
            for scene in bundled::SCENES {
                let source = SceneSource::Bundled(scene.name.to_string());
                let selected = current == Some(&source);
                let response = ui
                    .selectable_label(selected, scene.name)
                    .on_hover_text(scene.description);
                if response.clicked() {
                    chosen = Some(source);
                }
            }
            // Files on disk that are not bundled copies (edited or new).
            for path in disk_scenes {
                let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned());
                if stem.as_deref().is_some_and(|s| bundled::find(s).is_some()) {
                    continue;
                }
                let source = SceneSource::File(path.clone());
                let label = format!("{} (file)", source.label());
                if ui
                    .selectable_label(current == Some(&source), label)
                    .on_hover_text(path.display().to_string())
                    .clicked()
                {
                    chosen = Some(source);
                }
            }
        });
    if !recent.is_empty() {
        ui.collapsing("Recent files", |ui| {
            for path in recent {
                let source = SceneSource::File(path.clone());
                if ui
                    .selectable_label(current == Some(&source), source.label())
                    .on_hover_text(path.display().to_string())
                    .clicked()
                {
                    chosen = Some(source);
                }
            }
        });
    }
    chosen
}
