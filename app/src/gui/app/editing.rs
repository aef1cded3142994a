//! The scene editor's part of the frame: its window on the edited side, a
//! click on the image selecting the object it shows, a drag moving the
//! selected object, undo and redo, saving the scene, and the question
//! asked before unsaved edits would be thrown away.

use std::path::Path;

use tracer::render::Outcome;
use tracer::scene::edit::Effect;

use super::WorkbenchApp;
use super::saving::SceneSave;
use crate::gui::commands::Command;
use crate::gui::editor::{self, Pending};
use crate::gui::image::viewport::ViewportResponse;
use crate::gui::sides::SideId;
use crate::load::SceneSource;
use crate::measure::ray_tree_report;

impl WorkbenchApp {
    /// The editor window over the edited side, after the image took this
    /// frame's click; then the unsaved-edits question if one waits.
    pub(super) fn editor_window(&mut self, ctx: &egui::Context, commands: &mut Vec<Command>) {
        self.take_pick();
        let side = self.sides.active_mut();
        let outcome = editor::window(ctx, &mut self.tools.editor, side, commands);
        if outcome.camera_edited {
            self.navigation.camera = None;
        }
        self.unsaved_question(ctx);
    }

    /// A click on the image while the editor is open selects the object
    /// the pixel's eye ray meets first (nothing on a miss).
    fn take_pick(&mut self) {
        let Some(pixel) = self.tools.editor.pick_at.take() else {
            return;
        };
        let engine = &self.sides.active_mut().engine;
        let (Some(scene), Some(settings)) = (engine.scene(), engine.settings()) else {
            return;
        };
        let tree = ray_tree_report::inspect(&scene.world, engine.index(), settings, pixel, 0);
        let hit = tree
            .ok()
            .and_then(|tree| match &tree.nodes.first()?.outcome {
                Outcome::Surface(surface) => Some(surface.object as usize),
                _ => None,
            });
        self.tools.editor.select(hit);
    }

    /// In move mode, a left drag over the image moves the selected object
    /// instead of the camera.
    pub(super) fn move_selected(&mut self, viewport: &mut ViewportResponse) {
        let gestures = std::mem::take(&mut viewport.gestures);
        let side = self.sides.active_mut();
        let (rest, edit) = self
            .tools
            .editor
            .take_drag(gestures, side, viewport.image_rect);
        viewport.gestures = rest;
        if let Some(edit) = edit
            && let Err(why) = side.edit(edit)
        {
            self.tools.editor.message = Some(why);
        }
    }

    /// Undo (or `redo`) on the edited side.
    pub(super) fn step_history(&mut self, redo: bool) {
        let side = self.sides.active_mut();
        let result = if redo { side.redo() } else { side.undo() };
        let word = if redo { "redo" } else { "undo" };
        match result {
            Ok(Some(Effect::Camera)) => self.navigation.camera = None,
            Ok(Some(_)) => {}
            Ok(None) => self.messages.notify(format!("nothing to {word}")),
            Err(why) => self.messages.notify(format!("cannot {word}: {why}")),
        }
    }

    /// Whether a side's scene has edits no file holds.
    fn has_unsaved_edits(&self) -> bool {
        self.sides.each().any(|s| s.history.is_modified())
    }

    /// Opens `source` unless unsaved edits would be lost: then the user is
    /// asked first.
    pub(super) fn open_or_ask(&mut self, pending: Pending) {
        if self.has_unsaved_edits() {
            self.tools.editor.pending = Some(pending);
            return;
        }
        self.go_on(pending);
    }

    /// Does what waited for the user's word.
    fn go_on(&mut self, pending: Pending) {
        match pending {
            Pending::Open(source) => self.open_now(source),
            Pending::Reload => self.reload_now(),
        }
    }

    /// Side `side`'s scene to a P3F file the user picks.
    pub(super) fn save_scene_dialog(&mut self, side: SideId) {
        let Some((save, source)) = self.scene_to_save(side) else {
            self.messages.notify("there is no scene to save yet");
            return;
        };
        if !self.dialogs.save_scene(save, &source) {
            self.messages.notify("cannot open a file dialog");
        }
    }

    /// Side `side`'s scene, its history state and where it came from.
    pub(super) fn scene_to_save(&self, side: SideId) -> Option<(SceneSave, SceneSource)> {
        let side = self.sides.each().find(|s| s.id == side)?;
        let loaded = side.engine.scene()?;
        let save = SceneSave {
            scene: loaded.scene.clone(),
            side: side.id,
            state: side.history.state(),
        };
        Some((save, loaded.source.clone()))
    }

    /// `side`'s scene as it stood in `state` is now the file `path`: it is
    /// that file's scene from now on (A's reload reads it), and what
    /// waited on the save goes on when nothing else is unsaved.
    pub(super) fn scene_saved(&mut self, side: SideId, path: &Path, state: u64) {
        let Some(saved) = self.sides.each_mut().find(|s| s.id == side) else {
            return;
        };
        saved.history.mark_saved(state);
        saved.engine.saved_as(path);
        if side == SideId::A {
            self.session.remember(path.to_path_buf());
            self.session.last_scene = Some(SceneSource::File(path.to_path_buf()));
        }
        self.messages
            .notify(format!("saved the scene as {}", path.display()));
        if !self.has_unsaved_edits()
            && let Some(pending) = self.tools.editor.pending.take()
        {
            self.go_on(pending);
        }
    }

    /// The question before unsaved edits are lost: discard them, save the
    /// scene first (what waits goes on once it is saved), or keep them.
    fn unsaved_question(&mut self, ctx: &egui::Context) {
        let Some(pending) = self.tools.editor.pending.clone() else {
            return;
        };
        let unsaved: Vec<SideId> = self
            .sides
            .each()
            .filter(|s| s.history.is_modified())
            .map(|s| s.id)
            .collect();
        let names: Vec<&str> = unsaved.iter().map(|s| s.name()).collect();
        let what = match &pending {
            Pending::Open(source) => format!("Opening {}", source.label()),
            Pending::Reload => "Reloading the file".to_string(),
        };
        let mut answer = None;
        egui::Modal::new(egui::Id::unique("unsaved_edits")).show(ctx, |ui| {
            ui.heading("Unsaved edits");
            ui.label(format!(
                "{what} throws away the edits of {} not saved to a file.",
                names.join(" and ")
            ));
            ui.horizontal(|ui| {
                if ui.button("Discard edits").clicked() {
                    answer = Some(Answer::Discard);
                }
                if ui.button("Save scene...").clicked() {
                    answer = Some(Answer::Save);
                }
                if ui.button("Cancel").clicked() {
                    answer = Some(Answer::Cancel);
                }
            });
        });
        match answer {
            Some(Answer::Discard) => {
                self.tools.editor.pending = None;
                self.go_on(pending);
            }
            Some(Answer::Save) => {
                if let Some(&side) = unsaved.first() {
                    self.save_scene_dialog(side);
                }
            }
            Some(Answer::Cancel) => self.tools.editor.pending = None,
            None => {}
        }
    }
}

/// The buttons of the unsaved-edits question.
enum Answer {
    Discard,
    Save,
    Cancel,
}
