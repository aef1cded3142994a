//! Edits as `--set` text: [`FromStr`] reads `object 5 ior 1.33`,
//! [`Display`] writes an edit back in the same words (numbers in Rust's
//! shortest round-trip form, so the text reads back bit-exact), and
//! [`Edit::describe`] names the object as the inspector does.

use std::fmt::{self, Display, Formatter};
use std::str::FromStr;

use glam::Vec3;

use super::{
    CameraChange, Edit, EditError, GeometryChange, LightChange, MaterialField, ObjectChange,
};
use crate::scene::parse::parse_fragment;
use crate::scene::write::{MaterialValues, V, light_command, primitive_command};
use crate::scene::{LightSpec, Material, Primitive, Scene};

/// The material's fields, in the order the `f` line gives them.
pub(super) const MATERIAL_FIELDS: [&str; 7] =
    ["diffuse", "kd", "specular", "ks", "shine", "t", "ior"];
/// What an object has beside its material's fields.
const OBJECT_FIELDS: [&str; 4] = ["translate", "shape", "own", "share"];
/// A sphere's own geometry fields.
const SPHERE_FIELDS: [&str; 2] = ["centre", "radius"];
pub(super) const POINT_LIGHT_FIELDS: [&str; 4] = ["position", "colour", "remove", "add"];
const AREA_LIGHT_FIELDS: [&str; 6] = ["position", "colour", "aim", "size", "remove", "add"];
const CAMERA_FIELDS: [&str; 6] = ["from", "at", "up", "angle", "aperture", "focal"];
/// The commands `shape` takes.
const SHAPE_COMMANDS: [&str; 7] = ["s", "pl", "p", "pp", "c", "box", "mesh"];

/// "a sphere", "an area light".
pub(super) fn article(noun: &str) -> String {
    let an = noun.starts_with(['a', 'e', 'i', 'o', 'u']);
    format!("{} {noun}", if an { "an" } else { "a" })
}

/// The fields an `object N` edit of this primitive takes.
pub(super) fn object_fields(primitive: &Primitive) -> Vec<&'static str> {
    let mut fields = MATERIAL_FIELDS.to_vec();
    if matches!(primitive, Primitive::Sphere { .. }) {
        fields.extend(SPHERE_FIELDS);
    }
    fields.extend(OBJECT_FIELDS);
    fields
}

/// Every field of any object, for an edit read without its scene.
fn any_object_fields() -> Vec<&'static str> {
    let mut fields = MATERIAL_FIELDS.to_vec();
    fields.extend(SPHERE_FIELDS);
    fields.extend(OBJECT_FIELDS);
    fields
}

fn unknown(field: &str, target: &str, fields: &[&str]) -> EditError {
    EditError::UnknownField {
        field: field.to_string(),
        target: target.to_string(),
        fields: fields.join(", "),
    }
}

/// The words after the field name, read as numbers.
struct Values<'a> {
    field: &'a str,
    words: &'a [&'a str],
}

impl Values<'_> {
    /// Exactly `N` finite numbers.
    fn numbers<const N: usize>(&self, expected: &'static str) -> Result<[f32; N], EditError> {
        if self.words.len() != N {
            return Err(EditError::WrongCount {
                field: self.field.to_string(),
                expected,
                found: self.words.len(),
            });
        }
        let mut values = [0.0; N];
        for (value, word) in values.iter_mut().zip(self.words) {
            *value = number(self.field, word)?;
        }
        Ok(values)
    }

    fn one(&self) -> Result<f32, EditError> {
        Ok(self.numbers::<1>("1 number")?[0])
    }

    fn vec3(&self) -> Result<Vec3, EditError> {
        Ok(Vec3::from(self.numbers::<3>("3 numbers (X Y Z)")?))
    }

    fn none(&self) -> Result<(), EditError> {
        self.numbers::<0>("no values").map(|_| ())
    }

    /// The words as P3F text for the parser.
    fn p3f(&self) -> String {
        self.words.join(" ")
    }
}

/// A number as the parser reads one: NaN and infinity refused.
fn number(field: &str, word: &str) -> Result<f32, EditError> {
    match word.parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(EditError::NonFinite {
            field: field.to_string(),
            found: word.to_string(),
        }),
        Err(_) => Err(EditError::NotANumber {
            field: field.to_string(),
            found: word.to_string(),
        }),
    }
}

fn index(what: &'static str, word: Option<&&str>) -> Result<usize, EditError> {
    let word = word.copied().unwrap_or_default();
    word.parse().map_err(|_| EditError::BadIndex {
        what,
        found: word.to_string(),
    })
}

impl FromStr for Edit {
    type Err = EditError;

