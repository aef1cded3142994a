//! The benchmark matrix in the window: the course report's timing table
//! (every structure x shadows x sampling) on the current scene and camera,
//! run on a thread of its own, filling a table with a thumbnail per row and
//! a bar chart as results come in; cancellable; exported as Markdown, CSV
//! and images.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::Sender;

use egui::{TextureHandle, Ui};
use egui_plot::{Bar, BarChart, Plot};
use tracer::accel::AccelKind;
use tracer::render::{Encoding, RenderSettings};
use tracer::world::World;

use crate::image_file::save_png;
use crate::measure::benchmark::{self, Case, Event, Measurement, RunOptions};
use crate::reports::bench_table::{self, Columns, Format};
use crate::reports::render_stats::si;

use super::background::{self, Background};

/// Side of the thumbnails in the table, in pixels.
const THUMBNAIL: u32 = 64;

/// What the benchmark thread tells the window.
enum Update {
    Progress {
        case: usize,
        run: usize,
        fraction: f32,
    },
    Measured(Box<Measurement>),
    Finished(Result<bool, String>),
}

/// A finished row: its measurement and thumbnail.
struct Row {
    measurement: Measurement,
    thumbnail: TextureHandle,
}

/// The window's state.
pub struct BenchWindow {
    pub open: bool,
    /// Frames per configuration.
    runs: usize,
    cases: Vec<Case>,
    rows: Vec<Row>,
    progress: Option<(usize, usize, f32)>,
    task: Option<Background<Update>>,
    message: Option<String>,
    /// Where the last export went.
    exported: background::Export,
}

impl Default for BenchWindow {
    fn default() -> Self {
        Self {
            open: false,
            runs: 3,
            cases: Vec::new(),
            rows: Vec::new(),
            progress: None,
            task: None,
            message: None,
            exported: background::Export::default(),
        }
    }
}

impl BenchWindow {
    pub fn is_running(&self) -> bool {
        self.task.is_some()
    }

    /// The finished rows' measurements, in matrix order.
    pub fn measurements(&self) -> impl Iterator<Item = &Measurement> {
        self.rows.iter().map(|r| &r.measurement)
    }

    /// Starts the matrix over `world` with `base` settings (the current
    /// scene, camera and sizes; N is the course report's 4); `wake` asks
    /// the window to redraw.
    pub fn start(
        &mut self,
        world: Arc<World>,
        base: &RenderSettings,
        wake: impl Fn() + Send + 'static,
    ) {
        self.stop();
        let base = RenderSettings {
            samples: benchmark::MATRIX_SAMPLES,
            ..base.clone()
        };
        self.cases = benchmark::matrix(&base, &AccelKind::ALL, Encoding::Srgb);
        self.rows.clear();
        self.message = None;
        let cases = self.cases.clone();
        let options = RunOptions {
            runs: self.runs,
            threads: None,
        };
        let spawned = Background::spawn("benchmark", move |cancel, tx| {
            run(&world, &cases, options, cancel, tx, &wake)
        });
        match spawned {
            Ok(task) => self.task = Some(task),
            Err(e) => self.message = Some(format!("cannot start the benchmark: {e}")),
        }
    }

    /// Cancels a running matrix; the finished rows stay.
    pub fn stop(&mut self) {
        if let Some(task) = &self.task {
            task.cancel();
        }
    }

    /// Takes the thread's updates; call once per frame.
    pub fn receive(&mut self, ctx: &egui::Context) {
        while let Some(update) = self.task.as_ref().and_then(Background::try_recv) {
            match update {
                Update::Progress {
                    case,
                    run,
                    fraction,
                } => self.progress = Some((case, run, fraction)),
                Update::Measured(measurement) => {
                    let thumbnail = background::thumbnail(
                        ctx,
                        &measurement.image,
                        THUMBNAIL,
                        format!("bench {}", measurement.case.file_stem()),
                    );
                    self.rows.push(Row {
                        measurement: *measurement,
                        thumbnail,
                    });
                }
                Update::Finished(result) => {
                    self.message = Some(match result {
                        Ok(false) => format!("{} configurations measured", self.rows.len()),
                        Ok(true) => format!("cancelled after {} configurations", self.rows.len()),
                        Err(e) => e,
                    });
                    self.task = None;
                    self.progress = None;
                }
            }
        }
        if let Some(message) = self.exported.finished() {
            self.message = Some(message);
        }
    }

    /// Draws the window; `start` is called when the user asks for a run.
    pub fn show(&mut self, ctx: &egui::Context, scene_name: &str, start: &mut bool) {
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
            if self.is_running() {
                if ui.button("Cancel").clicked() {
                    self.stop();
                }
            } else if ui.button("Run").clicked() {
                *start = true;
            }
            if !self.rows.is_empty() && !self.is_running() && ui.button("Export...").clicked() {
                self.export(scene_name);
            }
        });
        if let Some((case, run, fraction)) = self.progress {
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
        if let Some(message) = &self.message {
            ui.label(message);
        }
        if self.rows.is_empty() {
            return;
        }
        let bars: Vec<Bar> = self
            .rows
            .iter()
            .enumerate()
            .map(|(i, r)| {
                Bar::new(i as f64, r.measurement.median().as_secs_f64() * 1e3)
                    .name(&r.measurement.case.label)
            })
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
                    for row in &self.rows {
                        let m = &row.measurement;
                        let [w, h] = row.thumbnail.size();
                        let fit = 48.0 / w.max(h).max(1) as f32;
                        ui.image((
                            row.thumbnail.id(),
                            egui::vec2(w as f32 * fit, h as f32 * fit),
                        ));
                        ui.label(&m.case.label);
                        ui.monospace(format!("{:.1} ms", m.median().as_secs_f64() * 1e3));
                        ui.monospace(format!(
                            "{:.1}..{:.1}",
                            m.min().as_secs_f64() * 1e3,
                            m.max().as_secs_f64() * 1e3
                        ));
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
        self.exported.start("Export the benchmark to", move |dir| {
            write_export(&dir.join(format!("bench-{stem}")), &measurements)
        });
    }
}

/// The table as `table.md` and `table.csv` and each image as PNG in `dir`.
pub fn write_export(dir: &Path, measurements: &[Measurement]) -> anyhow::Result<PathBuf> {
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

/// Runs the matrix, forwarding progress (at most one message per case and
/// run fraction step) and results.
fn run(
    world: &Arc<World>,
    cases: &[Case],
    options: RunOptions,
    cancel: &AtomicBool,
    tx: &Sender<Update>,
    wake: &dyn Fn(),
) {
    let mut on_event = |event: Event| {
        let update = match event {
            Event::Rendering {
                case,
                run,
                fraction,
            } => Update::Progress {
                case,
                run,
                fraction,
            },
            Event::Measured { measurement, .. } => Update::Measured(Box::new(measurement.clone())),
        };
        let _ = tx.send(update);
        wake();
    };
    let result = benchmark::run(world, cases, options, cancel, &mut on_event)
        .map(|outcome| outcome.cancelled)
        .map_err(|e| format!("{e:#}"));
    let _ = tx.send(Update::Finished(result));
    wake();
}
