//! The Studies window: a parameter study (see [`crate::measure::study`])
//! on the current scene and camera, or on a generated scene for the level
//! study, run on a thread of its own. The chart fills in point by point
//! with the best point ringed; hovering a point shows its numbers and
//! image, clicking it (or its row's Apply) shows its settings in the main
//! view. Exports the table (Markdown, CSV) and the chart (PNG).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::Sender;

use anyhow::Context;
use egui::{Color32, TextureHandle, Ui};
use egui_plot::{Line, MarkerShape, Plot, PlotPoint, Points};
use tracer::accel::AccelKind;
use tracer::generate::{self, GenerateOptions, GeneratorName};
use tracer::render::{Encoding, RenderSettings};
use tracer::world::World;

use crate::measure::bench_report::Format;
use crate::measure::benchmark::{RunOptions, Stop};
use crate::measure::study::{
    self, Param, Point, Study, StudyEvent, Subject, analysis, plot, report, values,
};
use crate::output::save_png;

use super::background::{self, Background};
use super::state::Controls;

/// Side of the thumbnails, in pixels.
const THUMBNAIL: u32 = 96;
/// How close (screen points) the pointer must be to a point to pick it.
const PICK_RADIUS: f32 = 14.0;

/// What the study thread tells the window.
enum Update {
    Preparing(String, f32),
    Rendering {
        point: usize,
        run: usize,
        fraction: f32,
    },
    Measured(Box<Point>),
    Finished(Result<bool, String>),
}

/// A measured point and its thumbnail.
struct Row {
    point: Point,
    thumbnail: TextureHandle,
}

/// A point's settings, for the main view.
#[derive(Debug, Clone, PartialEq)]
pub struct Applied {
    pub param: Param,
    pub value: f64,
    pub accel: AccelKind,
    /// The generator of a level study's point.
    pub generator: Option<GeneratorName>,
}

impl Applied {
    /// Sets `controls` to the point's structure and value; `scene_width`
    /// turns a resolution into the controls' scale.
    pub fn apply_to(&self, controls: &mut Controls, scene_width: u32) {
        controls.change_settings(scene_width, |settings| {
            settings.accel = self.accel;
            self.param.apply(settings, self.value);
        });
    }

    /// For a level study's point, its generated scene written as P3F in
    /// the temporary folder (with the point's structure), to open.
    pub fn scene_file(&self) -> anyhow::Result<Option<PathBuf>> {
        let Some(generator) = self.generator else {
            return Ok(None);
        };
        let level = self.value as u32;
        let mut scene = generate::generate(generator, &GenerateOptions { level, seed: 0 })?;
        scene.accel = Some(match self.accel {
            AccelKind::None => 0,
            AccelKind::Grid => 1,
            AccelKind::Bvh => 2,
        });
        let path = std::env::temp_dir().join(format!(
            "workbench-{generator}-{level}-{}.p3f",
            self.accel.name()
        ));
        let text = format!(
            "# {}\n{}",
            generate::describe(generator, level, 0),
            tracer::scene::write_p3f(&scene)
        );
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
        Ok(Some(path))
    }
}

/// The window's state.
pub struct StudiesWindow {
    pub open: bool,
    param: Param,
    values: String,
    generator: GeneratorName,
    structures: Vec<AccelKind>,
    runs: usize,
    /// The study running or last run.
    study: Option<Study>,
    subject: String,
    rows: Vec<Row>,
    progress: Option<Update>,
    task: Option<Background<Update>>,
    message: Option<String>,
    exported: background::Export,
    /// Show error against time instead of time against the value.
    error_view: bool,
}

impl Default for StudiesWindow {
    fn default() -> Self {
        let param = Param::GridM;
        Self {
            open: false,
            param,
            values: param.default_values(&RenderSettings::default()),
            generator: GeneratorName::Balls,
            structures: param.default_structures(AccelKind::Bvh),
            runs: 3,
            study: None,
            subject: String::new(),
            rows: Vec::new(),
            progress: None,
            task: None,
            message: None,
            exported: background::Export::default(),
            error_view: false,
        }
    }
}

