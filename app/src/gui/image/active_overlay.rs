//! Adaptive sampling's active pixels tinted over the image: the pixels
//! the next pass still refines, as the render decided after its last
//! pass. The tint shrinks to the edges and noisy areas as pixels stop,
//! and is gone once the render converged (a render its budget stopped
//! leaves the pixels still above the threshold tinted), so a user sees
//! where the samples are going while they go there (the samples view
//! shows where they went).

use egui::{Color32, ColorImage, Rect, TextureHandle, TextureOptions, Ui, pos2};

use crate::gui::sides::{Engine, Version};

/// An active pixel's tint (unmultiplied RGBA): magenta, rare in renders,
/// light enough to see the image through.
const TINT: [u8; 4] = [255, 0, 200, 110];

/// The overlay's switch and the texture of the last mask drawn.
#[derive(Default)]
pub struct ActiveOverlay {
    pub on: bool,
    texture: Option<TextureHandle>,
    /// The engine's version the mask was read at, and the mask: it
    /// changes only between passes, so the texture is made again only
    /// when it did.
    mask: Option<(Version, Vec<bool>)>,
}

impl ActiveOverlay {
    /// The side panel's switch, beside the adaptive controls.
    pub(crate) fn ui(&mut self, ui: &mut Ui) {
        ui.checkbox(&mut self.on, "Show active pixels")
            .on_hover_text(
                "Tint the pixels adaptive sampling still refines over side A's image; they \
             disappear as each pixel's error falls below the threshold",
            );
    }

    /// Active pixels drawn in the last frame: 0 when off, without an
    /// adaptive render, or once it is done.
    pub fn active_drawn(&self) -> usize {
        match (&self.mask, self.on) {
            (Some((_, mask)), true) => mask.iter().filter(|&&active| active).count(),
            _ => 0,
        }
    }

    /// Tints `engine`'s active pixels over `image_rect`.
    pub(crate) fn paint(&mut self, ui: &Ui, engine: &Engine, image_rect: Rect) {
        if !self.on {
            return;
        }
        let version = engine.version();
        if self.mask.as_ref().is_none_or(|(seen, _)| *seen != version) {
            self.update(ui.ctx(), engine, version);
        }
        if let (Some(texture), true) = (&self.texture, self.active_drawn() > 0) {
            let uv = Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0));
            ui.painter()
                .image(texture.id(), image_rect, uv, Color32::WHITE);
        }
    }

    /// Reads the engine's mask at `version`; makes the texture again when
    /// the mask changed.
    fn update(&mut self, ctx: &egui::Context, engine: &Engine, version: Version) {
        let Some((size, mask)) = engine.active_pixels() else {
            self.mask = Some((version, Vec::new()));
            return;
        };
        if self.mask.as_ref().is_some_and(|(_, old)| *old == mask) {
            self.mask = Some((version, mask));
            return;
        }
        let rgba: Vec<u8> = mask
            .iter()
            .flat_map(|&active| if active { TINT } else { [0; 4] })
            .collect();
        let image = ColorImage::from_rgba_unmultiplied(size, &rgba);
        let options = TextureOptions {
            magnification: egui::TextureFilter::Nearest,
            ..TextureOptions::default()
        };
        match &mut self.texture {
            Some(texture) => texture.set(image, options),
            None => self.texture = Some(ctx.load_texture("active pixels", image, options)),
        }
        self.mask = Some((version, mask));
    }
}
