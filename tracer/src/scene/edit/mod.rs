//! One typed edit of the scene document: a material's field, an object's
//! geometry, a light, the camera. Applying an edit validates it by the
//! rules the parser follows (the `scene::rules` module), changes nothing when it is
//! refused, and returns its inverse: undo applies the inverse, redo applies
//! what that returns. The command line's `--set` lines are the same edits
//! as text (module `text`), so the window can show any edit as its
//! `--set` line.

mod text;

#[cfg(test)]
mod tests;

use glam::Vec3;

use super::rules::{self, Invalid};
use super::{LightSpec, Limits, Material, Primitive, Scene, Viewpoint};

/// What an edit changes, so what must be prepared again before the next
/// frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Effect {
    /// Materials only: the world's surfaces. The shapes and the structure
    /// over them stay.
    Shading,
    /// One object's shapes: the world's shapes and the structure over them.
    Geometry,
    /// The lights (and the default colour of the colourless ones).
    Lights,
    /// The camera block: the world's view, which owns the lens renders see
    /// through ([`crate::render::RenderSettings::render_camera`]).
    Camera,
}

/// One change of a scene document. Indices count from 0 in the file's
/// order, as the inspector numbers objects (`sphere #0` is the first).
#[derive(Debug, Clone, PartialEq)]
pub enum Edit {
    /// `object N ...`: that object alone. A material field on a material
    /// other objects share first gives the object its own copy.
    Object {
        /// The object, counted from 0 in file order.
        index: usize,
        /// What happens to it.
        change: ObjectChange,
    },
    /// `material M FIELD ...`: every object that uses material M.
    Material {
        /// The material, counted from 0 in file order.
        index: usize,
        /// The field set and its new value.
        field: MaterialField,
    },
    /// `light N ...`.
    Light {
        /// The light, counted from 0 in file order.
        index: usize,
        /// What happens to it.
        change: LightChange,
    },
    /// `light N add l ...` / `add al ...`: a new light at `index` (the
    /// number of lights appends it).
    AddLight {
        /// Where the light goes: 0..=the number of lights.
        index: usize,
        /// The light added.
        light: LightSpec,
    },
    /// `light N remove`.
    RemoveLight(usize),
    /// `camera FIELD ...`.
    Camera(CameraChange),
}

/// One field of the P3F material line `f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MaterialField {
    /// `diffuse R G B`.
    Diffuse(Vec3),
    /// `kd K`.
    Kd(f32),
    /// `specular R G B`.
    Specular(Vec3),
    /// `ks K`.
    Ks(f32),
    /// `shine S`: the Blinn-Phong exponent.
    Shine(f32),
    /// `t T`: the transmittance, 0..1.
    Transmittance(f32),
    /// `ior N`: above 0 when T > 0.
    Ior(f32),
}

/// What an [`Edit::Object`] changes.
#[derive(Debug, Clone, PartialEq)]
pub enum ObjectChange {
    /// One field of the object's material (see [`Edit::Object`]).
    Material(MaterialField),
    /// `own DR DG DB KD SR SG SB KS SHINE T IOR`: the object gets a
    /// material of its own, appended to the scene's, with these values.
    Own(Material),
    /// `share M`: the object drops its own material (the scene's last, used
    /// by it alone) and uses material M again: the inverse of [`Self::Own`].
    Share(u32),
    /// Where the object is and what shape it has.
    Geometry(GeometryChange),
}

/// What an [`ObjectChange::Geometry`] changes.
#[derive(Debug, Clone, PartialEq)]
pub enum GeometryChange {
    /// `centre X Y Z`: a sphere's centre.
    Centre(Vec3),
    /// `radius R`: a sphere's radius; negative is inside-only, as in `s`.
    Radius(f32),
    /// `translate DX DY DZ`: moves any object.
    Translate(Vec3),
    /// `shape s ...` (any P3F shape command): the object's geometry
    /// replaced, the inverse of a translation (exact, where adding the
    /// opposite offset would round).
    Shape(Primitive),
}