impl StudiesWindow {
    pub fn is_running(&self) -> bool {
        self.task.is_some()
    }

    /// The points measured so far, in measuring order.
    pub fn points(&self) -> impl Iterator<Item = &Point> {
        self.rows.iter().map(|r| &r.point)
    }

    /// The message under the buttons (a count, an error), if any.
    pub fn message(&self) -> Option<&str> {
        self.message.as_deref()
    }

    /// Starts the study the window is set to: on `world` from `base` (the
    /// current scene, camera and size; without one only the level study
    /// can run), or for the level study on the
    /// generator's scenes with `controls` applied to each. `wake` asks the
    /// window to redraw.
    pub fn start(
        &mut self,
        world: Option<Arc<World>>,
        base: &RenderSettings,
        controls: &Controls,
        scene_name: &str,
        wake: impl Fn() + Send + 'static,
    ) {
        self.stop();
        self.message = None;
        let values = match values::parse(&self.values) {
            Ok(values) => values,
            Err(e) => {
                self.message = Some(format!("values: {e}"));
                return;
            }
        };
        let study = Study {
            param: self.param,
            values,
            structures: self.structures.clone(),
            options: RunOptions {
                runs: self.runs,
                threads: None,
            },
            encoding: Encoding::Srgb,
            reference_samples: None,
        };
        let (subject, name) = if self.param == Param::Level {
            let controls = controls.clone();
            let subject = Subject::Generated {
                generator: self.generator,
                seed: 0,
                settings: Box::new(move |scene| controls.render_settings(scene, None, false)),
            };
            (subject, self.generator.to_string())
        } else {
            let Some(world) = world else {
                self.message = Some("open a scene first: this study renders it".into());
                return;
            };
            let base = base.clone();
            (Subject::Scene { world, base }, scene_name.to_string())
        };
        if let Err(e) = study.check(&subject) {
            self.message = Some(format!("{e:#}"));
            return;
        }
        self.rows.clear();
        self.subject = name;
        let thread_study = study.clone();
        let spawned = Background::spawn("study", move |cancel, tx| {
            run(&thread_study, &subject, cancel, tx, &wake)
        });
        match spawned {
            Ok(task) => {
                self.study = Some(study);
                self.task = Some(task);
            }
            Err(e) => self.message = Some(format!("cannot start the study: {e}")),
        }
    }

    /// Cancels a running study; the measured points stay.
    pub fn stop(&mut self) {
        if let Some(task) = &self.task {
            task.cancel();
        }
    }

    /// Takes the thread's updates; call once per frame.
    pub fn receive(&mut self, ctx: &egui::Context) {
        while let Some(update) = self.task.as_ref().and_then(Background::try_recv) {
            match update {
                Update::Measured(point) => {
                    let thumbnail = background::thumbnail(
                        ctx,
                        &point.measurement.image,
                        THUMBNAIL,
                        format!("study point {}", self.rows.len()),
                    );
                    self.rows.push(Row {
                        point: *point,
                        thumbnail,
                    });
                }
                Update::Finished(result) => {
                    let total = self.study.as_ref().map_or(0, Study::len);
                    self.message = Some(match result {
                        Ok(false) => format!("{} points measured", self.rows.len()),
                        Ok(true) => {
                            format!("cancelled after {} of {total} points", self.rows.len())
                        }
                        Err(e) => e,
                    });
                    self.task = None;
                    self.progress = None;
                }
                progress => self.progress = Some(progress),
            }
        }
        if let Some(message) = self.exported.finished() {
            self.message = Some(message);
        }
    }

    /// Draws the window. `start` is set when the user asks for a run; the
    /// point the user picked, if any, is returned for the main view.
    pub fn show(
        &mut self,
        ctx: &egui::Context,
        base: &RenderSettings,
        start: &mut bool,
    ) -> Option<Applied> {
        let mut open = self.open;
        let mut applied = None;
        egui::Window::new("Studies")
            .open(&mut open)
            .default_size([720.0, 760.0])
            .show(ctx, |ui| applied = self.contents(ui, base, start));
        self.open = open;
        applied
    }

