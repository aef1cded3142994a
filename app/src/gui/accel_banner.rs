//! A banner over the image when the render runs brute force over a scene
//! large enough to look like a hang (course files carry `accel 0`), with
//! the one-click switch to a BVH. The file's choice is respected until the
//! user clicks.

use egui::{Color32, RichText, Ui};
use tracer::render::RenderSettings;
use tracer::stats::SceneCounts;

use crate::measure::cost::BruteForceCost;

/// Shows the banner when `settings` would be slow on a scene of `counts`;
/// true when the user asked to switch to the BVH.
pub fn show(ui: &mut Ui, side: &str, settings: &RenderSettings, counts: &SceneCounts) -> bool {
    let Some(cost) = BruteForceCost::of(settings, counts) else {
        return false;
    };
    let mut switch = false;
    egui::Frame::new()
        .fill(Color32::from_rgb(90, 70, 10))
        .inner_margin(6.0)
        .show(ui, |ui| {
            ui.set_width(ui.available_width());
            ui.horizontal_wrapped(|ui| {
                ui.label(RichText::new("Slow").strong().color(Color32::WHITE));
                ui.label(
                    RichText::new(format!("{side}{}.", cost.describe())).color(Color32::WHITE),
                );
                switch = ui
                    .button("Switch to BVH")
                    .on_hover_text("Render with a bounding volume hierarchy: seconds instead")
                    .clicked();
            });
        });
    switch
}
