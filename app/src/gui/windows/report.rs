//! Export report... in the window: the lab report (`reports::lab`) of the
//! current scene, camera, settings and edits, measured on a thread of its
//! own with a progress bar and Cancel, and written where the user chose,
//! whole or not at all (a cancelled export writes nothing).

use std::path::PathBuf;
use std::sync::mpsc::{Receiver, channel};

use egui::Ui;

use crate::gui::platform::target;
use crate::reports::lab::{self, ReportProgress, Request};

use super::background::Background;

/// What the export thread tells the window.
enum Update {
    Progress(ReportProgress),
    /// Where the page went; `None` when cancelled.
    Finished(Result<Option<PathBuf>, String>),
}

/// The export's state: a file being chosen, the report being measured,
/// or what the last one did.
#[derive(Default)]
pub struct ReportExport {
    choosing: Option<Receiver<Option<PathBuf>>>,
    task: Option<Background<Update>>,
    progress: Option<ReportProgress>,
    /// Where the running export writes.
    target: Option<PathBuf>,
    /// What the last export did, shown until the next.
    pub message: Option<String>,
}

impl ReportExport {
    pub fn is_running(&self) -> bool {
        self.task.is_some()
    }

    /// How far the running export has come.
    pub fn progress(&self) -> Option<&ReportProgress> {
        self.progress.as_ref()
    }

    /// Asks where to save the page, on a thread (the dialog must not block
    /// the window); [`ReportExport::chosen`] gives the answer.
    pub fn choose_file(&mut self) {
        let (tx, rx) = channel();
        let spawned = target::spawn("report file", move || {
            let path = target::FileDialog::new()
                .set_title("Export the lab report")
                .set_file_name("report.html")
                .add_filter("HTML page", &["html"])
                .save_file();
            let _ = tx.send(path);
        });
        match spawned {
            Ok(_) => self.choosing = Some(rx),
            Err(e) => self.message = Some(format!("cannot open a file dialog: {e}")),
        }
    }

    /// Answers the file dialog with `path` without showing it: what a
    /// test does, having no desktop to show it on.
    pub fn choose(&mut self, path: PathBuf) {
        let (tx, rx) = channel();
        let _ = tx.send(Some(path));
        self.choosing = Some(rx);
    }

    /// The file the user chose, once chosen; a dismissed dialog says so.
    pub fn chosen(&mut self) -> Option<PathBuf> {
        let answer = self.choosing.as_ref()?.try_recv().ok()?;
        self.choosing = None;
        if answer.is_none() {
            self.message = Some("report not exported (no file chosen)".into());
        }
        answer
    }

    /// Measures `request` and writes its page to `path`, on a thread;
    /// `wake` asks the window to redraw.
    pub fn start(&mut self, request: Request, path: PathBuf, wake: impl Fn() + Send + 'static) {
        self.cancel();
        self.message = None;
        self.progress = None;
        self.target = Some(path.clone());
        let spawned = Background::spawn("report", move |cancel, tx| {
            let outcome = lab::measure(&request, cancel, &mut |p| {
                let _ = tx.send(Update::Progress(p.clone()));
                wake();
            })
            .and_then(|lab| match lab {
                Some(lab) => {
                    lab::write_atomically(&path, &lab::page(&lab)?)?;
                    Ok(Some(path))
                }
                None => Ok(None),
            });
            let _ = tx.send(Update::Finished(outcome.map_err(|e| format!("{e:#}"))));
            wake();
        });
        match spawned {
            Ok(task) => self.task = Some(task),
            Err(e) => self.message = Some(format!("cannot start the report: {e}")),
        }
    }

    /// Stops a running export; nothing is written.
    pub fn cancel(&self) {
        if let Some(task) = &self.task {
            task.cancel();
        }
    }

    /// Takes the thread's updates; call once per frame.
    pub fn receive(&mut self) {
        while let Some(update) = self.task.as_ref().and_then(Background::try_recv) {
            match update {
                Update::Progress(p) => self.progress = Some(p),
                Update::Finished(result) => {
                    self.message = Some(match result {
                        Ok(Some(path)) => format!("report written to {}", path.display()),
                        Ok(None) => "report cancelled: nothing written".into(),
                        Err(e) => format!("report not written: {e}"),
                    });
                    self.task = None;
                    self.progress = None;
                    self.target = None;
                }
            }
        }
    }

    /// The export's window, while it runs or has something to say.
    pub fn show(&mut self, ctx: &egui::Context) {
        if self.task.is_none() && self.message.is_none() {
            return;
        }
        let mut open = true;
        egui::Window::new("Export report")
            .open(&mut open)
            .default_width(420.0)
            .show(ctx, |ui| self.contents(ui));
        if !open {
            self.cancel();
            self.message = None;
        }
    }

    fn contents(&mut self, ui: &mut Ui) {
        if self.is_running() {
            if let Some(target) = &self.target {
                ui.label(format!("Measuring for {}", target.display()));
            }
            let (fraction, doing) = self
                .progress
                .as_ref()
                .map_or((0.0, "starting"), |p| (p.fraction, p.doing.as_str()));
            ui.add(egui::ProgressBar::new(fraction).show_percentage());
            ui.label(doing);
            if ui.button("Cancel").clicked() {
                self.cancel();
            }
        } else if let Some(message) = &self.message {
            ui.label(message);
        }
    }
}