    /// Reads one `--set` line: `object N FIELD VALUE...`, `material M
    /// FIELD VALUE...`, `light N FIELD VALUE...` (or `light N add l ...`,
    /// `light N remove`), `camera FIELD VALUE...`. Indices are checked
    /// when the edit is applied, field names and values here.
    fn from_str(text: &str) -> Result<Edit, EditError> {
        let words: Vec<&str> = text.split_whitespace().collect();
        let Some(&target) = words.first() else {
            return Err(EditError::Empty);
        };
        let (field, rest) = match target {
            "camera" => (words.get(1), words.get(2..)),
            _ => (words.get(2), words.get(3..)),
        };
        let field = field.copied().unwrap_or_default();
        let values = Values {
            field,
            words: rest.unwrap_or_default(),
        };
        match target {
            "object" => {
                let index = index("object", words.get(1))?;
                let change = object_change(&values)?;
                Ok(Edit::Object { index, change })
            }
            "material" => {
                let index = index("material", words.get(1))?;
                let field = material_field(&values)?
                    .ok_or_else(|| unknown(field, "a material", &MATERIAL_FIELDS))?;
                Ok(Edit::Material { index, field })
            }
            "light" => light_edit(index("light", words.get(1))?, &values),
            "camera" => Ok(Edit::Camera(camera_change(&values)?)),
            other => Err(EditError::UnknownTarget(other.to_string())),
        }
    }
}

impl Edit {
    /// [`FromStr`] with the scene at hand: an unknown field of `object N`
    /// is reported with that object's kind and the fields it has.
    pub fn parse_in(text: &str, scene: &Scene) -> Result<Edit, EditError> {
        text.parse::<Edit>().map_err(|error| {
            let object = text
                .split_whitespace()
                .nth(1)
                .and_then(|w| w.parse::<usize>().ok())
                .filter(|_| text.split_whitespace().next() == Some("object"))
                .and_then(|i| scene.objects.get(i));
            match (error, object) {
                (EditError::UnknownField { field, .. }, Some(object)) => {
                    let kind = object.primitive.kind();
                    unknown(&field, &article(kind), &object_fields(&object.primitive))
                }
                (error, _) => error,
            }
        })
    }
}

/// `None` when the field is not one of the material's.
fn material_field(values: &Values) -> Result<Option<MaterialField>, EditError> {
    use MaterialField as F;
    Ok(Some(match values.field {
        "diffuse" => F::Diffuse(values.vec3()?),
        "kd" => F::Kd(values.one()?),
        "specular" => F::Specular(values.vec3()?),
        "ks" => F::Ks(values.one()?),
        "shine" => F::Shine(values.one()?),
        "t" => F::Transmittance(values.one()?),
        "ior" => F::Ior(values.one()?),
        _ => return Ok(None),
    }))
}

fn object_change(values: &Values) -> Result<ObjectChange, EditError> {
    use GeometryChange as G;
    if let Some(field) = material_field(values)? {
        return Ok(ObjectChange::Material(field));
    }
    let geometry = match values.field {
        "centre" | "center" => G::Centre(values.vec3()?),
        "radius" => G::Radius(values.one()?),
        "translate" => G::Translate(values.vec3()?),
        "shape" => G::Shape(shape(values)?),
        "own" => {
            let [dr, dg, db, kd, sr, sg, sb, ks, shine, t, ior] =
                values.numbers::<11>("11 numbers, as a P3F `f` line")?;
            return Ok(ObjectChange::Own(Material {
                diffuse: Vec3::new(dr, dg, db),
                kd,
                specular: Vec3::new(sr, sg, sb),
                ks,
                shine,
                transmittance: t,
                ior,
            }));
        }
        "share" => {
            let word = values.words.first();
            if values.words.len() != 1 {
                return Err(EditError::WrongCount {
                    field: "share".into(),
                    expected: "1 material index",
                    found: values.words.len(),
                });
            }
            let material = index("material", word)?;
            let material = u32::try_from(material).map_err(|_| EditError::BadIndex {
                what: "material",
                found: material.to_string(),
            })?;
            return Ok(ObjectChange::Share(material));
        }
        other => return Err(unknown(other, "an object", &any_object_fields())),
    };
    Ok(ObjectChange::Geometry(geometry))
}