/// What an [`Edit::Light`] changes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightChange {
    /// `position X Y Z`: a point light's position, an area light's centre.
    Position(Vec3),
    /// `colour R G B`, or `colour default` (white at 1/sqrt(lights)).
    Colour(Option<Vec3>),
    /// `aim X Y Z`: the point an area light faces.
    Aim(Vec3),
    /// `size W H`: an area light's width and height.
    Size {
        /// Extent along the light's first side, in scene units, > 0.
        width: f32,
        /// Extent along the second side, in scene units, > 0.
        height: f32,
    },
}

/// What an [`Edit::Camera`] changes: the `v` fields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CameraChange {
    /// `from X Y Z`: the eye's position.
    From(Vec3),
    /// `at X Y Z`: the point seen at the image's centre.
    At(Vec3),
    /// `up X Y Z`: the direction that is up in the image; not parallel to the view.
    Up(Vec3),
    /// Degrees, between the centres of the top and bottom pixel rows.
    Angle(f32),
    /// Lens diameter in pixels; 0 is a pinhole.
    Aperture(f32),
    /// Focal distance as a multiple of the view-plane distance.
    Focal(f32),
}

/// Why an edit was refused; the scene is then unchanged. Messages name the
/// valid range or the field names.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EditError {
    /// An index past the end.
    #[error("{what} {index}: the scene has {}", count_range(what, *count))]
    NoSuch {
        /// What was indexed: "object", "material", "light".
        what: &'static str,
        /// The index given.
        index: usize,
        /// How many there are.
        count: usize,
    },
    /// A new light's place past the end.
    #[error("light {index}: a new light goes at 0..{count} (the scene has {count} lights)")]
    NoSlot {
        /// The place given.
        index: usize,
        /// How many lights there are (the last valid place).
        count: usize,
    },
    /// A field the target does not have.
    #[error("no field '{field}' for {target}; fields: {fields}")]
    UnknownField {
        /// The field name given.
        field: String,
        /// "a sphere", "a material", "an area light", "the camera", ...
        target: String,
        /// The target's field names, comma-separated.
        fields: String,
    },
    /// A first word that names nothing to edit.
    #[error("unknown edit '{0}': an edit starts with object, material, light or camera")]
    UnknownTarget(String),
    /// No words at all.
    #[error("empty edit: give e.g. 'object 0 kd 0.5' or 'camera aperture 8'")]
    Empty,
    /// A word where an index was expected.
    #[error("{what} '{found}': not an index ({what}s count from 0)")]
    BadIndex {
        /// What was indexed: "object", "material", "light".
        what: &'static str,
        /// The word found instead.
        found: String,
    },
    /// A field given the wrong number of values.
    #[error("{field} takes {expected}, found {found}")]
    WrongCount {
        /// The field given.
        field: String,
        /// How many values it takes, in words ("3 numbers").
        expected: &'static str,
        /// How many values were given.
        found: usize,
    },
    /// A value that is not a number.
    #[error("{field}: expected a number, found '{found}'")]
    NotANumber {
        /// The field given.
        field: String,
        /// The word found instead of a number.
        found: String,
    },
    /// NaN or infinity.
    #[error("{field} must be a finite number, found {found}")]
    NonFinite {
        /// The field given.
        field: String,
        /// The value as written.
        found: String,
    },
    /// A value the parser would refuse in a file.
    #[error("invalid {what}: {why}")]
    Invalid {
        /// The value refused, as the parser names it.
        what: &'static str,
        /// The rule it breaks.
        why: String,
    },
    /// The P3F text of a `shape` or `add` that does not parse or is not one
    /// shape (light): the parser's message, at the column in that text.
    #[error("{field}: {message}")]
    Piece {
        /// `shape` or `add`.
        field: &'static str,
        /// The parser's message.
        message: String,
    },
    /// `share` on an object without a material of its own.
    #[error(
        "object {object}: its material {material} is not its own (the scene's last, used by it alone), so it cannot go back to sharing"
    )]
    NotOwn {
        /// The object.
        object: usize,
        /// The material it uses, shared with others or not the scene's last.
        material: u32,
    },
    /// An object that refers to a material the scene lacks (only a scene
    /// built in code can).
    #[error("object {object} refers to material {material}, which the scene lacks")]
    MissingMaterial {
        /// The object.
        object: usize,
        /// The material index it names, past the scene's materials.
        material: u32,
    },
    /// One more item than [`Limits`] allows.
    #[error("{what} would exceed the limit of {limit}")]
    AboveLimit {
        /// What would be too many: "the light count", "the material count".
        what: &'static str,
        /// The limit.
        limit: usize,
    },
}

