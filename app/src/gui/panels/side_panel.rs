//! The side panel: the scene list, compare mode and which side is edited,
//! the edited side's settings (with the active pixels' overlay beside the
//! adaptive controls), the per-pixel view and the structure overlay.

use std::path::PathBuf;

use egui::Ui;
use tracer::scene::Viewpoint;
use tracer::stats::SceneCounts;

use super::scene_list::{self, Picked, SceneList};
use super::settings::{self, command_button, command_toggle};
use crate::gui::commands::Command;
use crate::gui::image::active_overlay::ActiveOverlay;
use crate::gui::image::pixel_views::PixelViews;
use crate::gui::image::structure_overlay::StructureOverlay;
use crate::gui::observer::Observer;
use crate::gui::platform::transfer::Transfer;
use crate::gui::sides::{Controls, SideId};
use crate::load::SceneSource;

/// What the side panel shows and edits.
pub(crate) struct SidePanelView<'a> {
    pub(crate) scene_list: &'a SceneList,
    pub(crate) current: Option<&'a SceneSource>,
    pub(crate) recent: &'a [PathBuf],
    /// The scene being fetched from the page's site, and its progress.
    pub(crate) fetching: Option<(&'a str, &'a Transfer)>,
    pub(crate) counts: Option<&'a SceneCounts>,
    /// `Some` in compare mode: the side being edited.
    pub(crate) editing: Option<&'a mut SideId>,
    /// The edited side's controls.
    pub(crate) controls: &'a mut Controls,
    /// The edited side's view, once its scene is loaded: the lens the
    /// sliders show unless the controls override it.
    pub(crate) scene_view: Option<&'a Viewpoint>,
    pub(crate) paused: bool,
    pub(crate) views: &'a mut PixelViews,
    pub(crate) overlay: &'a mut StructureOverlay,
    pub(crate) active: &'a mut ActiveOverlay,
    pub(crate) observer: &'a mut Observer,
}

/// Draws the panel's contents; returns the scene the user picked.
pub(crate) fn show(
    ui: &mut Ui,
    view: SidePanelView<'_>,
    commands: &mut Vec<Command>,
) -> Option<Picked> {
    let shown = scene_list::Shown {
        current: view.current,
        recent: view.recent,
        fetching: view.fetching,
    };
    let picked = scene_list::show(ui, view.scene_list, shown, commands);
    if let Some(counts) = view.counts {
        ui.small(format!(
            "{} objects, {} lights",
            counts.objects(),
            counts.lights
        ));
    }
    ui.separator();
    let comparing = view.editing.is_some();
    command_toggle(ui, comparing, Command::ToggleCompare, commands);
    if let Some(editing) = view.editing {
        ui.horizontal(|ui| {
            ui.label("Editing");
            for side in [SideId::A, SideId::B] {
                ui.selectable_value(editing, side, side.name());
            }
            command_button(ui, Command::SwapSides, commands);
            command_button(ui, Command::CopyAToB, commands);
        });
    }
    settings::show(
        ui,
        view.controls,
        view.scene_view,
        view.active,
        view.paused,
        commands,
    );
    ui.separator();
    view.views.ui(ui, comparing);
    view.overlay.ui(ui);
    ui.separator();
    super::observer::show(ui, view.observer, commands);
    ui.separator();
    command_button(ui, Command::ToggleHelp, commands);
    picked
}
