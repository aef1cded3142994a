//! Editing the scene live: what is selected (an object picked in the image
//! or the list, a light), the selection outlined on the image, moving the
//! selected object by dragging in the image plane, and the question asked
//! before unsaved edits are thrown away. The edits themselves go through
//! the edited side ([`super::sides::Side::edit`]); the window is
//! [`panel`].

mod in_observer;
mod lights_and_camera;
mod panel;

use std::sync::Arc;

use egui::{Color32, Rect, Stroke, Ui, pos2};
use glam::Vec3A;
use tracer::camera::Camera;
use tracer::geometry::Aabb;
use tracer::render::Outcome;
use tracer::scene::edit::{Edit, GeometryChange, ObjectChange};
use tracer::world::World;

use super::image::viewport::Gesture;
use super::sides::{Engine, Side};
use crate::figures::projection::Projector;
use crate::load::SceneSource;
use crate::reports::ray_tree;

pub(crate) use panel::window;

/// The selection's colour, on the image and in the observer view.
const SELECTION_COLOUR: Color32 = Color32::from_rgb(255, 170, 0);

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
    pub(crate) search: String,
    /// For a material several objects share: whether edits go to all of
    /// them (true) or the selected object alone, asked once per selection.
    pub(crate) shared_scope: Option<(usize, bool)>,
    /// The pixel whose eye hit the next selection takes (a click).
    pub(crate) pick_at: Option<(u32, u32)>,
    /// Left drag on the image moves the selected object instead of the
    /// camera.
    pub move_mode: bool,
    /// An open or reload waiting for the user's word on unsaved edits.
    pub pending: Option<Pending>,
    /// Why the last edit was refused.
    pub(crate) message: Option<String>,
    /// What the drag under way in the observer view holds.
    grab: Option<in_observer::Grab>,
    /// A light was selected outside the panel: its list opens.
    pub(crate) reveal_lights: bool,
    /// The selected object's box, and what it was made for (the world's
    /// address, the object).
    outline: Option<((usize, usize), Aabb)>,
}

impl Editor {
    /// Selects `object` (or nothing): the shared-material question is
    /// asked again for it.
    pub(crate) fn select(&mut self, object: Option<usize>) {
        if self.selected != object {
            self.shared_scope = None;
        }
        self.selected = object;
    }

    /// Draws the selected object's bounding box over the image of `engine`
    /// in `rect`, through the camera it renders with.
    pub(crate) fn paint_outline(&mut self, ui: &Ui, engine: &Engine, rect: Rect) {
        let (Some(scene), Some(settings)) = (engine.scene(), engine.settings()) else {
            return;
        };
        if let Ok(camera) = settings.render_camera(&scene.world.view) {
            self.paint_outline_through(ui, &scene.world, &camera, rect);
        }
    }

    /// Draws the selected object's bounding box through `camera`, whose
    /// image fills `rect`.
    pub(crate) fn paint_outline_through(
        &mut self,
        ui: &Ui,
        world: &Arc<World>,
        camera: &Camera,
        rect: Rect,
    ) {
        let Some(object) = self.selected else {
            return;
        };
        let bounds = self.bounds(world, object);
        if bounds.is_empty() {
            return;
        }
        let projector = Projector::new(camera);
        let painter = ui.painter().with_clip_rect(rect.intersect(ui.clip_rect()));
        let stroke = Stroke::new(1.5, SELECTION_COLOUR);
        for [a, b] in box_edges(&bounds) {
            if let Some([a, b]) = projector.segment(a, b) {
                painter.line_segment(
                    [to_screen(camera, rect, a), to_screen(camera, rect, b)],
                    stroke,
                );
            }
        }
    }

    /// The bounding box of `object`'s shapes in `world`, kept while the
    /// world and the object stay the same.
    fn bounds(&mut self, world: &Arc<World>, object: usize) -> Aabb {
        let key = (Arc::as_ptr(world) as usize, object);
        match &self.outline {
            Some((k, bounds)) if *k == key => *bounds,
            _ => {
                let bounds = world
                    .shape_object
                    .iter()
                    .zip(&world.shapes)
                    .filter(|(o, _)| **o as usize == object)
                    .filter_map(|(_, shape)| shape.bounds())
                    .fold(Aabb::empty(), |b, s| b.union(&s));
                self.outline = Some((key, bounds));
                bounds
            }
        }
    }

    /// In move mode, turns a drag over the image (`image_rect`, the image
    /// of `side`) into a translation of the selected object parallel to
    /// the image plane; returns the gestures that still move the camera.
    pub(crate) fn take_drag(
        &mut self,
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
        let Ok(camera) = settings.render_camera(&scene.world.view) else {
            return (gestures, None);
        };
        self.drag_object(&scene.world, object, &camera, rect, gestures)
    }

    /// Turns a drag over `camera`'s image in `rect` into a translation of
    /// `object` of `world` parallel to the image plane, keeping its centre
    /// under the pointer; an object without bounds (a plane) is left alone
    /// and the gestures given back.
    fn drag_object(
        &mut self,
        world: &Arc<World>,
        object: usize,
        camera: &Camera,
        rect: Rect,
        gestures: Vec<Gesture>,
    ) -> (Vec<Gesture>, Option<Edit>) {
        let bounds = self.bounds(world, object);
        if bounds.is_empty() {
            return (gestures, None);
        }
        let (rest, moved) = drag_shift(camera, rect, bounds.centre(), gestures);
        let edit = (moved != Vec3A::ZERO).then(|| Edit::Object {
            index: object,
            change: ObjectChange::Geometry(GeometryChange::Translate(moved.into())),
        });
        (rest, edit)
    }

    /// Selects light `index` and opens the panel's list of lights on it.
    fn select_light(&mut self, index: usize) {
        self.light = Some(index);
        self.reveal_lights = true;
    }
}

/// The object the eye ray of `engine`'s render through `pixel` meets
/// first, if any.
pub(crate) fn object_at(engine: &Engine, pixel: (u32, u32)) -> Option<usize> {
    let (scene, settings) = (engine.scene()?, engine.settings()?);
    let tree = ray_tree::inspect(&scene.world, engine.index(), settings, pixel, 0).ok()?;
    match &tree.nodes.first()?.outcome {
        Outcome::Surface(surface) => Some(surface.object as usize),
        _ => None,
    }
}

/// Where image point `p` of `camera` lands on screen when its image fills
/// `rect`.
fn to_screen(camera: &Camera, rect: Rect, p: glam::Vec2) -> egui::Pos2 {
    let size = egui::vec2(camera.width() as f32, camera.height() as f32);
    let s = rect.min + egui::vec2(p.x, p.y) / size * rect.size();
    pos2(s.x, s.y)
}

/// Turns the orbit gestures of a left drag over `camera`'s image, shown in
/// `rect`, into a shift of the point `centre` parallel to the image plane
/// that keeps it under the pointer; gives back the other gestures.
fn drag_shift(
    camera: &Camera,
    rect: Rect,
    centre: Vec3A,
    gestures: Vec<Gesture>,
) -> (Vec<Gesture>, Vec3A) {
    let mut moved = Vec3A::ZERO;
    let mut rest = Vec::new();
    // Screen points per image pixel.
    let scale = rect.width() / camera.width().max(1) as f32;
    let projector = Projector::new(camera);
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
    (rest, moved)
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
