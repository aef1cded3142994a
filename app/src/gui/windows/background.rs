//! What the windows that work in the background share: work on a thread
//! of its own that reports updates through a channel and stops when asked
//! ([`Background`], also the lab report's export), and for the measuring
//! windows (benchmark matrix, studies) their run as a whole
//! ([`Measuring`]: its updates, rows with thumbnails, progress, message,
//! Run / Cancel / Export... and the export into a folder the user picks
//! without blocking the UI).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};

use egui::{ColorImage, TextureHandle, TextureOptions};
use image::RgbImage;
use image::imageops::FilterType;

use crate::gui::platform::file_button;
use crate::gui::platform::target;

/// Work running on its own thread, sending updates of type `U`.
pub(crate) struct Background<U> {
    cancel: Arc<AtomicBool>,
    updates: Receiver<U>,
}

impl<U: Send + 'static> Background<U> {
    /// Starts `work` on a thread called `name`; it gets the cancel flag
    /// and the sender of its updates. Refused where work that measures
    /// for long cannot run (`target::spawn_long`).
    pub(crate) fn spawn(
        name: &str,
        work: impl FnOnce(&AtomicBool, &Sender<U>) + Send + 'static,
    ) -> std::io::Result<Self> {
        let cancel = Arc::new(AtomicBool::new(false));
        let (tx, updates) = channel();
        let flag = cancel.clone();
        target::spawn_long(name, move || work(&flag, &tx))?;
        Ok(Self { cancel, updates })
    }

    /// Asks the work to stop.
    pub(crate) fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// The next update, if one has come.
    pub(crate) fn try_recv(&self) -> Option<U> {
        self.updates.try_recv().ok()
    }
}

/// `image` shrunk to at most `side` pixels a side (aspect kept) as a
/// texture called `name`.
pub(crate) fn thumbnail(
    ctx: &egui::Context,
    image: &RgbImage,
    side: u32,
    name: String,
) -> TextureHandle {
    let (w, h) = image.dimensions();
    let scale = (side as f32 / w.max(h).max(1) as f32).min(1.0);
    let size = |n: u32| ((n as f32 * scale).round() as u32).max(1);
    let small = image::imageops::resize(image, size(w), size(h), FilterType::Triangle);
    let pixels = ColorImage::from_rgb(
        [small.width() as usize, small.height() as usize],
        small.as_raw(),
    );
    ctx.load_texture(name, pixels, TextureOptions::LINEAR)
}

/// An export into a folder the user picks, run off the UI thread.
#[derive(Default)]
pub(crate) struct Export {
    pending: Option<Receiver<Result<PathBuf, String>>>,
}

impl Export {
    /// Asks for a folder (dialog `title`) on a thread, then runs `write`
    /// into it there.
    pub(crate) fn start(
        &mut self,
        title: &str,
        write: impl FnOnce(&Path) -> anyhow::Result<PathBuf> + Send + 'static,
    ) {
        let (tx, rx) = channel();
        let title = title.to_string();
        let spawned = target::spawn("export", move || {
            let result = match target::FileDialog::new().set_title(title).pick_folder() {
                Some(dir) => write(&dir).map_err(|e| format!("{e:#}")),
                None => Err("not exported (cancelled, or no file dialog on this desktop)".into()),
            };
            let _ = tx.send(result);
        });
        self.pending = spawned.ok().map(|_| rx);
    }

    /// Once the export is over: where it went, or why it did not.
    pub(crate) fn finished(&mut self) -> Option<String> {
        let result = self.pending.as_ref()?.try_recv().ok()?;
        self.pending = None;
        Some(match result {
            Ok(dir) => format!("exported to {}", dir.display()),
            Err(e) => e,
        })
    }
}

/// What a measuring thread tells its window: how far it has come (`P`),
/// one more thing measured (`M`), or the end.
pub(crate) enum Update<P, M> {
    Progress(P),
    Measured(Box<M>),
    /// Whether it was cancelled, or why it failed.
    Finished(Result<bool, String>),
}

/// A measured thing and its thumbnail.
pub(crate) struct Row<M> {
    pub(crate) measured: M,
    pub(crate) thumbnail: TextureHandle,
}