    fn contents(
        &mut self,
        ui: &mut Ui,
        base: &RenderSettings,
        start: &mut bool,
    ) -> Option<Applied> {
        let idle = !self.is_running();
        ui.add_enabled_ui(idle, |ui| self.settings(ui, base));
        ui.horizontal(|ui| {
            if self.is_running() {
                if ui.button("Cancel").clicked() {
                    self.stop();
                }
            } else if ui.button("Run").clicked() {
                *start = true;
            }
            if !self.rows.is_empty() && idle && ui.button("Export...").clicked() {
                self.export();
            }
        });
        self.progress_bar(ui);
        if let Some(message) = &self.message {
            ui.label(message);
        }
        let param = self.study.as_ref()?.param;
        if self.rows.is_empty() {
            return None;
        }
        let points: Vec<Point> = self.points().cloned().collect();
        for line in report::summary(param, &points) {
            ui.label(line);
        }
        let has_error = points.iter().any(|p| p.error.is_some());
        if has_error {
            ui.horizontal(|ui| {
                ui.selectable_value(&mut self.error_view, false, "time vs N");
                ui.selectable_value(&mut self.error_view, true, "error vs time");
            });
        }
        let picked = self.chart(ui, param, &points, has_error && self.error_view);
        let from_table = self.table(ui, param, &points);
        picked
            .or(from_table)
            .map(|i| self.applied(param, &self.rows[i].point))
    }

    /// The parameter, values, generator, structures and runs.
    fn settings(&mut self, ui: &mut Ui, base: &RenderSettings) {
        ui.horizontal(|ui| {
            let before = self.param;
            egui::ComboBox::from_label("parameter")
                .selected_text(self.param.name())
                .show_ui(ui, |ui| {
                    for param in Param::ALL {
                        ui.selectable_value(&mut self.param, param, param.name());
                    }
                });
            if self.param != before {
                self.values = self.param.default_values(base);
                self.structures = self.param.default_structures(base.accel);
            }
            if self.param == Param::Level {
                egui::ComboBox::from_label("generator")
                    .selected_text(self.generator.name())
                    .show_ui(ui, |ui| {
                        for generator in GeneratorName::ALL {
                            ui.selectable_value(&mut self.generator, generator, generator.name());
                        }
                    });
            }
        });
        ui.horizontal(|ui| {
            let label = ui.label("values");
            ui.add(egui::TextEdit::singleline(&mut self.values).desired_width(220.0))
                .labelled_by(label.id)
                .on_hover_text(values::SYNTAX);
            ui.add(egui::Slider::new(&mut self.runs, 1..=9).text("runs each"))
                .on_hover_text("Frames per point: the chart shows their median");
        });
        ui.horizontal(|ui| {
            ui.label("structures");
            for accel in AccelKind::ALL {
                let mut on = self.structures.contains(&accel);
                if ui.checkbox(&mut on, accel.name()).changed() {
                    self.structures.retain(|&a| a != accel);
                    if on {
                        self.structures.push(accel);
                        self.structures
                            .sort_by_key(|a| AccelKind::ALL.iter().position(|s| s == a));
                    }
                }
            }
        });
    }

    /// How far the running study is (0..=1) and what it is doing.
    pub fn progress(&self) -> Option<(f32, String)> {
        let study = self.study.as_ref()?;
        let plan = study.plan();
        let runs = study.options.runs.max(1);
        match &self.progress {
            Some(Update::Preparing(what, fraction)) => Some((*fraction, what.clone())),
            Some(Update::Rendering {
                point,
                run,
                fraction,
            }) => {
                let done = (*point as f32 + (*run as f32 + fraction) / runs as f32)
                    / plan.len().max(1) as f32;
                let (accel, value) = *plan.get(*point)?;
                let what = format!(
                    "{} {} = {} ({}/{}), run {}/{runs}",
                    accel.name(),
                    study.param,
                    values::format(value),
                    point + 1,
                    plan.len(),
                    run + 1
                );
                Some((done, what))
            }
            _ => None,
        }
    }

