//! The side panel: feature toggles (through the command table), sliders
//! with tooltips, and the render actions.

use egui::{Slider, Ui};
use tracer::accel::AccelKind;
use tracer::render::{MAX_DEPTH, MAX_GRID_MULTIPLIER, MAX_SAMPLES, RenderSettings, Sampling};
use tracer::scene::Viewpoint;

use crate::gui::commands::Command;
use crate::gui::image::active_overlay::ActiveOverlay;
use crate::gui::platform::file_button;
use crate::gui::sides::Controls;

/// The noise thresholds the slider offers, on a logarithmic scale: the
/// useful part of the valid range (`tracer::scene::NOISE_THRESHOLD`),
/// from near-exact to coarse; its ends are for the command line.
const NOISE_THRESHOLD_SLIDER: std::ops::RangeInclusive<f32> = 0.0005..=0.1;

/// Largest N offered by the slider (N x N samples per pixel).
const SLIDER_MAX_SAMPLES: u32 = 16;

/// Uniform or adaptive sampling.
fn adaptive_switch(ui: &mut Ui, render: &mut RenderSettings) {
    let mut adaptive = matches!(render.sampling, Sampling::Adaptive(_));
    if ui
        .checkbox(&mut adaptive, "adaptive")
        .on_hover_text(
            "Spend anti-aliasing's samples where each pixel's estimated error is above the \
             noise threshold, up to (2N)^2; flat pixels stop at the minimum",
        )
        .changed()
    {
        if adaptive {
            render.sample_adaptively(|_| {});
        } else {
            render.sampling = Sampling::Uniform;
        }
    }
}

/// Adaptive sampling's threshold, maximum and minimum, when it is on.
fn adaptive_knobs(ui: &mut Ui, render: &mut RenderSettings) {
    if let Sampling::Adaptive(a) = &mut render.sampling {
        ui.add(
            Slider::new(&mut a.noise_threshold, NOISE_THRESHOLD_SLIDER)
                .logarithmic(true)
                .text("Noise threshold"),
        )
        .on_hover_text(
            "A pixel at the minimum stops once its estimated error is below this (display \
             units: 0.01 is 2.55 levels of 255); with more or costlier samples the bar grows \
             in proportion",
        );
        let most = MAX_SAMPLES * MAX_SAMPLES;
        ui.add(
            Slider::new(&mut a.max_spp, 1..=most)
                .logarithmic(true)
                .text("Max spp"),
        )
        .on_hover_text("Samples no pixel exceeds; its square root stratifies the pixel");
        a.min_spp = a.min_spp.min(a.max_spp);
        ui.add(Slider::new(&mut a.min_spp, 1..=a.max_spp).text("Min spp"))
            .on_hover_text("Samples every pixel takes before its error is trusted");
    }
}

/// A structure's name in the window.
fn accel_label(kind: AccelKind) -> &'static str {
    match kind {
        AccelKind::None => "None",
        AccelKind::Grid => "Uniform grid",
        AccelKind::Bvh => "BVH",
    }
}

/// A toggle bound to a command: clicking it records the command, so the
/// key and the checkbox do exactly the same thing.
pub(crate) fn command_toggle(ui: &mut Ui, on: bool, command: Command, commands: &mut Vec<Command>) {
    let mut value = on;
    let text = format!("{} ({})", command.label(), command.shortcut_text(ui.ctx()));
    if ui
        .checkbox(&mut value, text)
        .on_hover_text(command.description())
        .changed()
    {
        commands.push(command);
    }
}

/// A button bound to a command.
pub(crate) fn command_button(ui: &mut Ui, command: Command, commands: &mut Vec<Command>) {
    let tip = format!(
        "{} ({})",
        command.description(),
        command.shortcut_text(ui.ctx())
    );
    let button = egui::Button::new(command.label());
    let button = if command.opens_files() {
        file_button(ui, true, button)
    } else {
        ui.add(button)
    };
    if button.on_hover_text(tip).clicked() {
        commands.push(command);
    }
}

