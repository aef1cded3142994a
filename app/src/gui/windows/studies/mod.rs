//! The Studies window: a parameter study (see [`crate::measure::study`])
//! on the current scene and camera, or on a generated scene for the level
//! study, run on a thread of its own. The chart fills in point by point
//! with the best point ringed; hovering a point shows its numbers and
//! image, clicking it (or its row's Apply) shows its settings in the main
//! view. Exports the table (Markdown, CSV) and the chart (PNG) into a
//! folder, or saves the chart alone (Save chart...: a download on the
//! web page, which has no folders).

use std::sync::Arc;

use egui::Ui;
use tracer::accel::AccelKind;
use tracer::generate::GeneratorName;
use tracer::render::{Encoding, RenderSettings};
use tracer::world::World;

use crate::measure::benchmark::RunOptions;
use crate::measure::study::{Param, Point, Study, Subject, values};
use crate::reports::study_table;

use crate::gui::sides::Controls;
use crate::gui::windows::background::Measuring;

/// Side of the thumbnails, in pixels.
const THUMBNAIL: u32 = 96;

/// How far the study is.
enum StudyProgress {
    /// Work before the points, and the fraction of it done.
    Preparing(String, f32),
    Rendering {
        point: usize,
        run: usize,
        fraction: f32,
    },
}

type Update = crate::gui::windows::background::Update<StudyProgress, Point>;

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
    /// The run and its measured points.
    measuring: Measuring<StudyProgress, Point>,
    /// Show error against time instead of time against the value.
    error_view: bool,
    /// Save chart... was clicked, not yet taken by [`Self::chart_to_save`].
    chart_asked: bool,
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
            measuring: Measuring::default(),
            error_view: false,
            chart_asked: false,
        }
    }
}

impl StudiesWindow {
    pub fn is_running(&self) -> bool {
        self.measuring.is_running()
    }

    /// The points measured so far, in measuring order.
    pub fn points(&self) -> impl Iterator<Item = &Point> {
        self.measuring.rows.iter().map(|r| &r.measured)
    }

    /// The message under the buttons (a count, an error), if any.
    pub fn message(&self) -> Option<&str> {
        self.measuring.message.as_deref()
    }

    /// Starts the study the window is set to: on `world` from `base` (the
    /// current scene, camera and size; without one only the level study
    /// can run), or for the level study on the
    /// generator's scenes with `controls` applied to each. `wake` asks the
    /// window to redraw.
    pub(crate) fn start(
        &mut self,
        world: Option<Arc<World>>,
        base: &RenderSettings,
        controls: &Controls,
        scene_name: &str,
        wake: impl Fn() + Send + 'static,
    ) {
        self.stop();
        self.measuring.message = None;
        let values = match values::parse(&self.values) {
            Ok(values) => values,
            Err(e) => {
                self.measuring.message = Some(format!("values: {e}"));
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
                self.measuring.message = Some("open a scene first: this study renders it".into());
                return;
            };
            let base = base.clone();
            (Subject::Scene { world, base }, scene_name.to_string())
        };
        if let Err(e) = study.check(&subject) {
            self.measuring.message = Some(format!("{e:#}"));
            return;
        }
        self.subject = name;
        let thread_study = study.clone();
        let started = self.measuring.start("study", wake, move |cancel, send| {
            task::run(&thread_study, &subject, cancel, send)
        });
        if started {
            self.study = Some(study);
        }
    }

    /// Cancels a running study; the measured points stay.
    pub(crate) fn stop(&mut self) {
        self.measuring.stop();
    }

    /// Takes the thread's updates; call once per frame.
    pub(crate) fn receive(&mut self, ctx: &egui::Context) {
        let total = self.study.as_ref().map_or(0, Study::len);
        self.measuring.receive(
            ctx,
            THUMBNAIL,
            |point, row| (&point.measurement.image, format!("study point {row}")),
            |cancelled, rows| match cancelled {
                false => format!("{rows} points measured"),
                true => format!("cancelled after {rows} of {total} points"),
            },
        );
    }

    /// Draws the window. `start` is set when the user asks for a run; the
    /// point the user picked, if any, is returned for the main view.
    pub(crate) fn show(
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
            if self.measuring.buttons(ui, start) {
                self.export();
            }
            let measured = !self.measuring.rows.is_empty() && idle;
            if measured
                && ui
                    .button("Save chart...")
                    .on_hover_text("The chart as a PNG image (on the web page, a download)")
                    .clicked()
            {
                self.chart_asked = true;
            }
        });
        self.progress_bar(ui);
        if let Some(message) = &self.measuring.message {
            ui.label(message);
        }
        let param = self.study.as_ref()?.param;
        if self.measuring.rows.is_empty() {
            return None;
        }
        let points: Vec<Point> = self.points().cloned().collect();
        for line in study_table::summary(param, &points) {
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
            .map(|i| self.applied(param, &self.measuring.rows[i].measured))
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
        match self.measuring.progress.as_ref()? {
            StudyProgress::Preparing(what, fraction) => Some((*fraction, what.clone())),
            StudyProgress::Rendering {
                point,
                run,
                fraction,
            } => {
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
        }
    }

    fn progress_bar(&self, ui: &mut Ui) {
        if let Some((done, what)) = self.progress() {
            ui.add(egui::ProgressBar::new(done).text(what));
        }
    }

    fn applied(&self, param: Param, point: &Point) -> Applied {
        Applied {
            param,
            value: point.value,
            accel: point.accel(),
            generator: (param == Param::Level).then_some(self.generator),
        }
    }

    /// Once Save chart... was clicked: the study's parameter, its points
    /// and its subject's name, for the window's save dialog.
    pub(crate) fn chart_to_save(&mut self) -> Option<(Param, Vec<Point>, String)> {
        if !std::mem::take(&mut self.chart_asked) {
            return None;
        }
        let param = self.study.as_ref()?.param;
        Some((
            param,
            self.points().cloned().collect(),
            self.subject.clone(),
        ))
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
        self.measuring.export("Export the study to", move |dir| {
            write_export(dir, param, &points, &subject)
        });
    }
}

mod applied;
mod results;
mod task;
#[cfg(test)]
mod tests;

pub(crate) use applied::Applied;
pub(crate) use task::write_export;