    fn progress_bar(&self, ui: &mut Ui) {
        if let Some((done, what)) = self.progress() {
            ui.add(egui::ProgressBar::new(done).text(what));
        }
    }

    /// The chart; returns the point clicked. Log axes plot log10 values
    /// with ticks labelled in plain numbers.
    fn chart(
        &self,
        ui: &mut Ui,
        param: Param,
        points: &[Point],
        error_view: bool,
    ) -> Option<usize> {
        let (log_x, log_y) = if error_view {
            (false, true)
        } else {
            plot::log_axes(param, points)
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
                    let [r, g, b] = plot::colour(accel);
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
                    let [r, g, b] = plot::colour(points[i].accel());
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
        let row = &self.rows[nearest];
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
    fn table(&self, ui: &mut Ui, param: Param, points: &[Point]) -> Option<usize> {
        let (headers, cells) = report::rows(param, points);
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
                    for (i, (row, cells)) in self.rows.iter().zip(&cells).enumerate() {
                        let [w, h] = row.thumbnail.size();
                        let fit = 32.0 / w.max(h).max(1) as f32;
                        ui.image((
                            row.thumbnail.id(),
                            egui::vec2(w as f32 * fit, h as f32 * fit),
                        ));
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

    fn applied(&self, param: Param, point: &Point) -> Applied {
        Applied {
            param,
            value: point.value,
            accel: point.accel(),
            generator: (param == Param::Level).then_some(self.generator),
        }
    }

    /// Writes the table and chart into a folder the user picks, off the
    /// UI thread.
    fn export(&mut self) {
        let Some(study) = &self.study else {
            return;
        };
        let param = study.param;
        let points: Vec<Point> = self.points().cloned().collect();
        let subject = self.subject.clone();
        self.exported.start("Export the study to", move |dir| {
            write_export(dir, param, &points, &subject)
        });
    }
}

/// A point's numbers (the table's row, one per line) and its image.
fn point_details(ui: &mut Ui, param: Param, points: &[Point], i: usize, image: &TextureHandle) {
    let (headers, cells) = report::rows(param, points);
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

/// The table as `table.md` and `table.csv` and the chart as `chart.png`
/// in `dir/study-<param>-<subject>`; returns that folder.
pub fn write_export(
    dir: &Path,
    param: Param,
    points: &[Point],
    subject: &str,
) -> anyhow::Result<PathBuf> {
    let stem = Path::new(subject)
        .file_stem()
        .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
    let dir = dir.join(format!("study-{param}-{stem}"));
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for (name, format) in [("table.md", Format::Markdown), ("table.csv", Format::Csv)] {
        let path = dir.join(name);
        std::fs::write(&path, report::table(param, points, format))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    save_png(&plot::chart(param, points, &stem)?, &dir.join("chart.png"))?;
    Ok(dir)
}

/// Runs the study, forwarding its events and points.
fn run(study: &Study, subject: &Subject, stop: &AtomicBool, tx: &Sender<Update>, wake: &dyn Fn()) {
    let never = AtomicBool::new(false);
    let stop = Stop {
        now: stop,
        after_frame: &never,
    };
    let mut on_event = |event: StudyEvent| {
        let update = match event {
            StudyEvent::Preparing { what, fraction } => {
                Update::Preparing(what.to_string(), fraction)
            }
            StudyEvent::Rendering {
                point,
                run,
                fraction,
            } => Update::Rendering {
                point,
                run,
                fraction,
            },
            StudyEvent::Measured { result, .. } => Update::Measured(Box::new(result.clone())),
        };
        let _ = tx.send(update);
        wake();
    };
    let result = study::run(study, subject, stop, &mut on_event)
        .map(|outcome| outcome.cancelled)
        .map_err(|e| format!("{e:#}"));
    let _ = tx.send(Update::Finished(result));
    wake();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_sets_its_structure_and_value_in_the_controls() {
        let mut controls = Controls::default();
        let point = |param, value| Applied {
            param,
            value,
            accel: AccelKind::Grid,
            generator: None,
        };
        point(Param::Spp, 3.0).apply_to(&mut controls, 200);
        assert!(controls.antialiasing && controls.samples == 3);
        assert_eq!(AccelKind::from(controls.accel), AccelKind::Grid);
        point(Param::Resolution, 50.0).apply_to(&mut controls, 200);
        assert_eq!(controls.resolution_scale, 0.25);
        point(Param::Aperture, 0.0).apply_to(&mut controls, 200);
        assert!(!controls.depth_of_field);
        // A scale that no whole width gives exactly survives other points.
        controls.resolution_scale = 0.3719;
        point(Param::GridM, 2.5).apply_to(&mut controls, 200);
        assert_eq!(controls.grid_multiplier, 2.5);
        assert_eq!(controls.resolution_scale, 0.3719);
        assert_eq!(point(Param::GridM, 2.0).scene_file().unwrap(), None);
    }

    #[test]
    fn a_level_point_opens_its_generated_scene_with_its_structure() {
        let point = Applied {
            param: Param::Level,
            value: 1.0,
            accel: AccelKind::None,
            generator: Some(GeneratorName::Balls),
        };
        let path = point.scene_file().unwrap().unwrap();
        let scene =
            tracer::scene::parse_scene_file(&path, &tracer::scene::Limits::default()).unwrap();
        assert_eq!(scene.accel, Some(0));
        assert_eq!(World::build(&scene).counts.primitives, 12);
        // Kept only when the test fails, to be inspected.
        std::fs::remove_file(&path).unwrap();
    }

    #[test]
    fn the_level_study_needs_no_open_scene_the_others_say_so() {
        let mut window = StudiesWindow {
            values: "1".into(),
            runs: 1,
            ..StudiesWindow::default()
        };
        let controls = Controls {
            resolution_scale: 0.05,
            ..Controls::default()
        };
        let base = RenderSettings::default();
        window.start(None, &base, &controls, "", || {});
        assert!(!window.is_running());
        assert!(window.message().unwrap().contains("open a scene first"));

        window.param = Param::Level;
        window.start(None, &base, &controls, "", || {});
        assert!(window.is_running(), "{:?}", window.message());
        window.stop();
    }

    #[test]
    fn the_export_writes_the_tables_and_the_chart() {
        let text = "v\nfrom 0 -5 1\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0.01\n\
                    resolution 8 8\nl 2 -2 4\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";
        let scene =
            tracer::scene::parse_scene(text, None, &tracer::scene::Limits::default()).unwrap();
        let subject = Subject::Scene {
            world: Arc::new(World::build(&scene)),
            base: RenderSettings::from_scene(&scene),
        };
        let study = Study {
            param: Param::Depth,
            values: vec![1.0, 2.0],
            structures: vec![AccelKind::Bvh],
            options: RunOptions {
                runs: 1,
                threads: Some(1),
            },
            encoding: Encoding::Srgb,
            reference_samples: None,
        };
        let never = AtomicBool::new(false);
        let stop = Stop {
            now: &never,
            after_frame: &never,
        };
        let outcome = study::run(&study, &subject, stop, &mut |_| {}).unwrap();
        let dir = tracer::scratch::Scratch::new("study-export");
        let written = write_export(&dir, Param::Depth, &outcome.points, "tiny.p3f").unwrap();
        assert_eq!(written, dir.join("study-depth-tiny"));
        let csv = std::fs::read_to_string(written.join("table.csv")).unwrap();
        assert_eq!(csv.lines().count(), 3);
        assert!(
            std::fs::read_to_string(written.join("table.md"))
                .unwrap()
                .contains("| bvh | 1 |")
        );
        let chart = image::open(written.join("chart.png")).unwrap();
        assert_eq!((chart.width(), chart.height()), plot::PANEL);
    }
}
