//! The statistics panel: live numbers from the renderer and a plot of time
//! and speed per pass.

use egui::Ui;
use egui_plot::{Legend, Line, Plot, PlotPoints};
use tracer::accel::AccelInfo;
use tracer::stats::{RenderStats, SceneCounts};

use crate::describe::{millis, si};

use crate::gui::comparison::Comparison;
use crate::gui::platform::frame_meter::FrameMeter;
use crate::gui::platform::target;
use crate::gui::sides::Sides;

/// Everything the panel shows.
pub(crate) struct StatsView<'a> {
    pub(crate) stats: &'a RenderStats,
    pub(crate) counts: &'a SceneCounts,
    pub(crate) accel: Option<&'a AccelInfo>,
    pub(crate) load_time: std::time::Duration,
    /// The window's own frame rate and work per frame.
    pub(crate) frame_meter: &'a FrameMeter,
}

/// The statistics panel: compare mode's numbers of both sides, then side
/// A's statistics.
pub(crate) fn panel(ui: &mut Ui, sides: &Sides, comparison: &Comparison, frame_meter: &FrameMeter) {
    if let Some(b) = &sides.b {
        ui.heading("Comparison");
        super::comparison::numbers(ui, comparison, &sides.a, b);
        ui.separator();
    }
    let a = &sides.a;
    match (a.image.shown(), a.engine.scene()) {
        (Some(shown), Some(scene)) => {
            let accel = a.engine.accel_info();
            show(
                ui,
                &StatsView {
                    stats: &shown.stats,
                    counts: &scene.world.counts,
                    accel: accel.as_ref(),
                    load_time: scene.load_time,
                    frame_meter,
                },
            );
        }
        _ => {
            ui.heading("Statistics");
            ui.label("Nothing rendered yet.");
        }
    }
}

fn row(ui: &mut Ui, name: &str, value: String) -> egui::Response {
    let response = ui.label(name);
    ui.monospace(value);
    ui.end_row();
    response
}

