//! The side panel's observer section: the view on or off, beside the image
//! or instead of it, its resolution, more pixels' rays (a row, a column, a
//! grid), which rays are drawn and how strongly, the animation of the
//! rays, and the observer camera's reset.

use egui::{Slider, Ui};

use super::settings::command_toggle;
use crate::figures::observer::PixelPattern;
use crate::gui::commands::Command;
use crate::gui::observer::{Observer, ObserverLayout};

pub(crate) fn show(ui: &mut Ui, observer: &mut Observer, commands: &mut Vec<Command>) {
    command_toggle(ui, observer.on, Command::ToggleObserver, commands);
    if !observer.on {
        return;
    }
    ui.horizontal(|ui| {
        ui.selectable_value(&mut observer.layout, ObserverLayout::Beside, "Beside")
            .on_hover_text("The observer beside the camera's image");
        ui.selectable_value(&mut observer.layout, ObserverLayout::Instead, "Instead")
            .on_hover_text("The observer in place of the camera's image");
        if ui
            .button("Reset observer")
            .on_hover_text("Back to the view behind and above the camera")
            .clicked()
        {
            observer.reset_camera();
        }
    });
    ui.add(Slider::new(&mut observer.resolution, 96..=960).text("Observer width (px)"))
        .on_hover_text("The observer's render: smaller follows moves faster");
    pattern(ui, observer);
    filter(ui, observer);
    animation(ui, observer);
    ui.small(match observer.trees().len() {
        0 => "Click a pixel of the image: its rays fly through the scene here.".to_string(),
        n => format!("{n} tree(s), {} segments drawn", observer.segments_drawn),
    });
}

/// More pixels whose rays are drawn: none, a row, a column or a grid.
fn pattern(ui: &mut Ui, observer: &mut Observer) {
    let (mut kind, mut number) = match observer.pattern {
        None => (0, 0),
        Some(PixelPattern::Row(y)) => (1, y),
        Some(PixelPattern::Column(x)) => (2, x),
        Some(PixelPattern::Grid(step)) => (3, step),
    };
    ui.horizontal(|ui| {
        ui.label("More pixels");
        egui::ComboBox::from_id_salt("observer_pixels")
            .selected_text(["none", "row", "column", "grid"][kind])
            .show_ui(ui, |ui| {
                for (i, name) in ["none", "row", "column", "grid"].iter().enumerate() {
                    ui.selectable_value(&mut kind, i, *name);
                }
            });
        if kind > 0 {
            let what = ["", "y", "x", "step"][kind];
            ui.add(
                egui::DragValue::new(&mut number)
                    .range(0..=16384)
                    .prefix(what),
            );
        }
    });
    observer.pattern = match kind {
        1 => Some(PixelPattern::Row(number)),
        2 => Some(PixelPattern::Column(number)),
        3 => Some(PixelPattern::Grid(number.max(1))),
        _ => None,
    };
}

/// Which rays are drawn: misses hidden, rays adding little to their pixel
/// hidden or faded, the tree grown one bounce at a time.
fn filter(ui: &mut Ui, observer: &mut Observer) {
    let deepest = observer.phases().saturating_sub(2);
    let filter = &mut observer.filter;
    ui.horizontal(|ui| {
        ui.checkbox(&mut filter.hide_misses, "Hide misses")
            .on_hover_text("Hide the rays that hit nothing and took the background");
        ui.checkbox(&mut observer.fade, "Fade by share")
            .on_hover_text("Draw each ray as strongly as it adds to its pixel's colour");
    });
    let mut percent = filter.min_share * 100.0;
    ui.add(
        Slider::new(&mut percent, 0.0..=50.0)
            .suffix(" %")
            .text("Hide under"),
    )
    .on_hover_text(
        "Hide the rays that, with the rays they spawn, add less than this share \
         of their pixel's colour",
    );
    filter.min_share = percent / 100.0;
    ui.horizontal(|ui| {
        let mut limited = filter.max_depth.is_some();
        ui.checkbox(&mut limited, "Bounces up to")
            .on_hover_text("Grow the trees one recursion depth at a time");
        match (limited, filter.max_depth) {
            (false, _) => filter.max_depth = None,
            (true, None) => filter.max_depth = Some(0),
            (true, Some(_)) => {}
        }
        if let Some(depth) = &mut filter.max_depth {
            let most = deepest.max(*depth);
            ui.add(egui::DragValue::new(depth).range(0..=most));
            if ui
                .add_enabled(*depth < deepest, egui::Button::new("Grow"))
                .on_hover_text("One bounce deeper")
                .clicked()
            {
                *depth += 1;
            }
        }
    });
}

/// Play, pause, step and speed of the rays growing out of the camera.
fn animation(ui: &mut Ui, observer: &mut Observer) {
    let phases = observer.phases();
    let animation = &mut observer.animation;
    ui.horizontal(|ui| {
        if ui
            .button("Play")
            .on_hover_text("Rays grow from the camera: eye rays, each bounce, then shadow rays")
            .clicked()
        {
            animation.play();
        }
        if animation.is_playing() {
            if ui.button("Pause").clicked() {
                animation.pause();
            }
        } else if animation.phase().is_some() && ui.button("Resume").clicked() {
            animation.resume();
        }
        if ui
            .button("Step")
            .on_hover_text("The next generation of rays")
            .clicked()
        {
            animation.step(phases);
        }
        if animation.phase().is_some() && ui.button("Whole").clicked() {
            animation.rest();
        }
    });
    ui.add(
        Slider::new(&mut animation.speed, 0.1..=8.0)
            .logarithmic(true)
            .text("generations / s"),
    );
    if let Some(phase) = animation.phase() {
        let what = if phase + 1 >= phases {
            "shadow rays".to_string()
        } else if phase == 0 {
            "eye rays".to_string()
        } else {
            format!("bounce {phase}")
        };
        ui.small(format!("showing {what} ({} of {phases})", phase + 1));
    }
}
