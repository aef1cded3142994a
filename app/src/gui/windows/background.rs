//! What the measuring windows (benchmark matrix, studies) share: work on a
//! thread of its own that reports updates through a channel and stops
//! when asked, thumbnails of measured images, and exports into a folder
//! the user picks without blocking the UI.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};

use egui::{ColorImage, TextureHandle, TextureOptions};
use image::RgbImage;
use image::imageops::FilterType;

/// Work running on its own thread, sending updates of type `U`.
pub struct Background<U> {
    cancel: Arc<AtomicBool>,
    updates: Receiver<U>,
}

impl<U: Send + 'static> Background<U> {
    /// Starts `work` on a thread called `name`; it gets the cancel flag
    /// and the sender of its updates.
    pub fn spawn(
        name: &str,
        work: impl FnOnce(&AtomicBool, &Sender<U>) + Send + 'static,
    ) -> std::io::Result<Self> {
        let cancel = Arc::new(AtomicBool::new(false));
        let (tx, updates) = channel();
        let flag = cancel.clone();
        std::thread::Builder::new()
            .name(name.into())
            .spawn(move || work(&flag, &tx))?;
        Ok(Self { cancel, updates })
    }

    /// Asks the work to stop.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// The next update, if one has come.
    pub fn try_recv(&self) -> Option<U> {
        self.updates.try_recv().ok()
    }
}

/// `image` shrunk to at most `side` pixels a side (aspect kept) as a
/// texture called `name`.
pub fn thumbnail(ctx: &egui::Context, image: &RgbImage, side: u32, name: String) -> TextureHandle {
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
pub struct Export {
    pending: Option<Receiver<Result<PathBuf, String>>>,
}

impl Export {
    /// Asks for a folder (dialog `title`) on a thread, then runs `write`
    /// into it there.
    pub fn start(
        &mut self,
        title: &str,
        write: impl FnOnce(&Path) -> anyhow::Result<PathBuf> + Send + 'static,
    ) {
        let (tx, rx) = channel();
        let title = title.to_string();
        let spawned = std::thread::Builder::new()
            .name("export".into())
            .spawn(move || {
                let result = match rfd::FileDialog::new().set_title(title).pick_folder() {
                    Some(dir) => write(&dir).map_err(|e| format!("{e:#}")),
                    None => {
                        Err("not exported (cancelled, or no file dialog on this desktop)".into())
                    }
                };
                let _ = tx.send(result);
            });
        self.pending = spawned.ok().map(|_| rx);
    }

    /// Once the export is over: where it went, or why it did not.
    pub fn finished(&mut self) -> Option<String> {
        let result = self.pending.as_ref()?.try_recv().ok()?;
        self.pending = None;
        Some(match result {
            Ok(dir) => format!("exported to {}", dir.display()),
            Err(e) => e,
        })
    }
}