impl<M> Row<M> {
    /// The thumbnail shrunk to at most `side` points a side.
    pub(crate) fn show_thumbnail(&self, ui: &mut egui::Ui, side: f32) {
        let [w, h] = self.thumbnail.size();
        let fit = side / w.max(h).max(1) as f32;
        ui.image((
            self.thumbnail.id(),
            egui::vec2(w as f32 * fit, h as f32 * fit),
        ));
    }
}

/// A measuring window's run (the benchmark matrix, a study): its thread,
/// the rows measured so far, how far it is, the message under the
/// buttons and the last export.
pub(crate) struct Measuring<P, M> {
    pub(crate) rows: Vec<Row<M>>,
    pub(crate) progress: Option<P>,
    task: Option<Background<Update<P, M>>>,
    pub(crate) message: Option<String>,
    exported: Export,
}

impl<P, M> Default for Measuring<P, M> {
    fn default() -> Self {
        Self {
            rows: Vec::new(),
            progress: None,
            task: None,
            message: None,
            exported: Export::default(),
        }
    }
}

impl<P: Send + 'static, M: Send + 'static> Measuring<P, M> {
    pub(crate) fn is_running(&self) -> bool {
        self.task.is_some()
    }

    /// Asks a running thread to stop; the rows measured stay.
    pub(crate) fn stop(&self) {
        if let Some(task) = &self.task {
            task.cancel();
        }
    }

    /// Clears the rows and starts `work` on a thread called `name`. It
    /// gets the cancel flag and `send`, which passes an update to the
    /// window and wakes it; it returns whether it was cancelled, and that
    /// or its error ends the run. Says whether the thread started.
    pub(crate) fn start(
        &mut self,
        name: &str,
        wake: impl Fn() + Send + 'static,
        work: impl FnOnce(&AtomicBool, &dyn Fn(Update<P, M>)) -> anyhow::Result<bool> + Send + 'static,
    ) -> bool {
        self.stop();
        self.rows.clear();
        self.message = None;
        let spawned = Background::spawn(name, move |cancel, tx| {
            let send = |update| {
                let _ = tx.send(update);
                wake();
            };
            let result = work(cancel, &send).map_err(|e| format!("{e:#}"));
            send(Update::Finished(result));
        });
        match spawned {
            Ok(task) => self.task = Some(task),
            Err(e) => self.message = Some(format!("cannot start the {name}: {e}")),
        }
        self.task.is_some()
    }

    /// Takes the thread's updates; call once per frame. A measured thing
    /// becomes a row with a thumbnail of at most `side` pixels a side of
    /// the image and texture name `picture` gives it (with its row's
    /// index); at the end `finished` says what was done (cancelled or
    /// not, with the rows' count).
    pub(crate) fn receive(
        &mut self,
        ctx: &egui::Context,
        side: u32,
        picture: impl Fn(&M, usize) -> (&RgbImage, String),
        finished: impl Fn(bool, usize) -> String,
    ) {
        while let Some(update) = self.task.as_ref().and_then(Background::try_recv) {
            match update {
                Update::Progress(progress) => self.progress = Some(progress),
                Update::Measured(measured) => {
                    let (image, name) = picture(&measured, self.rows.len());
                    let thumbnail = thumbnail(ctx, image, side, name);
                    self.rows.push(Row {
                        measured: *measured,
                        thumbnail,
                    });
                }
                Update::Finished(result) => {
                    self.message = Some(match result {
                        Ok(cancelled) => finished(cancelled, self.rows.len()),
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

    /// Cancel while running, else Run (which sets `start`), and Export...
    /// once rows are measured and the run is over; says whether Export...
    /// was clicked.
    pub(crate) fn buttons(&mut self, ui: &mut egui::Ui, start: &mut bool) -> bool {
        if self.is_running() {
            if ui.button("Cancel").clicked() {
                self.stop();
            }
        } else if ui.button("Run").clicked() {
            *start = true;
        }
        !self.rows.is_empty()
            && !self.is_running()
            && file_button(ui, true, egui::Button::new("Export...")).clicked()
    }

    /// Runs `write` into a folder the user picks (see [`Export::start`]);
    /// where it went, or why not, becomes the message.
    pub(crate) fn export(
        &mut self,
        title: &str,
        write: impl FnOnce(&Path) -> anyhow::Result<PathBuf> + Send + 'static,
    ) {
        self.exported.start(title, write);
    }
}
