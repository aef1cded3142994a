//! Banners above the image: the error until dismissed, and the slow
//! brute-force warning when a side renders without a structure over a
//! scene large enough to look like a hang (course files carry `accel 0`),
//! with the one-click switch to a BVH. The file's choice is respected until
//! the user clicks.

use egui::{Color32, RichText, Ui};
use tracer::render::RenderSettings;
use tracer::stats::SceneCounts;

use crate::measure::cost::BruteForceCost;

/// The error, wrapped to the panel's width, with its Dismiss button.
pub(crate) fn error(ui: &mut Ui, error: &mut Option<String>) {
    let Some(message) = error.clone() else {
        return;
    };
    banner(ui, Color32::from_rgb(90, 20, 20), |ui| {
        ui.horizontal(|ui| {
            ui.label(RichText::new("Error").strong().color(Color32::WHITE));
            ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                if ui.small_button("Dismiss").clicked() {
                    *error = None;
                }
            });
        });
        ui.add(egui::Label::new(RichText::new(&message).color(Color32::WHITE)).wrap());
    });
}

/// A banner of colour `fill` as wide as the panel, so that long messages
/// (paths, parser context) wrap inside it instead of widening it.
fn banner(ui: &mut Ui, fill: Color32, contents: impl FnOnce(&mut Ui)) {
    egui::Frame::new()
        .fill(fill)
        .inner_margin(6.0)
        .show(ui, |ui| {
            ui.set_width(ui.available_width());
            contents(ui);
        });
}

/// Shows the banner when `settings` would be slow on a scene of `counts`
/// (`side` prefixes its text: "B: "); true when the user asked to switch to
/// the BVH.
pub(crate) fn brute_force(
    ui: &mut Ui,
    side: &str,
    settings: &RenderSettings,
    counts: &SceneCounts,
) -> bool {
    let Some(cost) = BruteForceCost::of(settings, counts) else {
        return false;
    };
    let mut switch = false;
    banner(ui, Color32::from_rgb(90, 70, 10), |ui| {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new("Slow").strong().color(Color32::WHITE));
            ui.label(RichText::new(format!("{side}{}.", cost.describe())).color(Color32::WHITE));
            switch = ui
                .button("Switch to BVH")
                .on_hover_text("Render with a bounding volume hierarchy: seconds instead")
                .clicked();
        });
    });
    switch
}