/// Draws the controls; toggles and buttons record commands, sliders edit
/// `controls` directly.
/// `scene_view` is the side's scene's view (none before one loads): it owns
/// the lens, which the sliders show and a moved slider overrides.
pub(crate) fn show(
    ui: &mut Ui,
    controls: &mut Controls,
    scene_view: Option<&Viewpoint>,
    active: &mut ActiveOverlay,
    paused: bool,
    commands: &mut Vec<Command>,
) {
    ui.heading("Rendering");
    command_toggle(
        ui,
        controls.render.antialiasing,
        Command::ToggleAntialiasing,
        commands,
    );
    command_toggle(
        ui,
        controls.render.soft_shadows,
        Command::ToggleSoftShadows,
        commands,
    );
    command_toggle(
        ui,
        controls.render.depth_of_field,
        Command::ToggleDepthOfField,
        commands,
    );
    command_toggle(
        ui,
        controls.render.accel == AccelKind::Grid,
        Command::ToggleGrid,
        commands,
    );
    ui.horizontal(|ui| {
        ui.label("Acceleration");
        egui::ComboBox::from_id_salt("accel")
            .selected_text(accel_label(controls.render.accel))
            .show_ui(ui, |ui| {
                for choice in AccelKind::ALL {
                    if ui
                        .selectable_label(controls.render.accel == choice, accel_label(choice))
                        .clicked()
                    {
                        controls.set_accel(choice);
                    }
                }
            })
            .response
            .on_hover_text(
                "None tests every object; the uniform grid is the course's (a 3D-DDA walk, \
                 Amanatides-Woo, cells set by m); the BVH is the fastest",
            );
    });

    ui.separator();
    // N and the switch to adaptive sampling share a row: the panel keeps
    // its height (the overlay's options below stay on screen).
    ui.horizontal(|ui| {
        let mut n = controls.render.samples;
        if ui
            .add(Slider::new(&mut n, 1..=SLIDER_MAX_SAMPLES).text("Samples N"))
            .on_hover_text(
                "N x N samples per pixel (and strata of the lens and of soft shadows); \
                 adaptive sampling takes from N^2 / 4 to (2N)^2",
            )
            .changed()
        {
            controls.render.set_samples(n);
        }
        adaptive_switch(ui, &mut controls.render);
    });
    adaptive_knobs(ui, &mut controls.render);
    if controls.render.adaptive().is_some() {
        active.ui(ui);
    }
    let mut lens = controls
        .render
        .chosen_lens(scene_view.unwrap_or(&Viewpoint::default()));
    let lens_override = &mut controls.render.lens_override;
    if ui
        .add(Slider::new(&mut lens.aperture, 0.0..=64.0).text("Aperture (px)"))
        .on_hover_text("Lens diameter in pixels; depth of field must be on")
        .changed()
    {
        lens_override.aperture = Some(lens.aperture);
    }
    if ui
        .add(
            Slider::new(&mut lens.focal, 0.1..=4.0)
                .logarithmic(true)
                .text("Focal ratio"),
        )
        .on_hover_text("Distance of the sharp plane as a multiple of the view distance |at - from|")
        .changed()
    {
        lens_override.focal = Some(lens.focal);
    }
    ui.add(
        Slider::new(
            &mut controls.render.grid_multiplier,
            0.1..=MAX_GRID_MULTIPLIER,
        )
        .logarithmic(true)
        .text("Grid multiplier m"),
    )
    .on_hover_text(
        "Cells per axis = trunc(m * dim * cbrt(objects / volume)) + 1; rebuilds the grid",
    );
    ui.add(Slider::new(&mut controls.render.max_depth, 0..=MAX_DEPTH.min(16)).text("Max depth"))
        .on_hover_text("Bounces after the eye ray (reflection and refraction)");
    ui.add(
        Slider::new(&mut controls.render.light_size, 0.0..=4.0)
            .logarithmic(true)
            .text("Light size"),
    )
    .on_hover_text("Side of the square a point light becomes with soft shadows (scene units)");
    ui.add(
        Slider::new(&mut controls.resolution_scale, 0.125..=2.0)
            .logarithmic(true)
            .text("Resolution scale"),
    )
    .on_hover_text("Image size relative to the scene's resolution");
    ui.add(Slider::new(&mut controls.render.ambient, 0.0..=1.0).text("Ambient"))
        .on_hover_text("Ambient light times each surface's diffuse colour");
    ui.checkbox(&mut controls.srgb, "sRGB output")
        .on_hover_text(
            "Display and save with the sRGB curve instead of linear values (no restart)",
        );

    ui.separator();
    ui.horizontal_wrapped(|ui| {
        let pause = if paused { "Resume" } else { "Pause" };
        if ui
            .button(pause)
            .on_hover_text(format!("{} (Space)", Command::TogglePause.description()))
            .clicked()
        {
            commands.push(Command::TogglePause);
        }
        command_button(ui, Command::Restart, commands);
        command_button(ui, Command::ResetCamera, commands);
    });
    command_toggle(
        ui,
        controls.render.keep_refining,
        Command::ToggleKeepRefining,
        commands,
    );
    ui.horizontal_wrapped(|ui| {
        command_button(ui, Command::Save, commands);
        command_button(ui, Command::SaveExr, commands);
        command_button(ui, Command::ExportReport, commands);
        command_button(ui, Command::ZoomFit, commands);
        command_button(ui, Command::ZoomActualSize, commands);
    });
}

#[cfg(test)]
mod tests {
    use tracer::scene::NOISE_THRESHOLD;

    use super::NOISE_THRESHOLD_SLIDER;

    #[test]
    fn the_threshold_slider_stays_within_the_valid_range() {
        let (low, high) = NOISE_THRESHOLD.into_inner();
        let (slider_low, slider_high) = NOISE_THRESHOLD_SLIDER.into_inner();
        assert!(low <= slider_low && slider_low < slider_high && slider_high <= high);
    }
}
