//! The editor in the observer view, which shows side A's scene from
//! outside: a click selects the object or the light under the pointer; a
//! drag that starts on a light moves that light, and in move mode any other
//! drag moves the selected object, both parallel to the observer's image
//! plane, instead of orbiting the observer. The selection is drawn there
//! too.

use egui::{Pos2, Rect, Stroke, Ui};
use glam::Vec3A;
use tracer::camera::Camera;
use tracer::scene::edit::{Edit, LightChange};

use super::{Editor, SELECTION_COLOUR, drag_shift, object_at, to_screen};
use crate::figures::projection::Projector;
use crate::gui::image::viewport::ViewportResponse;
use crate::gui::observer::Observer;
use crate::gui::sides::Side;

/// How near a light's marker, in screen points, a press takes hold of it.
const GRAB_RADIUS: f32 = 12.0;

/// What a drag in the observer view holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Grab {
    Light(usize),
    Object(usize),
}

impl Editor {
    /// Takes this frame's clicks and drags over the observer's image, which
    /// shows `a`'s scene: selections, and the edits of A that drags make
    /// (only while the editor edits A: `edits_a`). The gestures left in
    /// `response` move the observer's camera.
    pub(crate) fn observer_input(
        &mut self,
        ui: &Ui,
        response: &mut ViewportResponse,
        observer: &Observer,
        a: &Side,
        edits_a: bool,
    ) -> Vec<Edit> {
        let (Some(rect), Some(scene)) = (response.image_rect, a.engine.scene()) else {
            return Vec::new();
        };
        let Some(camera) = observer.camera(&scene.world) else {
            return Vec::new();
        };
        if !self.open {
            self.grab = None;
            return Vec::new();
        }
        let lights: Vec<Vec3A> = scene
            .scene
            .lights
            .iter()
            .map(|l| l.position().into())
            .collect();
        let (pressed, released, clicked, origin, at) = ui.input(|i| {
            let p = &i.pointer;
            let (origin, at) = (p.press_origin(), p.interact_pos());
            (
                p.primary_pressed(),
                p.primary_released(),
                p.primary_clicked(),
                origin,
                at,
            )
        });
        let over_image = response.hovered_pixel.is_some();
        let light_at = |point: Option<Pos2>| {
            point.and_then(|point| nearest_marker(&camera, rect, &lights, point))
        };
        if pressed && over_image && edits_a {
            self.grab = match (light_at(origin), self.move_mode, self.selected) {
                (Some(light), ..) => Some(Grab::Light(light)),
                (None, true, Some(object)) => Some(Grab::Object(object)),
                _ => None,
            };
            if let Some(Grab::Light(light)) = self.grab {
                self.select_light(light);
            }
        }
        let mut edits = Vec::new();
        match self.grab {
            Some(Grab::Light(index)) if index < lights.len() => {
                let gestures = std::mem::take(&mut response.gestures);
                let (rest, moved) = drag_shift(&camera, rect, lights[index], gestures);
                response.gestures = rest;
                if moved != Vec3A::ZERO {
                    edits.push(Edit::Light {
                        index,
                        change: LightChange::Position((lights[index] + moved).into()),
                    });
                }
            }
            Some(Grab::Object(object)) => {
                let gestures = std::mem::take(&mut response.gestures);
                let (rest, edit) = self.drag_object(&scene.world, object, &camera, rect, gestures);
                response.gestures = rest;
                edits.extend(edit);
            }
            _ => {}
        }
        if released {
            self.grab = None;
        }
        if clicked && over_image {
            if let Some(light) = light_at(at) {
                self.select_light(light);
            } else if let Some(pixel) = response.hovered_pixel {
                self.select(object_at(observer.engine(), pixel));
            }
        }
        edits
    }

    /// Draws the selected object's box and a ring round the selected
    /// light over the observer's image in `rect`.
    pub(crate) fn paint_in_observer(&mut self, ui: &Ui, observer: &Observer, a: &Side, rect: Rect) {
        let Some(scene) = a.engine.scene() else {
            return;
        };
        let Some(camera) = observer.camera(&scene.world) else {
            return;
        };
        self.paint_outline_through(ui, &scene.world, &camera, rect);
        let light = self.light.and_then(|i| scene.scene.lights.get(i));
        if let Some(centre) = light.and_then(|l| marker(&camera, rect, l.position().into())) {
            ui.painter()
                .with_clip_rect(rect.intersect(ui.clip_rect()))
                .circle_stroke(
                    centre,
                    GRAB_RADIUS * 0.8,
                    Stroke::new(2.0, SELECTION_COLOUR),
                );
        }
    }
}

/// Where `point` is drawn on screen through `camera` into `rect`.
fn marker(camera: &Camera, rect: Rect, point: Vec3A) -> Option<Pos2> {
    Projector::new(camera)
        .point(point)
        .map(|p| to_screen(camera, rect, p))
}

/// The light whose marker is nearest `pointer`, within the grab radius.
fn nearest_marker(camera: &Camera, rect: Rect, lights: &[Vec3A], pointer: Pos2) -> Option<usize> {
    lights
        .iter()
        .enumerate()
        .filter_map(|(i, &light)| Some((i, marker(camera, rect, light)?.distance(pointer))))
        .filter(|(_, distance)| *distance <= GRAB_RADIUS)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}
