//! A render on screen: the GPU texture of an engine's latest image, uploaded
//! when it changed and at most at the progress pace, with the snapshot it
//! came from (for the pixel readout, the statistics and saving).

use std::time::{Duration, Instant};

use egui::{ColorImage, TextureHandle, TextureOptions};
use tracer::render::{Encoding, Snapshot, View, ViewHeatmap};

use super::engine::{Engine, Version};

pub struct LiveImage {
    /// The texture's name for egui.
    name: &'static str,
    texture: Option<TextureHandle>,
    shown: Option<Snapshot>,
    version: Version,
    encoding: Encoding,
    /// The view to show instead of the shaded image, with its heat map.
    view: Option<(View, ViewHeatmap)>,
    /// The view of the image on screen.
    shown_view: Option<(View, ViewHeatmap)>,
    last_upload: Instant,
}

impl LiveImage {
    pub fn new(name: &'static str) -> Self {
        Self {
            name,
            texture: None,
            shown: None,
            version: (0, 0),
            encoding: Encoding::Linear,
            view: None,
            shown_view: None,
            last_upload: Instant::now(),
        }
    }

    /// Uploads `engine`'s image when it changed (or the encoding did), at
    /// most every `interval`; asks for a later frame when it must wait.
    pub fn refresh(
        &mut self,
        ctx: &egui::Context,
        engine: &Engine,
        encoding: Encoding,
        interval: Duration,
    ) {
        let version = engine.version();
        let same_view = self.view == self.shown_view;
        if version == self.version && encoding == self.encoding && same_view && self.shown.is_some()
        {
            return;
        }
        let since = self.last_upload.elapsed();
        if since < interval && self.shown.is_some() && same_view {
            ctx.request_repaint_after(interval - since);
            return;
        }
        let snapshot = match &self.view {
            Some((view, heat)) => engine.view_snapshot(*view, heat, encoding),
            None => engine.snapshot(encoding),
        };
        let Some(snapshot) = snapshot else {
            return;
        };
        let image = ColorImage::from_rgba_unmultiplied(
            [snapshot.width as usize, snapshot.height as usize],
            &snapshot.rgba,
        );
        let options = TextureOptions {
            magnification: egui::TextureFilter::Nearest,
            minification: egui::TextureFilter::Linear,
            ..TextureOptions::default()
        };
        match &mut self.texture {
            Some(texture) => texture.set(image, options),
            None => self.texture = Some(ctx.load_texture(self.name, image, options)),
        }
        self.shown = Some(snapshot);
        self.version = version;
        self.encoding = encoding;
        self.shown_view = self.view;
        self.last_upload = Instant::now();
    }

    /// Shows `view` (with its heat map) instead of the shaded image from
    /// the next refresh on; `None` for the shaded image.
    pub fn set_view(&mut self, view: Option<(View, ViewHeatmap)>) {
        self.view = view;
    }

    pub fn texture(&self) -> Option<&TextureHandle> {
        self.texture.as_ref()
    }

    /// The snapshot on screen.
    pub fn shown(&self) -> Option<&Snapshot> {
        self.shown.as_ref()
    }

    /// Whether the screen shows `engine`'s latest image.
    pub fn is_current(&self, engine: &Engine) -> bool {
        self.shown.is_some() && self.version == engine.version()
    }

    /// Forgets the snapshot (a new scene): the texture stays on screen
    /// until the new image replaces it.
    pub fn forget(&mut self) {
        self.shown = None;
    }
}
