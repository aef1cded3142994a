//! "Compare with image...": side B becomes a picture read from disk (a PNG,
//! JPEG or EXR from another renderer, or a figure made earlier) instead of
//! a second render. It is read off the UI thread, fitted to A's size only
//! when the user asks, and shown by every compare view.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, channel};

use egui::{ColorImage, TextureHandle, TextureOptions};
use image::RgbImage;
use tracer::render::Encoding;

use crate::gui::platform::target;
use crate::measure::ab::{FittedReference, fit_reference, read_reference};

/// The image side B shows.
pub struct ReferenceImage {
    pub(crate) path: PathBuf,
    /// As read from the file (EXR already encoded like A).
    original: RgbImage,
    /// Resize it to A's size instead of refusing a mismatch.
    pub(crate) fit: bool,
    fitted: Option<Fitted>,
    texture: Option<TextureHandle>,
}

/// The image at A's size (or why not), and the size and fit it was made for.
struct Fitted {
    size: (u32, u32),
    fit: bool,
    result: Result<FittedReference, String>,
}

/// What the dialog thread sends: nothing picked, or the file read.
type Picked = Option<Result<(PathBuf, RgbImage), String>>;

/// A file dialog and the read, on their own thread.
pub(crate) struct PendingReference(Receiver<Picked>);

impl PendingReference {
    /// Asks for an image file and reads it (`None` when cancelled).
    pub(crate) fn pick(
        encoding: Encoding,
        wake: impl Fn() + Send + 'static,
    ) -> Option<PendingReference> {
        let (tx, rx) = channel();
        target::spawn("reference-dialog", move || {
            let picked = target::FileDialog::new()
                .add_filter("Images", &["png", "jpg", "jpeg", "exr"])
                .pick_file();
            let result = picked.map(|path| read(&path, encoding));
            let _ = tx.send(result);
            wake();
        })
        .ok()?;
        Some(PendingReference(rx))
    }

    /// The dialog's outcome once there is one: `Some(None)` when nothing
    /// was picked.
    pub(crate) fn poll(&self) -> Option<Option<Result<ReferenceImage, String>>> {
        let picked = self.0.try_recv().ok()?;
        Some(picked.map(|r| r.map(|(path, image)| ReferenceImage::new(path, image))))
    }
}

/// Reads `path` as [`read_reference`] does, the error as text.
fn read(path: &Path, encoding: Encoding) -> Result<(PathBuf, RgbImage), String> {
    read_reference(path, encoding)
        .map(|image| (path.to_path_buf(), image))
        .map_err(|e| format!("{e:#}"))
}

impl ReferenceImage {
    pub(crate) fn new(path: PathBuf, original: RgbImage) -> Self {
        Self {
            path,
            original,
            fit: false,
            fitted: None,
            texture: None,
        }
    }

    /// Reads `path` on the calling thread (tests, and files given by name).
    pub(crate) fn open(path: &Path, encoding: Encoding) -> Result<Self, String> {
        read(path, encoding).map(|(path, image)| Self::new(path, image))
    }

    /// "B: image NAME", for the comparison's labels.
    pub fn label(&self) -> String {
        let name = self.path.file_name().map_or_else(
            || self.path.display().to_string(),
            |n| n.to_string_lossy().into(),
        );
        format!("B: image {name}")
    }

    /// The image at A's `size`, or why it cannot be compared at it.
    pub(crate) fn at_size(&mut self, size: (u32, u32)) -> &Result<FittedReference, String> {
        let stale = !matches!(&self.fitted, Some(f) if f.size == size && f.fit == self.fit);
        if stale {
            self.fitted = None;
            self.texture = None;
        }
        let (fit, original) = (self.fit, &self.original);
        &self
            .fitted
            .get_or_insert_with(|| Fitted {
                size,
                fit,
                result: fit_reference(original.clone(), size, fit).map_err(|e| format!("{e:#}")),
            })
            .result
    }

    /// The texture of what B shows: the fitted image, or the file's own
    /// when it cannot be fitted (the numbers then say why).
    pub(crate) fn texture(&mut self, ctx: &egui::Context, size: (u32, u32)) -> TextureHandle {
        self.at_size(size);
        if let Some(texture) = &self.texture {
            return texture.clone();
        }
        let shown = match &self.fitted {
            Some(Fitted {
                result: Ok(reference),
                ..
            }) => &reference.image,
            _ => &self.original,
        };
        let (w, h) = shown.dimensions();
        let image = ColorImage::from_rgb([w as usize, h as usize], shown.as_raw());
        let texture = ctx.load_texture("reference B", image, TextureOptions::NEAREST);
        self.texture = Some(texture.clone());
        texture
    }
}
