//! Compare mode's panels: the header above the images (layout, B as an
//! image, what differs, the difference legend) and the numbers of both
//! sides in the statistics panel (time, rays, speed ratio, MSE, PSNR,
//! FLIP, or a cost view's means).

use egui::{Color32, RichText, Ui};
use tracer::metrics::Palette;
use tracer::render::{Encoding, Snapshot, View};

use crate::describe::{describe, side_labels};
use crate::figures::heat_map::format_number;
use crate::gui::comparison::{CompareLayout, Comparison};
use crate::gui::image::pixel_views::colour_bar;
use crate::gui::platform::file_button;
use crate::gui::sides::Side;
use crate::measure::ab::Match;
use crate::measure::value_difference::{ValueStats, diverging_colour};

/// "A: grid off", "B: grid on, m = 4": what differs between the sides
/// (or what A is, beside B's image), and the scene edits one side has and
/// the other has not ("B: sphere #2 T 0.9").
pub(crate) fn labels(comparison: &Comparison, a: &Side, b: &Side) -> Option<(String, String)> {
    let settings_a = a.settings()?;
    let view_a = &a.engine.scene()?.scene.view;
    if let Some(reference) = comparison.reference() {
        return Some((
            format!("A: {}", describe(settings_a, view_a)),
            reference.label(),
        ));
    }
    let view_b = &b.engine.scene()?.scene.view;
    let (label_a, label_b) = side_labels(settings_a, b.settings()?, [view_a, view_b]);
    let edits = |side: &Side| {
        side.engine
            .scene()
            .map_or_else(Vec::new, |s| side.history.describe(&s.scene))
    };
    let (edits_a, edits_b) = (edits(a), edits(b));
    let shared = edits_a
        .iter()
        .zip(&edits_b)
        .take_while(|(x, y)| x == y)
        .count();
    Some((
        format!("A: {}", with_edits(label_a, &edits_a[shared..])),
        format!("B: {}", with_edits(label_b, &edits_b[shared..])),
    ))
}

/// How many of a side's own edits its label names.
const EDITS_NAMED: usize = 3;

/// `settings` and then `edits` (the last few, with how many more).
fn with_edits(settings: String, edits: &[String]) -> String {
    if edits.is_empty() {
        return settings;
    }
    let shown = &edits[edits.len().saturating_sub(EDITS_NAMED)..];
    let more = edits.len() - shown.len();
    let mut text = if settings == "same settings" {
        String::new()
    } else {
        format!("{settings}; ")
    };
    if more > 0 {
        text.push_str(&format!("{more} edits, then "));
    }
    text.push_str(&shown.join(", "));
    text
}

/// Above the images in compare mode: the layout, B as an image, what each
/// side is, and the difference view's gain and legend.
pub(crate) fn header(ui: &mut Ui, comparison: &mut Comparison, a: &Side, b: &Side) {
    ui.horizontal(|ui| {
        for layout in CompareLayout::ALL {
            ui.selectable_value(&mut comparison.layout, layout, layout.label());
        }
        if comparison.layout == CompareLayout::Flip {
            ui.weak("hold X to see B");
        }
    });
    reference_controls(ui, comparison, a.controls.encoding());
    if comparison.reference().is_none() {
        match_controls(ui, comparison);
    }
    if let Some((label_a, label_b)) = labels(comparison, a, b) {
        ui.horizontal_wrapped(|ui| {
            ui.label(RichText::new(label_a).strong());
            ui.label("·");
            ui.label(RichText::new(label_b).strong());
        });
    }
    if comparison.layout == CompareLayout::Difference {
        difference_controls(ui, comparison);
    }
}

/// "Compare with image..." and, once B is an image, its fit and the way
/// back to a render; `encoding` is A's, for EXR files.
fn reference_controls(ui: &mut Ui, comparison: &mut Comparison, encoding: Encoding) {
    ui.horizontal(|ui| {
        let button = file_button(
            ui,
            !comparison.is_picking(),
            egui::Button::new("Compare with image..."),
        )
        .on_hover_text(
            "B shows a PNG, JPEG or EXR (another renderer's output) instead of a render",
        );
        if button.clicked() {
            comparison.pick_reference(encoding, ui.ctx());
        }
        if let Some(reference) = comparison.reference() {
            let mut fit = reference.fit;
            let hint = "Resize the image to the render's size instead of refusing a mismatch";
            if ui
                .checkbox(&mut fit, "Fit to A's size")
                .on_hover_text(hint)
                .changed()
            {
                comparison.set_fit(fit);
            }
            if ui.button("Render B again").clicked() {
                comparison.set_reference(None);
            }
        }
    });
    if let Some(error) = &comparison.picking_error {
        ui.colored_label(Color32::LIGHT_RED, error);
    }
}

/// B adaptive at A's cost: off, equal samples or equal time.
fn match_controls(ui: &mut Ui, comparison: &mut Comparison) {
    ui.horizontal(|ui| {
        ui.label("B adaptive at A's cost").on_hover_text(
            "B switches to adaptive sampling and renders once A is done, stopping when \
                 its samples reach A's total or when it has rendered as long as A did; its \
                 threshold still stops it sooner where the image is smooth enough",
        );
        let choice = &mut comparison.b_matches;
        ui.selectable_value(choice, None, "off");
        ui.selectable_value(choice, Some(Match::Samples), "equal samples");
        ui.selectable_value(choice, Some(Match::Time), "equal time");
    });
}