fn count_range(what: &str, count: usize) -> String {
    match count {
        0 => format!("no {what}s"),
        1 => format!("1 {what} (0)"),
        n => format!("{n} {what}s (0..{})", n - 1),
    }
}

impl From<Invalid> for EditError {
    fn from(Invalid { what, why }: Invalid) -> Self {
        EditError::Invalid { what, why }
    }
}

impl Edit {
    /// What must be rebuilt after this edit.
    pub fn kind(&self) -> Effect {
        match self {
            Edit::Object { change, .. } => match change {
                ObjectChange::Material(_) | ObjectChange::Own(_) | ObjectChange::Share(_) => {
                    Effect::Shading
                }
                ObjectChange::Geometry(_) => Effect::Geometry,
            },
            Edit::Material { .. } => Effect::Shading,
            Edit::Light { .. } | Edit::AddLight { .. } | Edit::RemoveLight(_) => Effect::Lights,
            Edit::Camera(_) => Effect::Camera,
        }
    }

    /// Applies the edit to `scene` and returns its inverse. A refused edit
    /// (an index past the end, a field the target lacks, a value the parser
    /// would refuse) leaves `scene` as it was.
    pub fn apply(&self, scene: &mut Scene) -> Result<Edit, EditError> {
        text::check_finite(self)?;
        match self {
            Edit::Object { index, change } => edit_object(scene, *index, change),
            Edit::Material { index, field } => {
                within("material", *index, scene.materials.len())?;
                let old = set_field(&mut scene.materials[*index], *field)?;
                Ok(Edit::Material {
                    index: *index,
                    field: old,
                })
            }
            Edit::Light { index, change } => edit_light(scene, *index, *change),
            Edit::AddLight { index, light } => {
                let count = scene.lights.len();
                if *index > count {
                    return Err(EditError::NoSlot {
                        index: *index,
                        count,
                    });
                }
                if count >= Limits::default().max_lights {
                    let limit = Limits::default().max_lights;
                    return Err(EditError::AboveLimit {
                        what: "the light count",
                        limit,
                    });
                }
                rules::light(light)?;
                scene.lights.insert(*index, *light);
                Ok(Edit::RemoveLight(*index))
            }
            Edit::RemoveLight(index) => {
                within("light", *index, scene.lights.len())?;
                let light = scene.lights.remove(*index);
                Ok(Edit::AddLight {
                    index: *index,
                    light,
                })
            }
            Edit::Camera(change) => {
                let mut view = scene.view.clone();
                let old = set_camera(&mut view, *change);
                rules::viewpoint(&view)?;
                scene.view = view;
                Ok(Edit::Camera(old))
            }
        }
    }
}

/// Applies `edits` in order, all or none: on a refusal the ones applied
/// are undone and the error comes with the index of the edit refused.
/// Returns the inverses in the order that undoes them.
pub fn apply_all(edits: &[Edit], scene: &mut Scene) -> Result<Vec<Edit>, (usize, EditError)> {
    let mut undo = Vec::with_capacity(edits.len());
    for (i, edit) in edits.iter().enumerate() {
        match edit.apply(scene) {
            Ok(inverse) => undo.push(inverse),
            Err(error) => {
                for inverse in undo.iter().rev() {
                    // An inverse applies to the scene its edit left.
                    let undone = inverse.apply(scene);
                    debug_assert!(undone.is_ok(), "{inverse} refused: {undone:?}");
                }
                return Err((i, error));
            }
        }
    }
    undo.reverse();
    Ok(undo)
}

/// Sets `field` on `material` if the result is a valid material; returns
/// the field's old value.
fn set_field(material: &mut Material, field: MaterialField) -> Result<MaterialField, EditError> {
    let mut changed = *material;
    let old = field_swap(&mut changed, field);
    rules::material(&changed)?;
    *material = changed;
    Ok(old)
}

