//! The acceleration structure drawn over the image in the window: the
//! BVH's boxes at a chosen depth (or its leaves), or the grid's box and
//! lattice, projected through the current camera each frame, so the
//! wireframe follows camera moves before the image re-renders. With a
//! pinned pixel, the cells or nodes its eye ray visited are drawn on top.

use egui::{Color32, Rect, Stroke, Ui, pos2};
use glam::Vec3A;
use tracer::accel::{AccelKind, StructureLayer, Visit};

use crate::figures::overlay::{Colour, VisitStep};
use crate::figures::projection::Projector;
use crate::gui::sides::Engine;

/// The overlay's controls and the segments of the structure it draws.
#[derive(Default)]
pub struct StructureOverlay {
    pub(crate) on: bool,
    /// BVH depth to draw (the root is 0).
    pub(crate) depth: u32,
    /// Draw every BVH leaf instead of one depth.
    pub(crate) leaves: bool,
    /// The segments and what they were made from.
    cache: Option<(CacheKey, Vec<[Vec3A; 2]>)>,
    /// Cells or nodes of the inspected pixel's eye ray drawn in the last
    /// frame.
    pub visits_drawn: usize,
}

/// The structure (its address: one per build) and the layer drawn.
type CacheKey = (usize, StructureLayer);

impl StructureOverlay {
    /// The side panel's controls.
    pub(crate) fn ui(&mut self, ui: &mut Ui) {
        ui.checkbox(&mut self.on, "Structure overlay")
            .on_hover_text("Draw the BVH's boxes or the grid's cells over the image");
        if self.on {
            ui.horizontal(|ui| {
                ui.add_enabled(
                    !self.leaves,
                    egui::Slider::new(&mut self.depth, 0..=24).text("BVH depth"),
                );
                ui.checkbox(&mut self.leaves, "leaves");
            });
        }
    }

    /// The layer for the structure `engine` renders with, if it has one.
    pub(crate) fn layer(&self, kind: AccelKind) -> Option<StructureLayer> {
        match kind {
            AccelKind::Bvh if self.leaves => Some(StructureLayer::BvhLeaves),
            AccelKind::Bvh => Some(StructureLayer::BvhDepth(self.depth)),
            AccelKind::Grid => Some(StructureLayer::Grid),
            AccelKind::None => None,
        }
    }

    /// How many segments are drawn (0 when off or without a structure).
    pub fn segments(&self) -> usize {
        if self.on {
            self.cache.as_ref().map_or(0, |(_, s)| s.len())
        } else {
            0
        }
    }

    /// Draws the structure of `engine`'s current job over `image_rect`
    /// through the camera of its current settings, and over it the cells
    /// or nodes of `visits` (the inspected pixel's eye ray) that `step`
    /// draws, yellow to red in visiting order.
    pub(crate) fn paint(
        &mut self,
        ui: &Ui,
        engine: &Engine,
        image_rect: Rect,
        visits: &[Visit],
        step: VisitStep,
    ) {
        self.visits_drawn = 0;
        if !self.on {
            return;
        }
        let (Some(index), Some(settings), Some(scene)) =
            (engine.index(), engine.settings(), engine.scene())
        else {
            return;
        };
        let Some(layer) = self.layer(index.kind()) else {
            return;
        };
        let key = (std::sync::Arc::as_ptr(&index) as usize, layer);
        if self.cache.as_ref().is_none_or(|(k, _)| *k != key) {
            self.cache = Some((key, index.wireframe(layer)));
        }
        let Ok(camera) = settings.render_camera(&scene.world.view) else {
            return;
        };
        let size = egui::vec2(settings.width as f32, settings.height as f32);
        let to_screen =
            |p: glam::Vec2| image_rect.min + egui::vec2(p.x, p.y) / size * image_rect.size();
        let painter = ui
            .painter()
            .with_clip_rect(image_rect.intersect(ui.clip_rect()));
        let projector = Projector::new(&camera);
        let line = |[a, b]: [Vec3A; 2], stroke: Stroke| {
            if let Some([a, b]) = projector.segment(a, b) {
                let (a, b) = (to_screen(a), to_screen(b));
                painter.line_segment([pos2(a.x, a.y), pos2(b.x, b.y)], stroke);
            }
        };
        let stroke = Stroke::new(1.0, Color32::from_rgb(80, 255, 120));
        for segment in self.cache.iter().flat_map(|(_, s)| s) {
            line(*segment, stroke);
        }
        // Only visits of the structure drawn: for one frame after a switch
        // the inspector still holds the other structure's.
        let grid = layer == StructureLayer::Grid;
        if visits
            .first()
            .is_some_and(|v| matches!(v, Visit::Cell { .. }) != grid)
        {
            return;
        }
        for (visit, colour) in step.coloured(visits) {
            let [r, g, b] = colour.rgb();
            let width = if colour == Colour::Current { 3.0 } else { 2.0 };
            let stroke = Stroke::new(width, Color32::from_rgb(r, g, b));
            for segment in visit.edges() {
                line(segment, stroke);
            }
        }
        self.visits_drawn = step.drawn(visits.len());
    }
}
