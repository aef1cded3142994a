//! The Studies window's results: the chart (log axes where the values
//! span decades, the best point ringed, a point's numbers and image on
//! hover) and the table with an Apply button per row.

use egui::{Color32, TextureHandle, Ui};
use egui_plot::{Line, MarkerShape, Plot, PlotPoint, Points};

use crate::figures::study_plot;
use crate::measure::study::{Param, Point, analysis, values};
use crate::reports::study_table;

use super::StudiesWindow;

/// How close (screen points) the pointer must be to a point to pick it.
const PICK_RADIUS: f32 = 14.0;

impl StudiesWindow {
    /// The chart; returns the point clicked. Log axes plot log10 values
    /// with ticks labelled in plain numbers.
    pub(super) fn chart(
        &self,
        ui: &mut Ui,
        param: Param,
        points: &[Point],
        error_view: bool,
    ) -> Option<usize> {
        let (log_x, log_y) = if error_view {
            (false, true)
        } else {
            study_plot::log_axes(param, points)
        };
        let axis = |log: bool, v: f64| if log { v.max(1e-12).log10() } else { v };
        let at = |p: &Point| -> [f64; 2] {
            match (error_view, p.error) {
                (true, Some(e)) => [axis(log_x, p.frame_ms()), axis(log_y, e.mse)],
                _ => [axis(log_x, p.x), axis(log_y, p.frame_ms())],
            }
        };
        let label = |log: bool| {
            move |mark: egui_plot::GridMark, _: &std::ops::RangeInclusive<f64>| {
                let v = if log {
                    10f64.powf(mark.value)
                } else {
                    mark.value
                };
                values::format(format!("{v:.3}").parse().unwrap_or(v))
            }
        };
        let (x_label, y_label) = if error_view {
            ("frame time (ms)", "MSE")
        } else {
            (param.axis(), "frame time (ms)")
        };
        let best = analysis::best(param, points);
        let response = Plot::new("study_chart")
            .height(220.0)
            .x_axis_label(x_label)
            .y_axis_label(y_label)
            .x_axis_formatter(label(log_x))
            .y_axis_formatter(label(log_y))
            .allow_drag(false)
            .allow_zoom(false)
            .allow_scroll(false)
            .allow_boxed_zoom(false)
            .legend(egui_plot::Legend::default().position(egui_plot::Corner::LeftTop))
            .show(ui, |plot_ui| {
                for accel in analysis::structures(points) {
                    let [r, g, b] = study_plot::colour(accel);
                    let colour = Color32::from_rgb(r, g, b);
                    let mut series: Vec<[f64; 2]> = analysis::series(points, accel)
                        .into_iter()
                        .filter(|p| !error_view || p.error.is_some())
                        .map(at)
                        .collect();
                    series.sort_by(|a, b| a[0].total_cmp(&b[0]));
                    plot_ui.line(Line::new(accel.name(), series.clone()).color(colour));
                    plot_ui.points(Points::new(accel.name(), series).radius(3.5).color(colour));
                }
                for &(i, _) in &best {
                    let [r, g, b] = study_plot::colour(points[i].accel());
                    plot_ui.points(
                        // Unnamed: ringed in its line's colour, not in the legend.
                        Points::new("", vec![at(&points[i])])
                            .shape(MarkerShape::Circle)
                            .filled(false)
                            .radius(9.0)
                            .color(Color32::from_rgb(r, g, b)),
                    );
                }
            });
        let pointer = response.response.hover_pos()?;
        let (nearest, distance) = points
            .iter()
            .enumerate()
            .filter(|(_, p)| !error_view || p.error.is_some())
            .map(|(i, p)| {
                let [x, y] = at(p);
                let screen = response
                    .transform
                    .position_from_point(&PlotPoint::new(x, y));
                (i, screen.distance(pointer))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        if distance > PICK_RADIUS {
            return None;
        }
        let clicked = response.response.clicked();
        let row = &self.measuring.rows[nearest];
        // Shown at once while the pointer is on a point (not after the
        // usual tooltip delay): the point was picked on purpose.
        egui::Tooltip::for_widget(&response.response)
            .at_pointer()
            .gap(12.0)
            .show(|ui| {
                point_details(ui, param, points, nearest, &row.thumbnail);
                ui.weak("click to show it in the main view");
            });
        clicked.then_some(nearest)
    }

    /// The table under the chart, as the command line prints it, with a
    /// thumbnail and an Apply button per row; returns the row applied.
    pub(super) fn table(&self, ui: &mut Ui, param: Param, points: &[Point]) -> Option<usize> {
        let (headers, cells) = study_table::rows(param, points);
        let mut applied = None;
        egui::ScrollArea::both().show(ui, |ui| {
            egui::Grid::new("study_rows")
                .num_columns(headers.len() + 2)
                .striped(true)
                .show(ui, |ui| {
                    ui.label("");
                    ui.label("");
                    for header in &headers {
                        ui.strong(header);
                    }
                    ui.end_row();
                    for (i, (row, cells)) in self.measuring.rows.iter().zip(&cells).enumerate() {
                        row.show_thumbnail(ui, 32.0);
                        if ui
                            .button("Apply")
                            .on_hover_text("Show this point's settings in the main view")
                            .clicked()
                        {
                            applied = Some(i);
                        }
                        for cell in cells {
                            ui.monospace(cell);
                        }
                        ui.end_row();
                    }
                });
        });
        applied
    }
}

/// A point's numbers (the table's row, one per line) and its image.
fn point_details(ui: &mut Ui, param: Param, points: &[Point], i: usize, image: &TextureHandle) {
    let (headers, cells) = study_table::rows(param, points);
    egui::Grid::new("study_point")
        .num_columns(2)
        .show(ui, |ui| {
            for (header, cell) in headers.iter().zip(&cells[i]) {
                ui.label(header);
                ui.monospace(cell);
                ui.end_row();
            }
        });
    ui.image(image);
}