/// Writes `field` into `m`, returning what it held.
fn field_swap(m: &mut Material, field: MaterialField) -> MaterialField {
    use MaterialField as F;
    match field {
        F::Diffuse(v) => F::Diffuse(std::mem::replace(&mut m.diffuse, v)),
        F::Kd(v) => F::Kd(std::mem::replace(&mut m.kd, v)),
        F::Specular(v) => F::Specular(std::mem::replace(&mut m.specular, v)),
        F::Ks(v) => F::Ks(std::mem::replace(&mut m.ks, v)),
        F::Shine(v) => F::Shine(std::mem::replace(&mut m.shine, v)),
        F::Transmittance(v) => F::Transmittance(std::mem::replace(&mut m.transmittance, v)),
        F::Ior(v) => F::Ior(std::mem::replace(&mut m.ior, v)),
    }
}

fn set_camera(view: &mut Viewpoint, change: CameraChange) -> CameraChange {
    use CameraChange as C;
    use std::mem::replace;
    match change {
        C::From(v) => C::From(replace(&mut view.from, v)),
        C::At(v) => C::At(replace(&mut view.at, v)),
        C::Up(v) => C::Up(replace(&mut view.up, v)),
        C::Angle(v) => C::Angle(replace(&mut view.angle, v)),
        C::Aperture(v) => C::Aperture(replace(&mut view.aperture, v)),
        C::Focal(v) => C::Focal(replace(&mut view.focal, v)),
    }
}

/// `index` if it is below `count`, the number of `what`s.
fn within(what: &'static str, index: usize, count: usize) -> Result<usize, EditError> {
    if index < count {
        return Ok(index);
    }
    Err(EditError::NoSuch { what, index, count })
}

/// Whether an object other than `object` uses material `material`.
fn shared(scene: &Scene, material: u32, object: usize) -> bool {
    scene
        .objects
        .iter()
        .enumerate()
        .any(|(i, o)| i != object && o.material == material)
}

fn edit_object(scene: &mut Scene, index: usize, change: &ObjectChange) -> Result<Edit, EditError> {
    within("object", index, scene.objects.len())?;
    let inverse = |change| Edit::Object { index, change };
    let material = scene.objects[index].material;
    let materials = scene.materials.len();
    let current = usize::try_from(material)
        .ok()
        .filter(|&m| m < materials)
        .ok_or(EditError::MissingMaterial {
            object: index,
            material,
        });
    match change {
        ObjectChange::Material(field) => {
            let m = current?;
            if !shared(scene, material, index) {
                let old = set_field(&mut scene.materials[m], *field)?;
                return Ok(inverse(ObjectChange::Material(old)));
            }
            let mut own = scene.materials[m];
            field_swap(&mut own, *field);
            give_own(scene, index, own)
        }
        ObjectChange::Own(own) => give_own(scene, index, *own),
        ObjectChange::Share(to) => {
            let own = current?;
            if own + 1 != materials || shared(scene, material, index) {
                return Err(EditError::NotOwn {
                    object: index,
                    material,
                });
            }
            within("material", *to as usize, own)?;
            let dropped = scene.materials.pop().unwrap_or_default();
            scene.objects[index].material = *to;
            Ok(inverse(ObjectChange::Own(dropped)))
        }
        ObjectChange::Geometry(change) => {
            let object = &mut scene.objects[index];
            let (moved, old) = reshape(&object.primitive, change)?;
            rules::primitive(&moved)?;
            object.primitive = moved;
            Ok(inverse(ObjectChange::Geometry(old)))
        }
    }
}

/// Gives object `index` a material of its own with the values `own`,
/// appended to the scene's; the inverse shares its old material again.
fn give_own(scene: &mut Scene, index: usize, own: Material) -> Result<Edit, EditError> {
    rules::material(&own)?;
    let limit = Limits::default().max_materials;
    let count = scene.materials.len();
    let Some(new) = u32::try_from(count).ok().filter(|_| count < limit) else {
        return Err(EditError::AboveLimit {
            what: "the material count",
            limit,
        });
    };
    scene.materials.push(own);
    let old = std::mem::replace(&mut scene.objects[index].material, new);
    Ok(Edit::Object {
        index,
        change: ObjectChange::Share(old),
    })
}

