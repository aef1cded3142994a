//! Export report... in the window: the lab report (`reports::lab`) of the
//! current scene, camera, settings and edits, measured on a thread of its
//! own with a progress bar and Cancel, and written where the user chose,
//! whole or not at all (a cancelled export writes nothing).

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, channel};

use egui::Ui;

use crate::gui::app::saving::{Answer, FileDialog, FileQuestion};
use crate::gui::platform::target::{self, SaveTo};
use crate::reports::lab::{self, ReportProgress, Request};

use super::background::Background;

/// What the export thread tells the window.
enum Update {
    Progress(ReportProgress),
    /// Where the page went; `None` when cancelled.
    Finished(Result<Option<String>, String>),
}

/// The export's state: a file being chosen, the report being measured,
/// or what the last one did.
#[derive(Default)]
pub struct ReportExport {
    choosing: Option<Receiver<Option<SaveTo>>>,
    task: Option<Background<Update>>,
    progress: Option<ReportProgress>,
    /// Where the running export writes, as said.
    target: Option<String>,
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

    /// Asks `dialog` where to save the page, on a thread (the dialog must
    /// not block the window): a file on the desktop, a download on the
    /// page; [`ReportExport::chosen`] gives the answer.
    pub(crate) fn choose_file(&mut self, dialog: Arc<dyn FileDialog>) {
        let (tx, rx) = channel();
        let spawned = target::spawn("report file", move || {
            let _ = tx.send(SaveTo::ask(&*dialog, &question()));
        });
        match spawned {
            Ok(_) => self.choosing = Some(rx),
            Err(e) => self.message = Some(format!("cannot open a file dialog: {e}")),
        }
    }

    /// Answers the file dialog with `path` without showing it: what a
    /// test does, having no desktop to show it on.
    pub(crate) fn choose(&mut self, path: PathBuf) {
        let (tx, rx) = channel();
        let _ = tx.send(SaveTo::ask(&Answer(path), &question()));
        self.choosing = Some(rx);
    }

    /// Where the user chose to save, once chosen; a dismissed dialog says
    /// so.
    pub(crate) fn chosen(&mut self) -> Option<SaveTo> {
        let answer = self.choosing.as_ref()?.try_recv().ok()?;
        self.choosing = None;
        if answer.is_none() {
            self.message = Some("report not exported (no file chosen)".into());
        }
        answer
    }

    /// Measures `request` and saves its page `to` the file or download
    /// chosen, on a thread; `wake` asks the window to redraw.
    pub(crate) fn start(&mut self, request: Request, to: SaveTo, wake: impl Fn() + Send + 'static) {
        self.cancel();
        self.message = None;
        self.progress = None;
        self.target = Some(to.describe());
        let spawned = Background::spawn("report", move |cancel, tx| {
            let outcome = lab::measure(&request, cancel, &mut |p| {
                let _ = tx.send(Update::Progress(p.clone()));
                wake();
            })
            .and_then(|lab| match lab {
                Some(lab) => {
                    to.write(lab::page(&lab)?.as_bytes())?;
                    Ok(Some(to.describe()))
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
    pub(crate) fn cancel(&self) {
        if let Some(task) = &self.task {
            task.cancel();
        }
    }

    /// Takes the thread's updates; call once per frame.
    pub(crate) fn receive(&mut self) {
        while let Some(update) = self.task.as_ref().and_then(Background::try_recv) {
            match update {
                Update::Progress(p) => self.progress = Some(p),
                Update::Finished(result) => {
                    self.message = Some(match result {
                        Ok(Some(to)) => format!("report written to {to}"),
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
    pub(crate) fn show(&mut self, ctx: &egui::Context) {
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
                ui.label(format!("Measuring for {target}"));
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

/// What Export report... asks: a name for the HTML page.
fn question() -> FileQuestion {
    FileQuestion {
        save: true,
        pick_folder: false,
        filter: ("HTML page", &["html"]),
        folder: None,
        name: Some("report.html".into()),
    }
}
