//! The editor window's lights and camera sections, and the row of three
//! numbers they and the geometry share.

use egui::{DragValue, Slider, Ui};
use glam::Vec3;
use tracer::scene::edit::{CameraChange, Edit, LightChange};
use tracer::scene::{LightSpec, Scene};

use super::Editor;

/// Three drag values in a row; whether one changed. Its own id keeps a
/// drag on it when rows above change.
pub(super) fn vector(ui: &mut Ui, label: &str, v: &mut Vec3) -> bool {
    ui.push_id(label, |ui| vector_row(ui, label, v)).inner
}

fn vector_row(ui: &mut Ui, label: &str, v: &mut Vec3) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        let mut changed = false;
        for (axis, value) in ["x ", "y ", "z "]
            .iter()
            .zip([&mut v.x, &mut v.y, &mut v.z])
        {
            changed |= ui
                .add(DragValue::new(value).speed(0.02).prefix(*axis))
                .changed();
        }
        changed
    })
    .inner
}

/// The lights: a list to select from, the selected one's position and
/// colour, adding and removing.
pub(super) fn lights(ui: &mut Ui, editor: &mut Editor, scene: &Scene, edits: &mut Vec<Edit>) {
    for (i, light) in scene.lights.iter().enumerate() {
        let kind = match light {
            LightSpec::Point { .. } => "point",
            LightSpec::Area { .. } => "area",
        };
        let at = light.position();
        let text = format!(
            "light {i}: {kind} at ({:.2}, {:.2}, {:.2})",
            at.x, at.y, at.z
        );
        if ui.selectable_label(editor.light == Some(i), text).clicked() {
            editor.light = Some(i);
        }
    }
    if let Some(index) = editor.light.filter(|i| *i < scene.lights.len()) {
        let light = &scene.lights[index];
        let (mut at, colour) = (light.position(), light.color());
        let light_edit = |change| Edit::Light { index, change };
        if vector(ui, "Position", &mut at) {
            edits.push(light_edit(LightChange::Position(at)));
        }
        ui.horizontal(|ui| {
            let mut rgb = colour.map_or([1.0; 3], |c| [c.x, c.y, c.z]);
            if egui::color_picker::color_edit_button_rgb(ui, &mut rgb).changed() {
                edits.push(light_edit(LightChange::Colour(Some(Vec3::from(rgb)))));
            }
            ui.label(if colour.is_some() {
                "Colour"
            } else {
                "Colour (default: white shared by the lights)"
            });
        });
        if ui.button("Remove this light").clicked() {
            edits.push(Edit::RemoveLight(index));
            editor.light = None;
        }
    }
    if ui
        .button("Add a light at the camera")
        .on_hover_text("A point light where the scene camera stands")
        .clicked()
    {
        edits.push(Edit::AddLight {
            index: scene.lights.len(),
            light: LightSpec::Point {
                position: scene.view.from,
                color: None,
            },
        });
        editor.light = Some(scene.lights.len());
    }
}

/// The scene camera's numbers.
pub(super) fn camera(ui: &mut Ui, scene: &Scene, edits: &mut Vec<Edit>) {
    let view = &scene.view;
    let (mut from, mut at, mut up) = (view.from, view.at, view.up);
    if vector(ui, "From", &mut from) {
        edits.push(Edit::Camera(CameraChange::From(from)));
    }
    if vector(ui, "At", &mut at) {
        edits.push(Edit::Camera(CameraChange::At(at)));
    }
    if vector(ui, "Up", &mut up) {
        edits.push(Edit::Camera(CameraChange::Up(up)));
    }
    let (mut angle, mut aperture, mut focal) = (view.angle, view.aperture, view.focal);
    if ui
        .add(Slider::new(&mut angle, 1.0..=170.0).text("Angle (degrees)"))
        .changed()
    {
        edits.push(Edit::Camera(CameraChange::Angle(angle)));
    }
    if ui
        .add(Slider::new(&mut aperture, 0.0..=64.0).text("Aperture (px)"))
        .changed()
    {
        edits.push(Edit::Camera(CameraChange::Aperture(aperture)));
    }
    if ui
        .add(
            Slider::new(&mut focal, 0.1..=4.0)
                .logarithmic(true)
                .text("Focal ratio"),
        )
        .changed()
    {
        edits.push(Edit::Camera(CameraChange::Focal(focal)));
    }
}