/// The primitive after a geometric `change`, and the change that undoes
/// it exactly.
fn reshape(
    primitive: &Primitive,
    change: &GeometryChange,
) -> Result<(Primitive, GeometryChange), EditError> {
    use GeometryChange as G;
    let sphere_only = |field: &str| EditError::UnknownField {
        field: field.to_string(),
        target: text::article(primitive.kind()),
        fields: text::object_fields(primitive).join(", "),
    };
    let Primitive::Sphere {
        centre,
        radius,
        inside_only,
    } = primitive
    else {
        return match change {
            G::Centre(_) => Err(sphere_only("centre")),
            G::Radius(_) => Err(sphere_only("radius")),
            G::Translate(by) => Ok((translated(primitive, *by), G::Shape(primitive.clone()))),
            G::Shape(to) => Ok((to.clone(), G::Shape(primitive.clone()))),
        };
    };
    let sphere = |centre, radius: f32| Primitive::Sphere {
        centre,
        radius: radius.abs(),
        inside_only: radius < 0.0,
    };
    // The radius as `s` writes it.
    let signed = if *inside_only { -radius } else { *radius };
    match change {
        G::Centre(to) => Ok((sphere(*to, signed), G::Centre(*centre))),
        G::Translate(by) => Ok((sphere(*centre + *by, signed), G::Centre(*centre))),
        G::Radius(to) => {
            rules::sphere_radius(*to)?;
            Ok((sphere(*centre, *to), G::Radius(signed)))
        }
        G::Shape(to) => Ok((to.clone(), G::Shape(primitive.clone()))),
    }
}

/// `primitive` moved by `by`; normals are unchanged by a translation.
fn translated(primitive: &Primitive, by: Vec3) -> Primitive {
    let moved = |points: &[Vec3]| points.iter().map(|&p| p + by).collect::<Vec<_>>();
    match primitive {
        Primitive::Sphere {
            centre,
            radius,
            inside_only,
        } => Primitive::Sphere {
            centre: *centre + by,
            radius: *radius,
            inside_only: *inside_only,
        },
        Primitive::Plane { points } => Primitive::Plane {
            points: points.map(|p| p + by),
        },
        Primitive::Polygon { vertices } => Primitive::Polygon {
            vertices: moved(vertices),
        },
        Primitive::Patch { vertices, normals } => Primitive::Patch {
            vertices: moved(vertices),
            normals: normals.clone(),
        },
        Primitive::Cone {
            base,
            base_radius,
            apex,
            apex_radius,
        } => Primitive::Cone {
            base: *base + by,
            base_radius: *base_radius,
            apex: *apex + by,
            apex_radius: *apex_radius,
        },
        Primitive::Box { min, max } => Primitive::Box {
            min: *min + by,
            max: *max + by,
        },
        Primitive::Mesh {
            vertices,
            triangles,
        } => Primitive::Mesh {
            vertices: moved(vertices),
            triangles: triangles.clone(),
        },
    }
}

fn edit_light(scene: &mut Scene, index: usize, change: LightChange) -> Result<Edit, EditError> {
    within("light", index, scene.lights.len())?;
    let mut light = scene.lights[index];
    let area_only = |field: &str| EditError::UnknownField {
        field: field.to_string(),
        target: "a point light".into(),
        fields: text::POINT_LIGHT_FIELDS.join(", "),
    };
    let old = match (&mut light, change) {
        (LightSpec::Point { position, .. }, LightChange::Position(to)) => {
            LightChange::Position(std::mem::replace(position, to))
        }
        (LightSpec::Area { centre, .. }, LightChange::Position(to)) => {
            LightChange::Position(std::mem::replace(centre, to))
        }
        (
            LightSpec::Point { color, .. } | LightSpec::Area { color, .. },
            LightChange::Colour(to),
        ) => LightChange::Colour(std::mem::replace(color, to)),
        (LightSpec::Area { aim, .. }, LightChange::Aim(to)) => {
            LightChange::Aim(std::mem::replace(aim, to))
        }
        (
            LightSpec::Area { width, height, .. },
            LightChange::Size {
                width: w,
                height: h,
            },
        ) => LightChange::Size {
            width: std::mem::replace(width, w),
            height: std::mem::replace(height, h),
        },
        (LightSpec::Point { .. }, LightChange::Aim(_)) => return Err(area_only("aim")),
        (LightSpec::Point { .. }, LightChange::Size { .. }) => return Err(area_only("size")),
    };
    rules::light(&light)?;
    scene.lights[index] = light;
    Ok(Edit::Light { index, change: old })
}
