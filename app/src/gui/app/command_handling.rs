//! What each [`Command`] does, once per frame after the panels recorded
//! them: the feature keys change the edited side's controls; the rest act
//! on both sides, the camera, the windows or the files.

use crate::gui::commands::Command;
use crate::gui::comparison::Comparison;
use crate::gui::editor::Pending;
use crate::gui::platform::target;
use crate::gui::sides::SideId;
use crate::gui::windows::studies::Applied;
use crate::load::SceneSource;

use super::WorkbenchApp;
use super::saving::SaveImage;

impl WorkbenchApp {
    pub(super) fn run_command(&mut self, command: Command, ctx: &egui::Context) {
        // Its key on the page: said as its greyed-out button says it.
        if let (true, Some(why)) = (command.opens_files(), target::NO_FILES) {
            self.messages.notify(why);
            return;
        }
        let controls = &mut self.sides.active_mut().controls;
        match command {
            Command::ToggleAntialiasing => controls.render.antialiasing ^= true,
            Command::ToggleSoftShadows => controls.render.soft_shadows ^= true,
            Command::ToggleDepthOfField => controls.render.depth_of_field ^= true,
            Command::ToggleGrid => controls.toggle_grid(),
            Command::ToggleKeepRefining => controls.render.keep_refining ^= true,
            Command::TogglePause => {
                let paused = !self.sides.a.engine.is_paused();
                for side in self.sides.each_mut() {
                    side.engine.set_paused(paused);
                }
            }
            Command::Restart => self.restart(),
            Command::ResetCamera => self.navigation.camera = None,
            Command::ZoomFit => self.navigation.fit(),
            Command::ZoomActualSize => self.navigation.actual_size(),
            Command::ToggleStats => self.session.show_stats ^= true,
            Command::CycleView => self.tools.views.cycle(),
            Command::ToggleHelp => self.tools.help_open ^= true,
            Command::ToggleCompare => {
                self.sides.toggle_b();
                self.comparison = Comparison::default();
            }
            Command::ToggleBenchmark => self.tools.bench.open ^= true,
            Command::ExportReport => self.tools.report.choose_file(self.dialogs.dialog.clone()),
            Command::ToggleStudies => self.tools.studies.open ^= true,
            Command::ToggleObserver => self.observer.on ^= true,
            Command::ToggleLessons => self.lessons.open ^= true,
            Command::SwapSides => {
                if !self.sides.swap() {
                    self.messages.notify("swap: turn compare mode on first (B)");
                }
            }
            Command::CopyAToB => {
                if !self.sides.copy_a_to_b() {
                    self.messages
                        .notify("copy A to B: turn compare mode on first (B)");
                }
            }
            Command::Reload => self.open_or_ask(Pending::Reload),
            Command::Open => {
                if !self.dialogs.open() {
                    self.messages.notify("cannot open a file dialog");
                }
            }
            Command::CopyLink => self.copy_link(ctx),
            Command::Save => self.save_dialog(false),
            Command::SaveExr => self.save_dialog(true),
            Command::ToggleEditor => self.tools.editor.open ^= true,
            Command::Undo => self.step_history(false),
            Command::Redo => self.step_history(true),
            Command::SaveScene => self.save_scene_dialog(self.sides.editing),
            // Esc answers a pending unsaved-edits question with Cancel first.
            Command::ClearSelection => {
                if self.tools.editor.pending.take().is_none() {
                    self.tools.editor.select(None);
                }
            }
        }
    }

    /// Throws away every side's samples and renders again (B not while it
    /// is an image).
    fn restart(&mut self) {
        let b_is_image = self.comparison.reference().is_some();
        for side in self.sides.each_mut() {
            if side.id == SideId::B && b_is_image {
                continue;
            }
            if let Err(e) = side.restart() {
                self.messages.error = Some(e);
            }
        }
    }

    /// Side A's render on screen (or its linear film) to a file the user
    /// picks, written off the UI thread.
    fn save_dialog(&mut self, exr: bool) {
        let image = match SaveImage::of(&self.sides.a, exr) {
            Ok(image) => image,
            Err(e) => {
                self.messages.notify(e.to_string());
                return;
            }
        };
        if self.navigation.is_camera_moving() {
            self.messages
                .notify("the camera is moving: save once the render settles");
            return;
        }
        let name = self
            .session
            .last_scene
            .as_ref()
            .map_or_else(|| "render".into(), SceneSource::label);
        if !self.dialogs.save(image, &name) {
            self.messages.notify("cannot open a file dialog");
        }
    }

    /// A study's point in the main view: its settings, or for the level
    /// study its generated scene.
    pub(super) fn apply_study_point(&mut self, applied: &Applied) {
        match applied.scene_file() {
            Ok(Some(path)) => self.open(SceneSource::File(path)),
            Ok(None) => {
                let a = &mut self.sides.a;
                let width = a.engine.scene().map_or(1, |s| s.scene.view.width);
                applied.apply_to(&mut a.controls, width);
            }
            Err(e) => self.messages.error = Some(format!("{e:#}")),
        }
    }
}