/// The numbers of both sides and their difference.
pub(crate) fn numbers(ui: &mut Ui, comparison: &Comparison, a: &Side, b: &Side) {
    let labels = labels(comparison, a, b).unwrap_or_default();
    let a = a.image.shown();
    // An image has no time or rays.
    let b = b.image.shown().filter(|_| comparison.reference().is_none());
    egui::Grid::new("compare_numbers")
        .num_columns(3)
        .striped(true)
        .show(ui, |ui| {
            ui.label("");
            ui.strong("A");
            ui.strong("B");
            ui.end_row();
            let row = |ui: &mut Ui, name: &str, f: &dyn Fn(&Snapshot) -> String| {
                ui.label(name);
                ui.monospace(a.map_or_else(|| "–".into(), f));
                ui.monospace(b.map_or_else(|| "–".into(), f));
                ui.end_row();
            };
            row(ui, "Time", &|s| {
                format!("{:.3} s", s.stats.render_time.as_secs_f64())
            });
            row(ui, "Samples", &|s| {
                format!("{} / {}", s.stats.passes_done, s.stats.passes_target)
            });
            row(ui, "Mean spp", &|s| {
                let pixels = u64::from(s.stats.width) * u64::from(s.stats.height);
                format!(
                    "{:.2}",
                    s.stats.samples_taken() as f64 / pixels.max(1) as f64
                )
            });
            row(ui, "Rays", &|s| {
                crate::describe::si(s.stats.counters.total_rays() as f64)
            });
            row(ui, "Rays per second", &|s| {
                crate::describe::si(s.stats.rays_per_second())
            });
        });
    if let (Some(a), Some(b)) = (a, b) {
        let ratio = a.stats.render_time.as_secs_f64() / b.stats.render_time.as_secs_f64().max(1e-9);
        ui.label(format!(
            "Speed ratio A/B: {ratio:.2} (above 1: B is faster)"
        ));
    }
    ui.label(RichText::new(&labels.0).small());
    ui.label(RichText::new(&labels.1).small());
    ui.separator();
    if let Some((view, d)) = comparison.value_difference() {
        value_stats(ui, view, &d.stats);
        return;
    }
    match comparison.metrics() {
        Some(Ok(m)) => {
            egui::Grid::new("compare_metrics")
                .num_columns(2)
                .show(ui, |ui| {
                    ui.label("MSE");
                    ui.monospace(format!("{:.3}", m.mse));
                    ui.end_row();
                    ui.label("PSNR");
                    ui.monospace(if m.psnr.is_finite() {
                        format!("{:.2} dB", m.psnr)
                    } else {
                        "∞ (identical)".into()
                    });
                    ui.end_row();
                    ui.label("FLIP");
                    ui.monospace(format!("{:.4}", m.flip));
                    ui.end_row();
                });
        }
        Some(Err(e)) => {
            ui.colored_label(Color32::LIGHT_RED, e);
        }
        None if comparison.is_measuring() => {
            ui.label("Measuring the difference…");
        }
        None => {
            ui.weak("MSE, PSNR and FLIP once both renders are done");
        }
    }
}

/// The view's statistics of both sides, in place of the image metrics.
fn value_stats(ui: &mut Ui, view: View, s: &ValueStats) {
    let unit = view.unit();
    let number = |v: f32| format!("{} {unit}", format_number(v));
    egui::Grid::new("compare_values")
        .num_columns(2)
        .show(ui, |ui| {
            let mut row = |name: &str, value: String| {
                ui.label(name);
                ui.monospace(value);
                ui.end_row();
            };
            row(&format!("Mean A ({})", view.name()), number(s.mean_a));
            row(&format!("Mean B ({})", view.name()), number(s.mean_b));
            row("Ratio A/B", format!("{:.3}", s.ratio));
            row("Mean |A − B|", number(s.mean_abs_difference));
            row("Max |A − B|", number(s.max_abs_difference));
        });
    ui.weak(format!(
        "over the {} pixels where both sides have a value",
        s.pixels
    ));
}

/// Under the difference view: the diverging legend of the values'
/// difference with its numbers, or the images' amplification and legend.
fn difference_controls(ui: &mut Ui, comparison: &mut Comparison) {
    if let Some((view, d)) = comparison.value_difference() {
        let top = format!("{} {}", format_number(d.scale), view.unit());
        ui.horizontal(|ui| {
            ui.label(format!("−{top}"));
            colour_bar(ui, 160.0, 32, |t| diverging_colour(2.0 * t - 1.0));
            ui.label(format!("+{top}"));
            ui.weak("A − B: red where A is higher, blue where B is")
                .on_hover_text(format!(
                    "The difference of the {} values per pixel; the bar's ends are the \
                     99th percentile of |A − B|, larger differences take the end colours",
                    view.name()
                ));
        });
        return;
    }
    ui.horizontal(|ui| {
        ui.add(
            egui::Slider::new(&mut comparison.gain, 1.0..=64.0)
                .logarithmic(true)
                .text("Amplification"),
        )
        .on_hover_text("Multiplies |A - B| before colouring, so small differences show");
        legend(ui, comparison.gain);
    });
}

/// A colour bar from 0 to `1 / gain` of the full range, for the difference
/// view.
fn legend(ui: &mut Ui, gain: f32) {
    ui.label("0");
    colour_bar(ui, 160.0, 32, |t| Palette::Heat.colour(t).0);
    ui.label(format!("{:.0}+ levels", 255.0 / gain.max(1e-3)));
}
