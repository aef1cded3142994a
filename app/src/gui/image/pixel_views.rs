//! The window's views: which per-pixel quantity the image shows (the
//! selector and the key that cycles it), the heat map's scale shared by
//! both sides of a comparison, the legend with its numbers, and the view's
//! summary (mean, median, p99, max).

use std::time::Duration;

use web_time::Instant;

use egui::{Color32, Ui};
use tracer::render::{HEAT_PALETTE, HeatScale, View, ViewHeatmap, ViewSummary};

use crate::figures::heat_map::format_number;
use crate::gui::sides::{Engine, Version};

/// What the user chose, and the scale fitted to what the engines measured.
#[derive(Debug, Clone, Default)]
pub struct PixelViews {
    pub view: View,
    pub scale: HeatScale,
    pub(crate) log: bool,
    /// Fitted over both sides; refitted when an image or the choice changes.
    heat: Option<ViewHeatmap>,
    summaries: [Option<ViewSummary>; 2],
    fitted_to: Option<(Version, Option<Version>, View, ScaleKey, bool)>,
    fitted_at: Option<Instant>,
}

/// Refits of a progressing render at most this often: each one sorts
/// every pixel's value.
const REFIT_INTERVAL: Duration = Duration::from_millis(250);

/// [`HeatScale`] in a form that compares exactly (the fixed value's bits).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ScaleKey {
    Max,
    P99,
    Fixed(u32),
}

impl From<HeatScale> for ScaleKey {
    fn from(s: HeatScale) -> Self {
        match s {
            HeatScale::Max => ScaleKey::Max,
            HeatScale::P99 => ScaleKey::P99,
            HeatScale::Fixed(v) => ScaleKey::Fixed(v.to_bits()),
        }
    }
}

impl PixelViews {
    /// Whether renders must measure views: any view but the shaded image.
    pub(crate) fn measures(&self) -> bool {
        self.view != View::Shaded
    }

    /// The next view (the `V` key).
    pub(crate) fn cycle(&mut self) {
        self.view = self.view.next();
    }

    /// What the images show: `None` for the shaded image, else the view
    /// with the heat map fitted over side A and, in compare mode, side B
    /// together, so both read on one scale. Refits only when an image
    /// changed.
    pub(crate) fn fit(
        &mut self,
        ctx: &egui::Context,
        a: &Engine,
        b: Option<&Engine>,
    ) -> Option<(View, ViewHeatmap)> {
        if !self.measures() {
            return None;
        }
        let key = (
            a.version(),
            b.map(Engine::version),
            self.view,
            ScaleKey::from(self.scale),
            self.log,
        );
        let choice_changed = self
            .fitted_to
            .is_none_or(|(_, _, view, scale, log)| (view, scale, log) != (key.2, key.3, key.4));
        let due = self
            .fitted_at
            .is_none_or(|at| at.elapsed() >= REFIT_INTERVAL);
        if self.fitted_to != Some(key) && !choice_changed && !due {
            // Come back for the last images' scale once the interval is over.
            ctx.request_repaint_after(REFIT_INTERVAL);
        } else if self.fitted_to != Some(key) {
            let values: Vec<Vec<Option<f32>>> = [Some(a), b]
                .into_iter()
                .flatten()
                .filter_map(|e| e.view_values(self.view))
                .collect();
            let sides: Vec<&[Option<f32>]> = values.iter().map(Vec::as_slice).collect();
            self.heat = Some(ViewHeatmap::fit(self.scale, self.log, &sides));
            self.summaries = [0, 1].map(|i| values.get(i).and_then(|v| ViewSummary::of(v)));
            self.fitted_to = Some(key);
            self.fitted_at = Some(Instant::now());
        }
        self.heat.map(|heat| (self.view, heat))
    }

    /// The heat map the images are drawn with, once fitted.
    pub fn heat(&self) -> Option<ViewHeatmap> {
        self.heat
    }

    /// Whether the heat map and the summaries were fitted over the images
    /// the engines hold now (`b` in compare mode).
    pub fn is_fitted_to(&self, a: &Engine, b: Option<&Engine>) -> bool {
        self.fitted_to
            .is_some_and(|(va, vb, ..)| va == a.version() && vb == b.map(Engine::version))
    }

    /// The view's summary of side A (0) or B (1), once measured.
    pub fn summary(&self, side: usize) -> Option<&ViewSummary> {
        self.summaries.get(side)?.as_ref()
    }

