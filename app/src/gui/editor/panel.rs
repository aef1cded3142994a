//! The scene editor window: the objects (searchable, fine with thousands),
//! the selected object's material and geometry, the lights, the camera's
//! numbers, and the edits so far (undo, redo, the `--set` line, saving).
//! Every change is an [`Edit`] applied to the edited side.

use egui::{DragValue, Slider, Ui};
use glam::Vec3;
use tracer::scene::edit::{Edit, Effect, GeometryChange, MaterialField, ObjectChange};
use tracer::scene::{Material, Primitive, Scene};

use super::Editor;
use super::lights_and_camera::{camera, lights, vector};
use crate::gui::commands::Command;
use crate::gui::panels::settings::command_button;
use crate::gui::sides::Side;

/// Rows of the object list shown at once (it scrolls).
const LIST_HEIGHT: f32 = 180.0;

/// What the window did beyond the edits it applied.
#[derive(Default)]
pub(crate) struct EditorOutcome {
    /// A camera field changed: the scene's camera is the one to render,
    /// not the orbit's.
    pub(crate) camera_edited: bool,
}

/// The editor window while open; edits go to `side` (the side the panel
/// edits), commands (undo, redo, save) into `commands`.
pub(crate) fn window(
    ctx: &egui::Context,
    editor: &mut Editor,
    side: &mut Side,
    commands: &mut Vec<Command>,
) -> EditorOutcome {
    let mut outcome = EditorOutcome::default();
    if !editor.open {
        return outcome;
    }
    let mut open = true;
    let mut edits = Vec::new();
    egui::Window::new(format!("Scene editor ({})", side.id.name()))
        .open(&mut open)
        .default_size([340.0, 560.0])
        // At the right, over the statistics rather than the image.
        .default_pos([ctx.content_rect().right() - 350.0, 60.0])
        .show(ctx, |ui| {
            let Some(scene) = side.engine.scene().map(|s| s.scene.clone()) else {
                ui.label("No scene yet.");
                return;
            };
            history(ui, editor, side, commands);
            egui::ScrollArea::vertical().show(ui, |ui| {
                egui::CollapsingHeader::new(format!("Objects ({})", scene.objects.len()))
                    .id_salt("editor_objects")
                    .default_open(true)
                    .show(ui, |ui| object_list(ui, editor, &scene));
                if let Some(object) = editor.selected.filter(|o| *o < scene.objects.len()) {
                    egui::CollapsingHeader::new(format!(
                        "{} #{object}",
                        scene.objects[object].primitive.kind()
                    ))
                    .default_open(true)
                    .show(ui, |ui| {
                        selected_object(ui, editor, &scene, object, &mut edits)
                    });
                }
                egui::CollapsingHeader::new(format!("Lights ({})", scene.lights.len()))
                    .id_salt("editor_lights")
                    .open(std::mem::take(&mut editor.reveal_lights).then_some(true))
                    .show(ui, |ui| lights(ui, editor, &scene, &mut edits));
                egui::CollapsingHeader::new("Camera").show(ui, |ui| camera(ui, &scene, &mut edits));
            });
        });
    if !open {
        editor.open = false;
    }
    for edit in edits {
        match side.edit(edit) {
            Ok(effect) => {
                outcome.camera_edited |= effect == Effect::Camera;
                editor.message = None;
            }
            Err(why) => editor.message = Some(why),
        }
    }
    outcome
}

/// Undo, redo, the edits as `--set` arguments, saving.
fn history(ui: &mut Ui, editor: &mut Editor, side: &Side, commands: &mut Vec<Command>) {
    ui.horizontal_wrapped(|ui| {
        ui.add_enabled_ui(side.history.can_undo(), |ui| {
            command_button(ui, Command::Undo, commands);
        });
        ui.add_enabled_ui(side.history.can_redo(), |ui| {
            command_button(ui, Command::Redo, commands);
        });
        command_button(ui, Command::SaveScene, commands);
        if ui
            .add_enabled(!side.history.is_empty(), egui::Button::new("Copy as --set"))
            .on_hover_text("The edits as command-line arguments of render, compare, sweep...")
            .clicked()
        {
            ui.ctx().copy_text(side.history.set_lines());
        }
    });
    let edits = side.history.len();
    ui.small(match (edits, side.history.is_modified()) {
        (0, false) => "No edits: the scene is as its file says.".to_string(),
        (n, true) => format!("{n} edit(s), not saved"),
        (n, false) => format!("{n} edit(s), saved"),
    });
    if let Some(message) = &editor.message {
        ui.colored_label(ui.visuals().error_fg_color, message);
    }
    ui.checkbox(&mut editor.move_mode, "Drag moves the selected object")
        .on_hover_text("Left drag on the image moves it in the image plane instead of orbiting");
}

/// The objects, filtered by the search text; a click selects.
fn object_list(ui: &mut Ui, editor: &mut Editor, scene: &Scene) {
    ui.add(
        egui::TextEdit::singleline(&mut editor.search)
            .hint_text("search: kind, #index or line")
            .desired_width(f32::INFINITY),
    );
    let needle = editor.search.trim().to_lowercase();
    let rows: Vec<usize> = (0..scene.objects.len())
        .filter(|&i| needle.is_empty() || object_line(scene, i).to_lowercase().contains(&needle))
        .collect();
    ui.small(format!("{} of {} objects", rows.len(), scene.objects.len()));
    let height = ui.text_style_height(&egui::TextStyle::Body);
    egui::ScrollArea::vertical()
        .id_salt("object_list")
        .max_height(LIST_HEIGHT)
        .show_rows(ui, height, rows.len(), |ui, range| {
            for &i in &rows[range] {
                let selected = editor.selected == Some(i);
                if ui
                    .selectable_label(selected, object_line(scene, i))
                    .clicked()
                {
                    editor.select(Some(i));
                }
            }
        });
}

