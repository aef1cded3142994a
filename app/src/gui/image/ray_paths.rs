//! The pinned pixel's rays drawn over the image through the camera: the
//! same colours for each kind of ray wherever rays are drawn.

use egui::{Color32, Pos2, Rect, Stroke, Ui, pos2};
use glam::Vec3A;
use tracer::render::{Outcome, RayKind, RayNode, RayTree};

use crate::gui::sides::Engine;

/// Draws `tree` (side A's pinned pixel) over the image in `image_rect`:
/// every ray from its origin to its hit projected through the camera of
/// `engine`'s render, coloured by kind; shadow rays to their light sample,
/// dashed when blocked; rays that leave the scene as a short stub. Returns
/// the segments drawn.
pub(crate) fn paint(ui: &Ui, tree: &RayTree, engine: &Engine, image_rect: Rect) -> usize {
    let (Some(settings), Some(scene)) = (engine.settings(), engine.scene()) else {
        return 0;
    };
    let Ok(camera) = settings.render_camera(&scene.world.view) else {
        return 0;
    };
    let size = egui::vec2(settings.width as f32, settings.height as f32);
    let to_screen = |p: Vec3A| {
        let p = camera.project(p)?;
        let s = image_rect.min + egui::vec2(p.x, p.y) / size * image_rect.size();
        s.is_finite().then(|| pos2(s.x, s.y))
    };
    let stub = scene.world.bounds.extent().length().max(1.0) * 0.25;
    let painter = ui
        .painter()
        .with_clip_rect(image_rect.intersect(ui.clip_rect()));
    let mut drawn = 0;
    for node in &tree.nodes {
        let (end, blocked) = path_end(node, stub);
        let (Some(a), Some(b)) = (to_screen(node.origin), to_screen(end)) else {
            continue;
        };
        segment(
            &painter,
            [a, b],
            Stroke::new(2.0, kind_colour(node.kind)),
            blocked,
        );
        drawn += 1;
    }
    drawn
}

/// A ray's segment on screen: dashed where it was blocked or hidden, the
/// same dashes in the image and in the observer view.
pub(crate) fn segment(painter: &egui::Painter, [a, b]: [Pos2; 2], stroke: Stroke, dashed: bool) {
    if dashed {
        painter.extend(egui::Shape::dashed_line(&[a, b], stroke, 6.0, 4.0));
    } else {
        painter.line_segment([a, b], stroke);
    }
}

/// Where a ray's drawn path ends, and whether it was blocked.
fn path_end(node: &RayNode, stub: f32) -> (Vec3A, bool) {
    match &node.outcome {
        Outcome::Surface(s) => (s.point, false),
        Outcome::Background => (node.origin + node.dir * stub, false),
        Outcome::Light {
            distance, occluder, ..
        } => (node.origin + node.dir * *distance, occluder.is_some()),
    }
}

/// The colour of each kind of ray, in the paths and nowhere else.
fn kind_colour(kind: RayKind) -> Color32 {
    match kind {
        RayKind::Eye => Color32::from_rgb(255, 255, 255),
        RayKind::Reflection => Color32::from_rgb(90, 200, 255),
        RayKind::Refraction => Color32::from_rgb(255, 120, 220),
        RayKind::Shadow => Color32::from_rgb(255, 220, 60),
    }
}