/// `shape CMD ...`: one P3F shape command, checked by the parser.
fn shape(values: &Values) -> Result<Primitive, EditError> {
    let piece = |message: String| EditError::Piece {
        field: "shape",
        message,
    };
    let command = values.words.first().copied().unwrap_or_default();
    if !SHAPE_COMMANDS.contains(&command) {
        return Err(piece(format!(
            "expected a P3F shape command ({}), found '{command}'",
            SHAPE_COMMANDS.join(", ")
        )));
    }
    let scene = parse_fragment(&values.p3f()).map_err(|e| piece(e.to_string()))?;
    match <[_; 1]>::try_from(scene.objects) {
        Ok([object]) if scene.lights.is_empty() => Ok(object.primitive),
        _ => Err(piece("give exactly one shape command".into())),
    }
}

fn light_edit(index: usize, values: &Values) -> Result<Edit, EditError> {
    let change = match values.field {
        "position" => LightChange::Position(values.vec3()?),
        "colour" | "color" => match values.words {
            ["default"] => LightChange::Colour(None),
            _ => LightChange::Colour(Some(values.vec3()?)),
        },
        "aim" => LightChange::Aim(values.vec3()?),
        "size" => {
            let [width, height] = values.numbers::<2>("2 numbers (W H)")?;
            LightChange::Size { width, height }
        }
        "remove" => {
            values.none()?;
            return Ok(Edit::RemoveLight(index));
        }
        "add" => {
            return Ok(Edit::AddLight {
                index,
                light: light(values)?,
            });
        }
        other => return Err(unknown(other, "a light", &AREA_LIGHT_FIELDS)),
    };
    Ok(Edit::Light { index, change })
}

/// `add l ...` / `add al ...`: one P3F light command, checked by the
/// parser.
fn light(values: &Values) -> Result<LightSpec, EditError> {
    let piece = |message: String| EditError::Piece {
        field: "add",
        message,
    };
    let command = values.words.first().copied().unwrap_or_default();
    if command != "l" && command != "al" {
        return Err(piece(format!(
            "expected a P3F light command (l or al), found '{command}'"
        )));
    }
    let scene = parse_fragment(&values.p3f()).map_err(|e| piece(e.to_string()))?;
    match <[_; 1]>::try_from(scene.lights) {
        Ok([light]) if scene.objects.is_empty() => Ok(light),
        _ => Err(piece("give exactly one light command".into())),
    }
}

fn camera_change(values: &Values) -> Result<CameraChange, EditError> {
    use CameraChange as C;
    Ok(match values.field {
        "from" => C::From(values.vec3()?),
        "at" => C::At(values.vec3()?),
        "up" => C::Up(values.vec3()?),
        "angle" => C::Angle(values.one()?),
        "aperture" => C::Aperture(values.one()?),
        "focal" => C::Focal(values.one()?),
        other => return Err(unknown(other, "the camera", &CAMERA_FIELDS)),
    })
}

impl Display for MaterialField {
    /// `ior 1.33`, `diffuse 1 0.5 0`.
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        use MaterialField as F;
        match self {
            F::Diffuse(v) => write!(f, "diffuse {}", V(*v)),
            F::Kd(v) => write!(f, "kd {v}"),
            F::Specular(v) => write!(f, "specular {}", V(*v)),
            F::Ks(v) => write!(f, "ks {v}"),
            F::Shine(v) => write!(f, "shine {v}"),
            F::Transmittance(v) => write!(f, "t {v}"),
            F::Ior(v) => write!(f, "ior {v}"),
        }
    }
}

impl Display for ObjectChange {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        use GeometryChange as G;
        match self {
            ObjectChange::Material(field) => write!(f, "{field}"),
            ObjectChange::Own(m) => write!(f, "own {}", MaterialValues(m)),
            ObjectChange::Share(m) => write!(f, "share {m}"),
            ObjectChange::Geometry(G::Centre(v)) => write!(f, "centre {}", V(*v)),
            ObjectChange::Geometry(G::Radius(r)) => write!(f, "radius {r}"),
            ObjectChange::Geometry(G::Translate(v)) => write!(f, "translate {}", V(*v)),
            ObjectChange::Geometry(G::Shape(p)) => write!(f, "shape {}", primitive_command(p)),
        }
    }
}

impl Display for LightChange {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            LightChange::Position(v) => write!(f, "position {}", V(*v)),
            LightChange::Colour(Some(c)) => write!(f, "colour {}", V(*c)),
            LightChange::Colour(None) => write!(f, "colour default"),
            LightChange::Aim(v) => write!(f, "aim {}", V(*v)),
            LightChange::Size { width, height } => write!(f, "size {width} {height}"),
        }
    }
}

impl Display for CameraChange {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        use CameraChange as C;
        match self {
            C::From(v) => write!(f, "from {}", V(*v)),
            C::At(v) => write!(f, "at {}", V(*v)),
            C::Up(v) => write!(f, "up {}", V(*v)),
            C::Angle(v) => write!(f, "angle {v}"),
            C::Aperture(v) => write!(f, "aperture {v}"),
            C::Focal(v) => write!(f, "focal {v}"),
        }
    }
}