/// "sphere #5 (line 31:1), material 3".
fn object_line(scene: &Scene, index: usize) -> String {
    let object = &scene.objects[index];
    let at = scene
        .object_positions
        .get(index)
        .map_or_else(String::new, |(l, c)| format!(" (line {l}:{c})"));
    format!(
        "{} #{index}{at}, material {}",
        object.primitive.kind(),
        object.material
    )
}

/// The selected object's material and geometry.
fn selected_object(
    ui: &mut Ui,
    editor: &mut Editor,
    scene: &Scene,
    object: usize,
    edits: &mut Vec<Edit>,
) {
    let material_index = scene.objects[object].material;
    let users = scene
        .objects
        .iter()
        .filter(|o| o.material == material_index)
        .count();
    let Some(material) = scene.materials.get(material_index as usize).copied() else {
        ui.label("Its material is missing.");
        return;
    };
    let all = if users > 1 {
        match editor.shared_scope.filter(|(o, _)| *o == object) {
            Some((_, all)) => {
                ui.small(if all {
                    format!("Editing material {material_index}: all {users} objects change")
                } else {
                    "Editing this object's own copy of the material".to_string()
                });
                Some(all)
            }
            None => {
                ui.label(format!(
                    "Material {material_index} is shared by {users} objects. Change:"
                ));
                ui.horizontal(|ui| {
                    if ui.button("This object alone").clicked() {
                        editor.shared_scope = Some((object, false));
                    }
                    if ui.button(format!("All {users}")).clicked() {
                        editor.shared_scope = Some((object, true));
                    }
                });
                None
            }
        }
    } else {
        // The same line as for a shared material, so the fields below do
        // not move when an edit gives the object a material of its own.
        ui.small(format!(
            "Editing material {material_index}, used by this object only"
        ));
        Some(false)
    };
    if let Some(all) = all {
        let target = |field: MaterialField| {
            if all {
                Edit::Material {
                    index: material_index as usize,
                    field,
                }
            } else {
                Edit::Object {
                    index: object,
                    change: ObjectChange::Material(field),
                }
            }
        };
        edits.extend(material_fields(ui, &material).into_iter().map(target));
    }
    ui.separator();
    edits.extend(geometry(ui, scene, object));
}

/// The material's fields as the `f` line has them; what changed.
fn material_fields(ui: &mut Ui, m: &Material) -> Vec<MaterialField> {
    let mut changed = Vec::new();
    let colour = |ui: &mut Ui, label: &str, c: Vec3| -> Option<Vec3> {
        let mut rgb = [c.x, c.y, c.z];
        ui.push_id(label, |ui| {
            ui.horizontal(|ui| {
                let picked = egui::color_picker::color_edit_button_rgb(ui, &mut rgb).changed();
                ui.label(label);
                picked.then(|| Vec3::from(rgb))
            })
            .inner
        })
        .inner
    };
    // Each field keeps its id whatever shows around it (a drag stays on
    // its slider, a colour popup open) when the rows above change.
    let number = |ui: &mut Ui, label: &str, v: f32, range: std::ops::RangeInclusive<f32>, log| {
        let mut value = v;
        let slider = Slider::new(&mut value, range).text(label).logarithmic(log);
        ui.push_id(label, |ui| ui.add(slider).changed())
            .inner
            .then_some(value)
    };
    changed.extend(colour(ui, "Diffuse colour", m.diffuse).map(MaterialField::Diffuse));
    changed.extend(number(ui, "Kd", m.kd, 0.0..=1.0, false).map(MaterialField::Kd));
    changed.extend(colour(ui, "Specular colour", m.specular).map(MaterialField::Specular));
    changed.extend(number(ui, "Ks", m.ks, 0.0..=1.0, false).map(MaterialField::Ks));
    changed.extend(number(ui, "Shine", m.shine, 1.0..=1000.0, true).map(MaterialField::Shine));
    changed.extend(
        number(ui, "T (transmittance)", m.transmittance, 0.0..=1.0, false)
            .map(MaterialField::Transmittance),
    );
    if m.transmittance > 0.0 {
        changed.extend(number(ui, "ior", m.ior, 1.0..=3.0, false).map(MaterialField::Ior));
    } else {
        ui.weak("ior applies once T > 0");
    }
    changed
}

/// A sphere's centre and radius, or a translation for any other shape.
fn geometry(ui: &mut Ui, scene: &Scene, object: usize) -> Option<Edit> {
    let edit = |change| Edit::Object {
        index: object,
        change: ObjectChange::Geometry(change),
    };
    match &scene.objects[object].primitive {
        Primitive::Sphere {
            centre,
            radius,
            inside_only,
        } => {
            let mut c = *centre;
            let mut r = *radius;
            let moved = vector(ui, "Centre", &mut c);
            let resized = ui
                .add(
                    DragValue::new(&mut r)
                        .speed(0.01)
                        .range(1e-4..=1e6)
                        .prefix("radius "),
                )
                .changed();
            if moved {
                Some(edit(GeometryChange::Centre(c)))
            } else if resized {
                let signed = if *inside_only { -r } else { r };
                Some(edit(GeometryChange::Radius(signed)))
            } else {
                None
            }
        }
        _ => {
            let mut by = Vec3::ZERO;
            vector(ui, "Move by", &mut by).then(|| edit(GeometryChange::Translate(by)))
        }
    }
}
