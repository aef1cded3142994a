//! The observer's figure painted over its image: the scene camera with
//! side A's render on its image plane, the lights, the structure, and the
//! recorded rays growing as the animation says; solid where the observer
//! sees them, faint where its render's surfaces hide them.

use egui::epaint::{Mesh, Vertex};
use egui::{Color32, Pos2, Rect, Stroke, Ui, pos2};
use glam::Vec2;

use super::Observer;
use crate::figures::observer::{self, Part};
use crate::figures::overlay::{Colour, VisitStep};
use crate::figures::projection::Projector;
use crate::gui::image::ray_paths;
use crate::gui::image::structure_overlay::StructureOverlay;
use crate::gui::sides::Side;

/// Pieces a segment is cut into to find where it is hidden.
const PIECES: usize = 16;
/// Most segments painted in a frame: the window stays interactive with a
/// grid of pixels' trees.
const MAX_PAINTED: usize = 4000;
/// Cells of the image plane's grid per side (the texture is mapped per
/// cell, so a coarse grid would bend it).
const PLANE_CELLS: usize = 12;

/// Paints the figure over the observer's image in `rect`, the eye ray's
/// walk as far as `step`; returns the segments painted.
pub(crate) fn paint(
    ui: &Ui,
    rect: Rect,
    observer: &Observer,
    a: &Side,
    overlay: &StructureOverlay,
    step: VisitStep,
) -> usize {
    let Some(scene) = a.engine.scene() else {
        return 0;
    };
    let world = &scene.world;
    let (Some(camera), Some(a_settings)) = (observer.camera(world), a.engine.settings()) else {
        return 0;
    };
    let Ok(scene_camera) = a_settings.render_camera(&world.view) else {
        return 0;
    };
    let projector = Projector::new(&camera);
    let depth = observer.depth();
    let size = Vec2::new(camera.width() as f32, camera.height() as f32);
    let to_screen = |p: Vec2| -> Pos2 {
        let s = rect.min + egui::vec2(p.x / size.x, p.y / size.y) * rect.size();
        pos2(s.x, s.y)
    };
    let painter = ui.painter().with_clip_rect(rect.intersect(ui.clip_rect()));

    // The image plane, showing A's render.
    if let Some(texture) = a.image.texture() {
        let corners = observer::image_corners(&scene_camera);
        let mut mesh = Mesh::with_texture(texture.id());
        let at = |u: f32, v: f32| {
            let top = corners[0] + (corners[1] - corners[0]) * u;
            let bottom = corners[3] + (corners[2] - corners[3]) * u;
            top + (bottom - top) * v
        };
        for j in 0..PLANE_CELLS {
            for i in 0..PLANE_CELLS {
                let (u0, v0) = (i as f32 / PLANE_CELLS as f32, j as f32 / PLANE_CELLS as f32);
                let (u1, v1) = (u0 + 1.0 / PLANE_CELLS as f32, v0 + 1.0 / PLANE_CELLS as f32);
                let points = [(u0, v0), (u1, v0), (u1, v1), (u0, v1)];
                let projected: Option<Vec<Pos2>> = points
                    .iter()
                    .map(|&(u, v)| projector.point(at(u, v)).map(&to_screen))
                    .collect();
                let Some(projected) = projected else {
                    continue;
                };
                let centre = at((u0 + u1) * 0.5, (v0 + v1) * 0.5);
                let hidden = depth.is_some_and(|d| d.hides(&projector, centre));
                let alpha = if hidden { 40 } else { 130 };
                let tint = Color32::from_white_alpha(alpha);
                let base = mesh.vertices.len() as u32;
                for (p, &(u, v)) in projected.iter().zip(&points) {
                    mesh.vertices.push(Vertex {
                        pos: *p,
                        uv: pos2(u, v),
                        color: tint,
                    });
                }
                mesh.indices
                    .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
            }
        }
        painter.add(mesh);
    }

    let mut segments = observer::camera_segments(&scene_camera);
    segments.extend(observer::light_segments(world, a_settings));
    if overlay.on
        && let Some(index) = a.engine.index()
    {
        let visits = observer
            .trees
            .iter()
            .find(|(side, _)| *side == 0)
            .map_or(&[][..], |(_, t)| &t.eye_visits[..]);
        let layer = overlay.layer(index.kind());
        segments.extend(observer::structure_segments(&index, layer, visits, step));
    }
    let stub = observer::stub_length(world);
    for (side, tree) in &observer.trees {
        if segments.len() >= MAX_PAINTED {
            break;
        }
        segments.extend(observer::filtered_ray_segments(
            tree,
            stub,
            *side,
            &observer.filter,
        ));
    }
    segments.truncate(MAX_PAINTED);

    let mut painted = 0;
    for segment in &segments {
        let Some([a, b]) = projector.clip(segment.ends[0], segment.ends[1]) else {
            continue;
        };
        let grown = observer.animation.fraction(segment.phase);
        if grown <= 0.0 {
            continue;
        }
        let pieces = match depth {
            Some(depth) => depth.split_params(&projector, [a, b], PIECES),
            None => vec![([0.0, 1.0], false)],
        };
        let (colour, dashed) = observer::style(segment, world);
        let width = match segment.part {
            Part::Ray { .. }
            | Part::BlockedShadow
            | Part::Visit {
                colour: Colour::Current,
            } => 2.0,
            _ => 1.0,
        };
        for ([t0, t1], hidden) in pieces {
            if t0 >= grown {
                break;
            }
            let along = |t: f32| a + (b - a) * t;
            let Some([p, q]) = projector.segment(along(t0), along(t1.min(grown))) else {
                continue;
            };
            let mut alpha = if hidden { 80.0 } else { 255.0 };
            if observer.fade && matches!(segment.part, Part::Ray { .. } | Part::BlockedShadow) {
                // Never quite invisible: a faded ray still says it exists.
                alpha *= 0.12 + 0.88 * segment.share.sqrt();
            }
            let alpha = alpha as u8;
            let [r, g, bl] = colour;
            let stroke = Stroke::new(width, Color32::from_rgba_unmultiplied(r, g, bl, alpha));
            ray_paths::segment(&painter, [to_screen(p), to_screen(q)], stroke, dashed);
        }
        painted += 1;
    }
    painted
}