impl Display for Edit {
    /// The edit as its `--set` line, which [`FromStr`] reads back equal.
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Edit::Object { index, change } => write!(f, "object {index} {change}"),
            Edit::Material { index, field } => write!(f, "material {index} {field}"),
            Edit::Light { index, change } => write!(f, "light {index} {change}"),
            Edit::AddLight { index, light } => {
                write!(f, "light {index} add {}", light_command(light))
            }
            Edit::RemoveLight(index) => write!(f, "light {index} remove"),
            Edit::Camera(change) => write!(f, "camera {change}"),
        }
    }
}

impl Edit {
    /// The edit in a label's words, naming an object as the inspector does
    /// (`sphere #5 ior 1.33`), as it reads before it is applied to `scene`.
    pub fn describe(&self, scene: &Scene) -> String {
        let object = |index: usize| {
            let kind = scene.objects.get(index).map(|o| o.primitive.kind());
            format!("{} #{index}", kind.unwrap_or("object"))
        };
        match self {
            Edit::Object { index, change } => match change {
                ObjectChange::Own(_) => format!("{} gets its own material", object(*index)),
                ObjectChange::Share(m) => format!("{} shares material {m}", object(*index)),
                ObjectChange::Geometry(GeometryChange::Shape(p)) => {
                    format!("{} reshaped as {}", object(*index), article(p.kind()))
                }
                _ => format!("{} {change}", object(*index)),
            },
            Edit::AddLight { index, .. } => format!("light {index} added"),
            Edit::RemoveLight(index) => format!("light {index} removed"),
            Edit::Material { .. } | Edit::Light { .. } | Edit::Camera(_) => self.to_string(),
        }
    }
}

/// Refuses NaN and infinity anywhere in an edit built in code (text is
/// checked as it is read); whole shapes and lights are checked by their
/// rules.
pub(super) fn check_finite(edit: &Edit) -> Result<(), EditError> {
    use GeometryChange as G;
    let check = |field: &str, values: &[f32]| match values.iter().find(|v| !v.is_finite()) {
        Some(v) => Err(EditError::NonFinite {
            field: field.to_string(),
            found: v.to_string(),
        }),
        None => Ok(()),
    };
    let material_field = |field: &MaterialField| {
        let name = field.to_string();
        let name = name.split(' ').next().unwrap_or_default();
        match *field {
            MaterialField::Diffuse(v) | MaterialField::Specular(v) => check(name, &v.to_array()),
            MaterialField::Kd(v)
            | MaterialField::Ks(v)
            | MaterialField::Shine(v)
            | MaterialField::Transmittance(v)
            | MaterialField::Ior(v) => check(name, &[v]),
        }
    };
    match edit {
        Edit::Object { change, .. } => match change {
            ObjectChange::Material(field) => material_field(field),
            ObjectChange::Own(m) => {
                let [dr, dg, db] = m.diffuse.to_array();
                let [sr, sg, sb] = m.specular.to_array();
                let numbers = [dr, dg, db, m.kd, sr, sg, sb, m.ks];
                check("own", &numbers)?;
                check("own", &[m.shine, m.transmittance, m.ior])
            }
            ObjectChange::Share(_) | ObjectChange::Geometry(G::Shape(_)) => Ok(()),
            ObjectChange::Geometry(G::Centre(v)) => check("centre", &v.to_array()),
            ObjectChange::Geometry(G::Translate(v)) => check("translate", &v.to_array()),
            ObjectChange::Geometry(G::Radius(r)) => check("radius", &[*r]),
        },
        Edit::Material { field, .. } => material_field(field),
        Edit::Light { change, .. } => match change {
            LightChange::Position(v) => check("position", &v.to_array()),
            LightChange::Colour(c) => check("colour", &c.unwrap_or_default().to_array()),
            LightChange::Aim(v) => check("aim", &v.to_array()),
            LightChange::Size { width, height } => check("size", &[*width, *height]),
        },
        Edit::AddLight { .. } | Edit::RemoveLight(_) => Ok(()),
        Edit::Camera(change) => {
            let name = change.to_string();
            let name = name.split(' ').next().unwrap_or_default();
            match *change {
                CameraChange::From(v) | CameraChange::At(v) | CameraChange::Up(v) => {
                    check(name, &v.to_array())
                }
                CameraChange::Angle(v) | CameraChange::Aperture(v) | CameraChange::Focal(v) => {
                    check(name, &[v])
                }
            }
        }
    }
}
