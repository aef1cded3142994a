//! A render on screen: the GPU texture of an engine's latest image, uploaded
//! when it changed and at most at the progress pace, with the snapshot it
//! came from (for the pixel readout, the statistics and saving). A restarted
//! render (a camera move) draws over the last image until it covers it.

use std::time::Duration;

use web_time::Instant;

use egui::{ColorImage, TextureHandle, TextureOptions};
use tracer::render::{Encoding, JobState, Snapshot, View, ViewHeatmap};

use super::engine::{Activity, Engine, Version};
use crate::gui::image::viewport::Layers;

/// Slowest refresh while a render's first pass has not covered the view.
const FIRST_PASS_INTERVAL: Duration = Duration::from_millis(200);

pub struct LiveImage {
    /// The texture's name for egui.
    name: &'static str,
    texture: Option<TextureHandle>,
    /// The previous render's last complete image, drawn under the current
    /// one until the current one has a sample in every pixel, so a restart
    /// never shows an empty view.
    backdrop: Option<TextureHandle>,
    /// Whether the backdrop has a sample in every pixel.
    backdrop_covered: bool,
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
    pub(crate) fn new(name: &'static str) -> Self {
        Self {
            name,
            texture: None,
            backdrop: None,
            backdrop_covered: false,
            shown: None,
            version: (0, 0),
            encoding: Encoding::Linear,
            view: None,
            shown_view: None,
            last_upload: Instant::now(),
        }
    }

    /// Uploads `engine`'s image when it changed (or the encoding did), at
    /// most every `interval` while it renders; asks for a later frame when
    /// it must wait. A finished render (or its last pass) is uploaded at
    /// once: its last image must reach the screen.
    pub(crate) fn refresh(
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
        let rendering = matches!(
            engine.activity(),
            Activity::Job(JobState::Rendering | JobState::Building)
        ) && !engine.is_complete();
        // A first pass shows its tiles sooner: until it covers the view,
        // the user sees holes or the previous image.
        let first_pass =
            version.0 != self.version.0 || self.shown.as_ref().is_some_and(|s| !is_covered(s));
        let interval = if first_pass {
            interval.min(FIRST_PASS_INTERVAL)
        } else {
            interval
        };
        let since = self.last_upload.elapsed();
        if rendering && since < interval && self.shown.is_some() && same_view {
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
        if version.0 != self.version.0 {
            self.keep_as_backdrop();
        }
        if is_covered(&snapshot) {
            self.backdrop = None;
        }
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
    pub(crate) fn set_view(&mut self, view: Option<(View, ViewHeatmap)>) {
        self.view = view;
    }

    /// A new render starts: the texture on screen goes under it, unless it
    /// has holes and an older complete image is already there.
    fn keep_as_backdrop(&mut self) {
        let complete = self.shown.as_ref().is_some_and(is_covered);
        if complete || self.backdrop.is_none() {
            // The old backdrop's texture is reused for the new render.
            std::mem::swap(&mut self.texture, &mut self.backdrop);
            self.backdrop_covered = complete;
        }
    }

    /// The textures to draw, bottom first: the backdrop while the render
    /// has holes, then the render.
    pub(crate) fn layers(&self) -> Layers<'_> {
        Layers {
            textures: self.backdrop.iter().chain(&self.texture).collect(),
            opaque: self.is_opaque(),
        }
    }

    /// Whether the layers have no hole: the render or its backdrop has a
    /// sample in every pixel.
    pub(crate) fn is_opaque(&self) -> bool {
        let backdrop_covers = self.backdrop.is_some() && self.backdrop_covered;
        backdrop_covers || self.shown.as_ref().is_some_and(is_covered)
    }

    /// The render's own texture (without the backdrop).
    pub(crate) fn texture(&self) -> Option<&TextureHandle> {
        self.texture.as_ref()
    }

    /// The snapshot on screen.
    pub(crate) fn shown(&self) -> Option<&Snapshot> {
        self.shown.as_ref()
    }

    /// Whether the screen shows `engine`'s latest image.
    pub fn is_current(&self, engine: &Engine) -> bool {
        self.shown.is_some() && self.version == engine.version()
    }

    /// Forgets the snapshot (a new scene): the texture stays on screen
    /// until the new image replaces it.
    pub(crate) fn forget(&mut self) {
        self.shown = None;
    }
}

/// Whether every pixel of `snapshot` has a sample (a first pass finished).
fn is_covered(snapshot: &Snapshot) -> bool {
    snapshot.stats.passes_done >= 1
}