pub(crate) fn show(ui: &mut Ui, view: &StatsView) {
    let s = view.stats;
    let c = &s.counters;
    ui.heading("Statistics");
    egui::Grid::new("stats")
        .num_columns(2)
        .striped(true)
        .show(ui, |ui| {
            row(ui, "Resolution", format!("{} x {}", s.width, s.height));
            if let Some(on) = target::rendered_on(s) {
                // Its short form in the grid, which a long value would
                // widen past the image's room; the whole on hover.
                let short = on.split(" (").next().unwrap_or(&on).to_string();
                row(ui, "Rendered on", short).on_hover_text(on);
            }
            match &s.adaptive {
                None => {
                    row(
                        ui,
                        "Samples per pixel",
                        format!("{} / {}", s.passes_done, s.passes_target),
                    );
                }
                Some(a) => {
                    row(
                        ui,
                        "Passes",
                        format!("{} / at most {}", s.passes_done, s.passes_target),
                    );
                    row(
                        ui,
                        "Samples per pixel",
                        format!("{:.1} mean, {} max", a.mean_spp(), a.max_spp),
                    );
                    row(
                        ui,
                        "Pixels done",
                        format!("{:.1}%", 100.0 * (1.0 - a.active_share())),
                    )
                    .on_hover_text(
                        "Pixels that stopped: their estimated error, pooled with their \
                         neighbours', is below the noise threshold times their samples over the \
                         minimum times what their samples cost, or they reached the maximum",
                    );
                    row(
                        ui,
                        "Estimated error",
                        if a.error.is_finite() {
                            format!("{:.4} ({:.1} levels)", a.error, a.error * 255.0)
                        } else {
                            "-".into()
                        },
                    )
                    .on_hover_text(
                        "RMS of the pixels' standard errors, in display units: about the RMS \
                         distance to the converged image",
                    );
                }
            }
            row(
                ui,
                "Render time",
                format!("{:.3} s", s.render_time.as_secs_f64()),
            );
            // Rows and plots are there from the first frame of a render
            // on: a widget that appears mid-render makes egui lay the
            // window out again, two more frames that take the render's CPU
            // on a software rasterizer.
            row(
                ui,
                "Last pass",
                s.pass_times
                    .last()
                    .map_or("-".into(), |last| format!("{:.1} ms", millis(*last))),
            );
            row(ui, "Rays", si(c.total_rays() as f64));
            row(ui, "  eye", si(c.eye_rays as f64));
            row(ui, "  shadow", si(c.shadow_rays as f64));
            row(ui, "  reflection", si(c.reflection_rays as f64));
            row(ui, "  refraction", si(c.refraction_rays as f64));
            row(ui, "Rays per second", si(s.rays_per_second()));
            row(ui, "Intersection tests", si(c.intersection_tests as f64));
            row(
                ui,
                "Tests per ray",
                format!(
                    "{:.2}",
                    c.intersection_tests as f64 / c.total_rays().max(1) as f64
                ),
            );
            if let Some(a) = view.accel {
                row(ui, "Acceleration", format!("{:?}", a.kind).to_lowercase());
                row(
                    ui,
                    "  build time",
                    format!("{:.1} ms", millis(a.build_time)),
                );
                row(ui, "  memory", format!("{}B", si(a.memory_bytes as f64)));
                if let Some(nodes) = a.bvh_nodes {
                    row(ui, "  BVH nodes", nodes.to_string());
                }
                if let Some(g) = &a.grid {
                    row(
                        ui,
                        "  grid cells",
                        format!("{} x {} x {}", g.cells[0], g.cells[1], g.cells[2]),
                    );
                    row(ui, "  empty cells", si(g.empty_cells as f64));
                    row(ui, "  references", si(g.references as f64));
                    row(
                        ui,
                        "  per non-empty cell",
                        format!("{:.2}", g.mean_per_cell),
                    );
                }
                row(
                    ui,
                    "  nodes per ray",
                    format!(
                        "{:.2}",
                        c.nodes_visited as f64 / c.total_rays().max(1) as f64
                    ),
                );
            }
            // One row per kind: a long list would widen the panel.
            row(ui, "Objects", view.counts.objects().to_string());
            for (kind, n) in &view.counts.objects_by_kind {
                row(ui, &format!("  {kind}"), n.to_string());
            }
            row(ui, "Primitives", view.counts.primitives.to_string());
            row(ui, "Lights", view.counts.lights.to_string());
            row(
                ui,
                "Scene load",
                format!("{:.1} ms", millis(view.load_time)),
            );
            row(
                ui,
                "UI frames per second",
                view.frame_meter.frames_per_second().to_string(),
            );
            row(
                ui,
                "UI work per frame",
                format!("{:.1} ms", view.frame_meter.work_per_frame() * 1e3),
            );
            row(
                ui,
                "UI CPU per frame",
                format!("{:.1} ms", millis(view.frame_meter.frame_cost())),
            )
            .on_hover_text(
                "CPU time a frame costs on every thread but the render's: the UI's work and \
                 painting, including a software rasterizer's threads",
            );
            // Short values: a wider column would widen the panel and move
            // the image while it renders.
            row(
                ui,
                "Redraw interval",
                format!("{:.0} ms", millis(view.frame_meter.progress_interval())),
            )
            .on_hover_text(
                "How often a render's progress redraws the window: progress redraws take at \
                 most a tenth of the CPU the render gets",
            );
        });

    ui.separator();
    let times = s.pass_times.iter().copied().map(millis).collect();
    pass_plot(ui, "pass_times", "ms per pass", times);
    let rays = s
        .pass_times
        .iter()
        .zip(&s.pass_rays)
        .map(|(t, n)| *n as f64 / t.as_secs_f64().max(1e-9) / 1e6)
        .collect();
    pass_plot(ui, "pass_rays", "Mrays/s", rays);
}

/// A plot of one value per completed pass (pass 1 first).
fn pass_plot(ui: &mut Ui, id: &str, name: &str, values: Vec<f64>) {
    let points: PlotPoints = values
        .into_iter()
        .enumerate()
        .map(|(i, v)| [i as f64 + 1.0, v])
        .collect();
    Plot::new(id)
        .height(120.0)
        .legend(Legend::default())
        .x_axis_label("pass")
        .allow_scroll(false)
        .show(ui, |plot| {
            plot.line(Line::new(name, points));
        });
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::*;

    /// The height the panel takes for `stats`, laid out in a bare context.
    fn panel_height(stats: &RenderStats) -> f32 {
        let ctx = egui::Context::default();
        let counts = SceneCounts::default();
        let meter = FrameMeter::default();
        let view = StatsView {
            stats,
            counts: &counts,
            accel: None,
            load_time: Duration::ZERO,
            frame_meter: &meter,
        };
        let mut height = 0.0;
        // Two passes: the first one measures text, the second lays it out.
        for _ in 0..2 {
            let mut output = ctx.run_ui(egui::RawInput::default(), |ui| {
                show(ui, &view);
                height = ui.min_rect().height();
            });
            // Nothing is painted: the font atlas is never uploaded.
            output.textures_delta.clear();
        }
        height
    }

    #[test]
    fn the_panel_keeps_its_layout_while_passes_complete() {
        let before = RenderStats {
            passes_target: 16,
            ..RenderStats::default()
        };
        let during = RenderStats {
            passes_done: 3,
            pass_times: vec![Duration::from_millis(90); 3],
            pass_rays: vec![1_000_000; 3],
            render_time: Duration::from_millis(270),
            ..before.clone()
        };
        assert_eq!(panel_height(&before), panel_height(&during));
    }
}
