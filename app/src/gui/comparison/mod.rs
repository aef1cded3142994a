//! Compare mode beyond the two sides themselves: how they are laid out
//! (side by side, split by a divider, flipped, or their difference), B as
//! an image from disk instead of a render ([`reference`]), and what is
//! measured of the pair ([`measures`]: the difference map, MSE, PSNR and
//! FLIP, or with a cost view on the values' difference).

mod measures;
mod reference;

use std::path::Path;
use std::sync::mpsc::Receiver;

use egui::TextureHandle;
use tracer::render::{Encoding, View};

use crate::measure::ab::{Match, Metrics};
use crate::measure::value_difference::ValueDifference;

use reference::PendingReference;
pub use reference::ReferenceImage;

use super::platform::waker;
use super::sides::{Side, Version};

/// How the two renders are shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompareLayout {
    SideBySide,
    /// A left of a draggable divider, B right of it.
    Split,
    /// A, or B while the flip key is held.
    Flip,
    /// |A - B| as a heat map (A - B of the values with a view on).
    Difference,
}

impl CompareLayout {
    pub const ALL: [CompareLayout; 4] = [
        CompareLayout::SideBySide,
        CompareLayout::Split,
        CompareLayout::Flip,
        CompareLayout::Difference,
    ];

    pub fn label(self) -> &'static str {
        match self {
            CompareLayout::SideBySide => "Side by side",
            CompareLayout::Split => "Split",
            CompareLayout::Flip => "Flip",
            CompareLayout::Difference => "Difference",
        }
    }
}

/// The versions of A and B and the view a values' difference is of.
type ValuesKey = (Version, Version, View);

/// The comparison's choices and results; reset when compare mode ends.
pub struct Comparison {
    pub layout: CompareLayout,
    /// Divider of the split view, as a fraction of the image width.
    pub(crate) split: f32,
    /// Amplification of the difference heat map.
    pub(crate) gain: f32,
    difference: Option<TextureHandle>,
    /// What the difference map was made from: the images' versions, its
    /// gain, and the view whose values it shows (`None`: the images).
    difference_of: Option<(Version, Version, f32, Option<View>)>,
    /// The values' difference while a view is on, and what it is of.
    values: Option<(ValuesKey, ValueDifference)>,
    /// Metrics of the last pair of finished images, and the versions they
    /// belong to; FLIP runs on its own thread.
    metrics: Option<Result<Metrics, String>>,
    metrics_of: Option<(Version, Version)>,
    pending: Option<Receiver<Result<Metrics, String>>>,
    /// The image B shows instead of its render, when one was chosen.
    reference: Option<ReferenceImage>,
    /// Counts changes of the reference (or its fit), as B's version.
    reference_changes: u64,
    picking: Option<PendingReference>,
    /// Why the last image picked could not be read.
    pub(crate) picking_error: Option<String>,
    /// B adaptive at A's cost: it renders once A is done, stopped at A's
    /// samples or A's time.
    pub(crate) b_matches: Option<Match>,
}

impl Default for Comparison {
    fn default() -> Self {
        Self {
            layout: CompareLayout::SideBySide,
            split: 0.5,
            gain: 8.0,
            difference: None,
            difference_of: None,
            values: None,
            metrics: None,
            metrics_of: None,
            pending: None,
            reference: None,
            reference_changes: 0,
            picking: None,
            picking_error: None,
            b_matches: None,
        }
    }
}

impl Comparison {
    /// Makes `reference` side B (or a render again with `None`).
    pub(crate) fn set_reference(&mut self, reference: Option<ReferenceImage>) {
        self.reference = reference;
        self.reference_changes += 1;
        self.forget_results();
    }

    /// Makes the image at `path` side B; why it cannot be read shows under
    /// the reference controls. Read on the calling thread (the file dialog
    /// reads on its own).
    pub(crate) fn open_reference(&mut self, path: &Path, encoding: Encoding) {
        match ReferenceImage::open(path, encoding) {
            Ok(reference) => {
                self.picking_error = None;
                self.set_reference(Some(reference));
            }
            Err(message) => self.picking_error = Some(message),
        }
    }

    /// Whether the reference image is resized to A's size.
    pub(crate) fn set_fit(&mut self, fit: bool) {
        if let Some(reference) = &mut self.reference {
            reference.fit = fit;
            self.reference_changes += 1;
            self.forget_results();
        }
    }

    /// The image B shows instead of a render, if any.
    pub fn reference(&self) -> Option<&ReferenceImage> {
        self.reference.as_ref()
    }

    /// Opens the file dialog for an image as B; `encoding` is A's, for EXR
    /// files.
    pub(crate) fn pick_reference(&mut self, encoding: Encoding, ctx: &egui::Context) {
        self.picking = PendingReference::pick(encoding, waker(ctx));
    }

    /// Whether the file dialog for an image is open.
    pub(crate) fn is_picking(&self) -> bool {
        self.picking.is_some()
    }

    /// Takes the image the dialog read, once it is done.
    pub(crate) fn receive_picked(&mut self) {
        let Some(outcome) = self.picking.as_ref().and_then(PendingReference::poll) else {
            return;
        };
        self.picking = None;
        self.picking_error = None;
        match outcome {
            Some(Ok(reference)) => self.set_reference(Some(reference)),
            Some(Err(message)) => self.picking_error = Some(message),
            None => {
                self.picking_error =
                    Some("no image picked (cancelled, or no file dialog on this desktop)".into())
            }
        }
    }

    /// B's version: its render's, or the reference image's.
    fn b_version(&self, b: &Side) -> Version {
        match self.reference {
            Some(_) => (u64::MAX, self.reference_changes),
            None => b.engine.version(),
        }
    }

    /// B's textures at A's `size`, bottom first: the reference image, or
    /// B's render over its backdrop.
    pub(crate) fn b_layers(
        &mut self,
        ctx: &egui::Context,
        b: &Side,
        size: (u32, u32),
    ) -> Vec<TextureHandle> {
        match &mut self.reference {
            Some(reference) => vec![reference.texture(ctx, size)],
            None => b.image.layers().textures.into_iter().cloned().collect(),
        }
    }

    /// Whether B's textures cover its image with opaque pixels: a finished
    /// first pass (or backdrop) of its render; a reference image may have
    /// transparent pixels of its own.
    pub(crate) fn b_is_opaque(&self, b: &Side) -> bool {
        self.reference.is_none() && b.image.is_opaque()
    }

    /// A opened another scene: what was measured of the last one goes.
    pub(crate) fn forget_results(&mut self) {
        self.metrics = None;
        self.metrics_of = None;
        self.pending = None;
        self.difference_of = None;
        self.values = None;
    }

    /// The values' difference and statistics while a cost view is on.
    pub fn value_difference(&self) -> Option<(View, &ValueDifference)> {
        self.values.as_ref().map(|((_, _, view), d)| (*view, d))
    }

    /// The difference heat map, once made.
    pub fn difference(&self) -> Option<&TextureHandle> {
        self.difference.as_ref()
    }

    /// The image metrics of the finished pair, if computed.
    pub fn metrics(&self) -> Option<&Result<Metrics, String>> {
        self.metrics.as_ref()
    }

    /// Whether the metrics are being computed.
    pub(crate) fn is_measuring(&self) -> bool {
        self.pending.is_some()
    }
}
