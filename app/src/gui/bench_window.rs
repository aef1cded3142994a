//! The benchmark matrix in the window: the seed's timing table (every
//! structure x shadows x sampling) on the current scene and camera, run on a
//! thread of its own, filling a table with a thumbnail per row and a bar
//! chart as results come in; cancellable; exported as Markdown, CSV and
//! images.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};

use egui::{ColorImage, TextureHandle, TextureOptions, Ui};
use egui_plot::{Bar, BarChart, Plot};
use image::imageops::FilterType;
use tracer::accel::AccelKind;
use tracer::render::{Encoding, RenderSettings};
use tracer::world::World;

use crate::measure::bench_report::{self, Format, Layout};
use crate::measure::benchmark::{self, Case, Event, Measurement, RunOptions};
use crate::output::save_png;
use crate::report::si;

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
    cancel: Option<Arc<AtomicBool>>,
    updates: Option<Receiver<Update>>,
    message: Option<String>,
    /// Where the last export went.
    exported: Option<Receiver<Result<PathBuf, String>>>,
}

impl Default for BenchWindow {
    fn default() -> Self {
        Self {
            open: false,
            runs: 3,
            cases: Vec::new(),
            rows: Vec::new(),
            progress: None,
            cancel: None,
            updates: None,
            message: None,
            exported: None,
        }
    }
}

impl BenchWindow {
    pub fn is_running(&self) -> bool {
        self.updates.is_some()
    }

    /// The finished rows' measurements, in matrix order.
    pub fn measurements(&self) -> impl Iterator<Item = &Measurement> {
        self.rows.iter().map(|r| &r.measurement)
    }

    /// Starts the matrix over `world` with `base` settings (the current
    /// scene, camera and sizes; N is the seed's 4); `wake` asks the window
    /// to redraw.
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
        self.cases = benchmark::matrix(
            &base,
            &[AccelKind::None, AccelKind::Grid, AccelKind::Bvh],
            Encoding::Srgb,
        );
        self.rows.clear();
        self.message = None;
        let cancel = Arc::new(AtomicBool::new(false));
        let (tx, rx) = channel();
        let cases = self.cases.clone();
        let options = RunOptions {
            runs: self.runs,
            threads: None,
        };
        let flag = cancel.clone();
        let spawned = std::thread::Builder::new()
            .name("benchmark".into())
            .spawn(move || run(&world, &cases, options, &flag, &tx, &wake));
        match spawned {
            Ok(_) => {
                self.cancel = Some(cancel);
                self.updates = Some(rx);
            }
            Err(e) => self.message = Some(format!("cannot start the benchmark: {e}")),
        }
    }

    /// Cancels a running matrix; the finished rows stay.
    pub fn stop(&mut self) {
        if let Some(cancel) = &self.cancel {
            cancel.store(true, Ordering::Relaxed);
        }
    }

    /// Takes the thread's updates; call once per frame.
    pub fn receive(&mut self, ctx: &egui::Context) {
        while let Some(update) = self.updates.as_ref().and_then(|rx| rx.try_recv().ok()) {
            match update {
                Update::Progress {
                    case,
                    run,
                    fraction,
                } => self.progress = Some((case, run, fraction)),
                Update::Measured(measurement) => {
                    let thumbnail = thumbnail(ctx, &measurement);
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
                    self.updates = None;
                    self.cancel = None;
                    self.progress = None;
                }
            }
        }
        if let Some(rx) = &self.exported
            && let Ok(result) = rx.try_recv()
        {
            self.message = Some(match result {
                Ok(dir) => format!("exported to {}", dir.display()),
                Err(e) => e,
            });
            self.exported = None;
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
            "The seed's timing table on {scene_name}: none / grid / BVH x hard / soft \
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
        let (tx, rx) = channel();
        let spawned = std::thread::Builder::new()
            .name("bench-export".into())
            .spawn(move || {
                let result = match rfd::FileDialog::new()
                    .set_title("Export the benchmark to")
                    .pick_folder()
                {
                    Some(dir) => write_export(&dir.join(format!("bench-{stem}")), &measurements)
                        .map_err(|e| format!("{e:#}")),
                    None => {
                        Err("not exported (cancelled, or no file dialog on this desktop)".into())
                    }
                };
                let _ = tx.send(result);
            });
        if spawned.is_ok() {
            self.exported = Some(rx);
        }
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
            bench_report::table(measurements, Layout::Matrix, format),
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

/// The image shrunk to at most [`THUMBNAIL`] pixels a side, aspect kept.
fn thumbnail(ctx: &egui::Context, m: &Measurement) -> TextureHandle {
    let (w, h) = m.image.dimensions();
    let scale = THUMBNAIL as f32 / w.max(h).max(1) as f32;
    let size = |n: u32| ((n as f32 * scale).round() as u32).max(1);
    let small = image::imageops::resize(&m.image, size(w), size(h), FilterType::Triangle);
    let image = ColorImage::from_rgb(
        [small.width() as usize, small.height() as usize],
        small.as_raw(),
    );
    ctx.load_texture(
        format!("bench {}", m.case.file_stem()),
        image,
        TextureOptions::LINEAR,
    )
}
