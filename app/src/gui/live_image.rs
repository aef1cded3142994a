//! A render on screen: the GPU texture of an engine's latest image, uploaded
//! when it changed and at most at the progress pace, with the snapshot it
//! came from (for the pixel readout, the statistics and saving).

use std::time::{Duration, Instant};

use egui::{ColorImage, TextureHandle, TextureOptions};
use tracer::render::{Encoding, Snapshot};

use super::engine::{Engine, Version};

pub struct LiveImage {
    /// The texture's name for egui.
    name: &'static str,
    texture: Option<TextureHandle>,
    shown: Option<Snapshot>,
    version: Version,
    encoding: Encoding,
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
        if version == self.version && encoding == self.encoding && self.shown.is_some() {
            return;
        }
        let since = self.last_upload.elapsed();
        if since < interval && self.shown.is_some() {
            ctx.request_repaint_after(interval - since);
            return;
        }
        let Some(snapshot) = engine.snapshot(encoding) else {
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
        self.last_upload = Instant::now();
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
