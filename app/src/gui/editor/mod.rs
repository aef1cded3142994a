//! Editing the scene live: what is selected (an object picked in the image
//! or the list, a light), the selection outlined on the image, moving the
//! selected object by dragging in the image plane, and the question asked
//! before unsaved edits are thrown away. The edits themselves go through
//! the edited side ([`super::sides::Side::edit`]); the window is
//! [`panel`].

mod lights_and_camera;
mod panel;

use egui::{Color32, Rect, Stroke, Ui, pos2};
use glam::Vec3A;
use tracer::geometry::Aabb;
use tracer::render::Frame;
use tracer::scene::edit::{Edit, GeometryChange, ObjectChange};

use super::image::viewport::Gesture;
use super::sides::{Engine, Side};
use crate::load::SceneSource;
use crate::measure::projection::Projector;

pub use panel::window;

/// What waits for the user's word because the scene has unsaved edits.
#[derive(Debug, Clone, PartialEq)]
pub enum Pending {
    Open(SceneSource),
    Reload,
}

/// The editor's state.
#[derive(Default)]
pub struct Editor {
    pub open: bool,
    /// The selected object (its index in the scene, as the inspector
    /// numbers them).
    pub selected: Option<usize>,
    /// The selected light.
    pub light: Option<usize>,
    /// The object list's filter.
    pub search: String,
    /// For a material several objects share: whether edits go to all of
    /// them (true) or the selected object alone, asked once per selection.
    pub shared_scope: Option<(usize, bool)>,
    /// The pixel whose eye hit the next selection takes (a click).
    pub pick_at: Option<(u32, u32)>,
    /// Left drag on the image moves the selected object instead of the
    /// camera.
    pub move_mode: bool,
    /// An open or reload waiting for the user's word on unsaved edits.
    pub pending: Option<Pending>,
    /// Why the last edit was refused.
    pub message: Option<String>,
    /// The selected object's box, and what it was made for (the world's
    /// address, the object).
    outline: Option<((usize, usize), Aabb)>,
}

impl Editor {
    /// Selects `object` (or nothing): the shared-material question is
    /// asked again for it.
    pub fn select(&mut self, object: Option<usize>) {
        if self.selected != object {
            self.shared_scope = None;
        }
        self.selected = object;
    }

    /// Draws the selected object's bounding box over the image of `engine`
    /// in `rect`, through the camera it renders with.
    pub fn paint_outline(&mut self, ui: &Ui, engine: &Engine, rect: Rect) {
        let (Some(object), Some(scene), Some(settings)) =
            (self.selected, engine.scene(), engine.settings())
        else {
            return;
        };
        let world = &scene.world;
        let key = (std::sync::Arc::as_ptr(world) as usize, object);
        if self.outline.as_ref().is_none_or(|(k, _)| *k != key) {
            let bounds = world
                .shape_object
                .iter()
                .zip(&world.shapes)
                .filter(|(o, _)| **o as usize == object)
                .filter_map(|(_, shape)| shape.bounds())
                .fold(Aabb::empty(), |b, s| b.union(&s));
            self.outline = Some((key, bounds));
        }
        let Some((_, bounds)) = &self.outline else {
            return;
        };
        if bounds.is_empty() {
            return;
        }
        let Ok(camera) = Frame::camera(world, settings) else {
            return;
        };
        let projector = Projector::new(&camera);
        let size = egui::vec2(settings.width as f32, settings.height as f32);
        let to_screen = |p: glam::Vec2| {
            let s = rect.min + egui::vec2(p.x, p.y) / size * rect.size();
            pos2(s.x, s.y)
        };
        let painter = ui.painter().with_clip_rect(rect.intersect(ui.clip_rect()));
        let stroke = Stroke::new(1.5, Color32::from_rgb(255, 170, 0));
        for [a, b] in box_edges(bounds) {
            if let Some([a, b]) = projector.segment(a, b) {
                painter.line_segment([to_screen(a), to_screen(b)], stroke);
            }
        }
    }

    /// In move mode, turns a drag over the image (`image_rect`, the image
    /// of `side`) into a translation of the selected object parallel to
    /// the image plane; returns the gestures that still move the camera.
    pub fn take_drag(
        &self,
        gestures: Vec<Gesture>,
        side: &Side,
        image_rect: Option<Rect>,
    ) -> (Vec<Gesture>, Option<Edit>) {
        let (true, Some(object), Some(rect)) = (self.move_mode, self.selected, image_rect) else {
            return (gestures, None);
        };
        let (Some(scene), Some(settings)) = (side.engine.scene(), side.engine.settings()) else {
            return (gestures, None);
        };
        let Ok(camera) = Frame::camera(&scene.world, settings) else {
            return (gestures, None);
        };
        let Some(centre) = self
            .outline
            .as_ref()
            .filter(|((_, o), b)| *o == object && !b.is_empty())
            .map(|(_, b)| b.centre())
        else {
            return (gestures, None);
        };
        let mut moved = Vec3A::ZERO;
        let mut rest = Vec::new();
        // Screen points per image pixel.
        let scale = rect.width() / settings.width.max(1) as f32;
        let projector = Projector::new(&camera);
        for gesture in gestures {
            let Gesture::Orbit { yaw, pitch } = gesture else {
                rest.push(gesture);
                continue;
            };
            // The viewport reports a drag of (dx, dy) points as a yaw of
            // -dx / 100 and a pitch of dy / 100 radians.
            let (dx, dy) = (-yaw * 100.0 / scale, pitch * 100.0 / scale);
            let Some(at) = projector.point(centre + moved) else {
                continue;
            };
            let eye = camera.eye();
            let depth = camera.depth(centre + moved);
            let plane = |x: f32, y: f32| {
                let through = camera.view_plane_point(x, y);
                eye + (through - eye) * (depth / camera.depth(through))
            };
            moved += plane(at.x + dx, at.y + dy) - plane(at.x, at.y);
        }
        let edit = (moved != Vec3A::ZERO).then(|| Edit::Object {
            index: object,
            change: ObjectChange::Geometry(GeometryChange::Translate(moved.into())),
        });
        (rest, edit)
    }
}

/// The 12 edges of `bounds`.
fn box_edges(bounds: &Aabb) -> Vec<[Vec3A; 2]> {
    let corner = |i: usize| {
        Vec3A::new(
            if i & 1 == 0 {
                bounds.min.x
            } else {
                bounds.max.x
            },
            if i & 2 == 0 {
                bounds.min.y
            } else {
                bounds.max.y
            },
            if i & 4 == 0 {
                bounds.min.z
            } else {
                bounds.max.z
            },
        )
    };
    let mut edges = Vec::with_capacity(12);
    for i in 0..8 {
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                edges.push([corner(i), corner(i | bit)]);
            }
        }
    }
    edges
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_box_has_twelve_edges_each_along_one_axis() {
        let edges = box_edges(&Aabb::new(Vec3A::ZERO, Vec3A::new(1.0, 2.0, 3.0)));
        assert_eq!(edges.len(), 12);
        for [a, b] in edges {
            let d = (b - a).abs();
            assert_eq!((d.cmpgt(Vec3A::ZERO)).bitmask().count_ones(), 1, "{a} {b}");
        }
    }
}
