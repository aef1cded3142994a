//! The benchmark matrix in the window: the course report's timing table
//! (every structure x shadows x sampling) on the current scene and camera,
//! run on a thread of its own, filling a table with a thumbnail per row and
//! a bar chart as results come in; cancellable; exported as Markdown, CSV
//! and images.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use egui::Ui;
use egui_plot::{Bar, BarChart, Plot};
use tracer::accel::AccelKind;
use tracer::render::{Encoding, RenderSettings};
use tracer::world::World;

use crate::describe::{millis, si};
use crate::image_file::save_png;
use crate::measure::benchmark::{self, Case, Event, Measurement, RunOptions};
use crate::reports::bench_table::{self, Columns, Format};

use super::background::Measuring;

/// Side of the thumbnails in the table, in pixels.
const THUMBNAIL: u32 = 64;

/// How far the matrix is: case, run and the fraction of that run done.
type MatrixProgress = (usize, usize, f32);

type Update = super::background::Update<MatrixProgress, Measurement>;

/// The window's state.
pub struct BenchWindow {
    pub(crate) open: bool,
    /// Frames per configuration.
    runs: usize,
    cases: Vec<Case>,
    /// The run and its finished rows.
    measuring: Measuring<MatrixProgress, Measurement>,
}

impl Default for BenchWindow {
    fn default() -> Self {
        Self {
            open: false,
            runs: 3,
            cases: Vec::new(),
            measuring: Measuring::default(),
        }
    }
}

impl BenchWindow {
    pub fn is_running(&self) -> bool {
        self.measuring.is_running()
    }

    /// The finished rows' measurements, in matrix order.
    pub fn measurements(&self) -> impl Iterator<Item = &Measurement> {
        self.measuring.rows.iter().map(|r| &r.measured)
    }

    /// Starts the matrix over `world` with `base` settings (the current
    /// scene, camera and sizes; N is the course report's 4); `wake` asks
    /// the window to redraw.
    pub(crate) fn start(
        &mut self,
        world: Arc<World>,
        base: &RenderSettings,
        wake: impl Fn() + Send + 'static,
    ) {
        let base = RenderSettings {
            samples: benchmark::MATRIX_SAMPLES,
            ..base.clone()
        };
        self.cases = benchmark::matrix(&base, &world.view, &AccelKind::ALL, Encoding::Srgb);
        let cases = self.cases.clone();
        let options = RunOptions {
            runs: self.runs,
            threads: None,
        };
        self.measuring
            .start("benchmark", wake, move |cancel, send| {
                run(&world, &cases, options, cancel, send)
            });
    }

    /// Takes the thread's updates; call once per frame.
    pub(crate) fn receive(&mut self, ctx: &egui::Context) {
        self.measuring.receive(
            ctx,
            THUMBNAIL,
            |m, _| (&m.image, format!("bench {}", m.case.file_stem())),
            |cancelled, rows| match cancelled {
                false => format!("{rows} configurations measured"),
                true => format!("cancelled after {rows} configurations"),
            },
        );
    }

    /// Draws the window; `start` is called when the user asks for a run.
    pub(crate) fn show(&mut self, ctx: &egui::Context, scene_name: &str, start: &mut bool) {
        let mut open = self.open;
        egui::Window::new("Benchmark matrix")
            .open(&mut open)
            .default_size([620.0, 560.0])
            .show(ctx, |ui| self.contents(ui, scene_name, start));
        self.open = open;
    }

    fn contents(&mut self, ui: &mut Ui, scene_name: &str, start: &mut bool) {
        ui.label(format!(
            "The course report's timing table (its Figure 5.1) on {scene_name}: none / grid / BVH x hard / soft \
             shadows x one sample / AA 4x4 / AA 4x4 with depth of field, at the current \
             camera and size."
        ));
        ui.horizontal(|ui| {
            ui.add_enabled(
                !self.is_running(),
                egui::Slider::new(&mut self.runs, 1..=9).text("runs each"),
            )
            .on_hover_text("Frames per configuration: the table shows their median and spread");
            if self.measuring.buttons(ui, start) {
                self.export(scene_name);
            }
        });
        if let Some((case, run, fraction)) = self.measuring.progress {
            let total = self.cases.len().max(1);
            let done = (case as f32 + (run as f32 + fraction) / self.runs as f32) / total as f32;
            ui.add(egui::ProgressBar::new(done).text(format!(
                "{} ({}/{}), run {}/{}",
                self.cases.get(case).map_or("", |c| c.label.as_str()),
                case + 1,
                total,
                run + 1,
                self.runs
            )));
        }
        if let Some(message) = &self.measuring.message {
            ui.label(message);
        }
        if self.measuring.rows.is_empty() {
            return;
        }
        let bars: Vec<Bar> = self
            .measurements()
            .enumerate()
            .map(|(i, m)| Bar::new(i as f64, millis(m.median())).name(&m.case.label))
            .collect();
        Plot::new("bench_bars")
            .height(140.0)
            .y_axis_label("ms (median)")
            .allow_scroll(false)
            .show(ui, |plot| plot.bar_chart(BarChart::new("frame time", bars)));
        egui::ScrollArea::vertical().show(ui, |ui| {
            egui::Grid::new("bench_rows")
                .num_columns(5)
                .striped(true)
                .show(ui, |ui| {
                    for header in ["", "configuration", "median", "spread", "rays/s"] {
                        ui.strong(header);
                    }
                    ui.end_row();
                    for row in &self.measuring.rows {
                        let m = &row.measured;
                        row.show_thumbnail(ui, 48.0);
                        ui.label(&m.case.label);
                        ui.monospace(format!("{:.1} ms", millis(m.median())));
                        ui.monospace(format!("{:.1}..{:.1}", millis(m.min()), millis(m.max())));
                        ui.monospace(si(m.rays_per_second()));
                        ui.end_row();
                    }
                });
        });
    }

    /// Writes the table (Markdown and CSV) and every image into a folder
    /// the user picks, off the UI thread.
    fn export(&mut self, scene_name: &str) {
        let measurements: Vec<Measurement> = self.measurements().cloned().collect();
        let stem = Path::new(scene_name)
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        self.measuring
            .export("Export the benchmark to", move |dir| {
                write_export(&dir.join(format!("bench-{stem}")), &measurements)
            });
    }
}

/// The table as `table.md` and `table.csv` and each image as PNG in `dir`.
pub(crate) fn write_export(dir: &Path, measurements: &[Measurement]) -> anyhow::Result<PathBuf> {
    use anyhow::Context;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for (name, format) in [("table.md", Format::Markdown), ("table.csv", Format::Csv)] {
        let path = dir.join(name);
        std::fs::write(
            &path,
            bench_table::table(measurements, Columns::Matrix, format),
        )
        .with_context(|| format!("cannot write {}", path.display()))?;
    }
    for m in measurements {
        save_png(&m.image, &dir.join(format!("{}.png", m.case.file_stem())))?;
    }
    Ok(dir.to_path_buf())
}

/// Runs the matrix, sending its progress and results.
fn run(
    world: &Arc<World>,
    cases: &[Case],
    options: RunOptions,
    cancel: &AtomicBool,
    send: &dyn Fn(Update),
) -> anyhow::Result<bool> {
    let mut on_event = |event: Event| {
        send(match event {
            Event::Rendering {
                case,
                run,
                fraction,
            } => Update::Progress((case, run, fraction)),
            Event::Measured { measurement, .. } => Update::Measured(Box::new(measurement.clone())),
        })
    };
    benchmark::run(world, cases, options, cancel, &mut on_event).map(|outcome| outcome.cancelled)
}