    /// The side panel's section: the selector, the scale, the legend and
    /// the numbers.
    pub(crate) fn ui(&mut self, ui: &mut Ui, comparing: bool) {
        ui.label("View (V cycles)")
            .on_hover_text("What the image shows per pixel");
        ui.horizontal_wrapped(|ui| {
            for view in View::ALL {
                ui.selectable_value(&mut self.view, view, view.name())
                    .on_hover_text(describe(view));
            }
        });
        if !self.view.is_scalar() {
            return;
        }
        ui.horizontal(|ui| {
            ui.label("Scale");
            let fixed = match self.scale {
                HeatScale::Fixed(v) => v,
                _ => self.heat.map_or(1.0, |h| h.top),
            };
            ui.selectable_value(&mut self.scale, HeatScale::Max, "max");
            ui.selectable_value(&mut self.scale, HeatScale::P99, "p99");
            ui.selectable_value(&mut self.scale, HeatScale::Fixed(fixed), "fixed");
            ui.checkbox(&mut self.log, "log");
        });
        if let HeatScale::Fixed(v) = &mut self.scale {
            ui.add(
                egui::DragValue::new(v)
                    .range(1e-3..=1e9)
                    .speed(0.5)
                    .prefix("top "),
            );
        }
        if let Some(heat) = self.heat {
            legend(ui, &heat, self.view);
        }
        for (side, name) in [(0, "A"), (1, "B")] {
            if side == 1 && !comparing {
                break;
            }
            let line = match self.summary(side) {
                Some(s) => format!(
                    "{}mean {}, median {}, p99 {}, max {}",
                    if comparing {
                        format!("{name}: ")
                    } else {
                        String::new()
                    },
                    format_number(s.mean),
                    format_number(s.median),
                    format_number(s.p99),
                    format_number(s.max)
                ),
                None => "no value yet".to_string(),
            };
            ui.label(line);
        }
    }
}

/// A colour bar from 0 to the heat map's top, with the numbers and unit.
fn legend(ui: &mut Ui, heat: &ViewHeatmap, view: View) {
    let width = ui.available_width().min(260.0);
    colour_bar(ui, width, 64, |t| HEAT_PALETTE.colour(t).0);
    ui.horizontal(|ui| {
        ui.label("0");
        ui.label(format!(
            "..  {}{}  {}",
            format_number(heat.top),
            if heat.log { " (log)" } else { "" },
            view.unit()
        ));
    });
}

/// A horizontal bar `width` wide of `colour(t)` for `t` from 0 to 1, in
/// `steps` cells: the legends of the views and of compare's difference.
pub(crate) fn colour_bar(ui: &mut Ui, width: f32, steps: u32, colour: impl Fn(f32) -> [u8; 3]) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(width, 12.0), egui::Sense::hover());
    for i in 0..steps {
        let [r, g, b] = colour(i as f32 / (steps - 1) as f32);
        let x0 = rect.left() + rect.width() * i as f32 / steps as f32;
        let x1 = rect.left() + rect.width() * (i + 1) as f32 / steps as f32;
        let cell = egui::Rect::from_x_y_ranges(x0..=x1, rect.y_range());
        ui.painter()
            .rect_filled(cell, 0.0, Color32::from_rgb(r, g, b));
    }
}

/// A view's tooltip.
fn describe(view: View) -> &'static str {
    match view {
        View::Shaded => "The rendered image",
        View::Tests => "Intersection tests of every ray the pixel spawned",
        View::Steps => "BVH nodes visited or grid cells walked by those rays",
        View::Rays => "Rays spawned, all kinds",
        View::Shadow => "Shadow rays spawned",
        View::Blocked => "Fraction of the shadow rays that were blocked",
        View::Depth => "Deepest bounce reached",
        View::Distance => "Distance to the eye ray's hit",
        View::Normals => "The eye hit's shading normal as a colour",
        View::Objects => "A false colour per scene object",
        View::Samples => "Samples the pixel took: where adaptive sampling spent them",
    }
}

/// The readout of a scalar view's raw value under the cursor; `None`
/// while the image shows no numbers.
pub(crate) fn readout(engine: &Engine, view: View, x: u32, y: u32) -> Option<String> {
    if !view.is_scalar() {
        return None;
    }
    Some(match engine.view_value(view, x, y) {
        Some(v) => format!("{} {v:.3} ({})", view.name(), view.unit()),
        None => format!("{}: no value", view.name()),
    })
}
