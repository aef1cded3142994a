//! PLY (ASCII, binary little and big endian) through `ply-rs-bw`: the
//! `vertex` element's x, y, z and the `face` element's index lists, fanned
//! into triangles. Other elements are read past.

use std::path::Path;

use glam::Vec3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, ElementDef, Encoding, Header, Property, PropertyAccess};

use super::{Bounds, FileReader, MeshFile, MeshFileError, MeshPart, MeshPlace, check_finite};

/// A vertex as the file gives it; only the position matters.
struct PlyVertex([f32; 3]);

impl PropertyAccess for PlyVertex {
    fn new() -> Self {
        PlyVertex([0.0; 3])
    }

    fn set_property(&mut self, name: &str, property: Property) {
        let axis = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => return,
        };
        self.0[axis] = match property {
            Property::Char(v) => v.into(),
            Property::UChar(v) => v.into(),
            Property::Short(v) => v.into(),
            Property::UShort(v) => v.into(),
            Property::Int(v) => v as f32,
            Property::UInt(v) => v as f32,
            Property::Float(v) => v,
            Property::Double(v) => v as f32,
            _ => f32::NAN,
        };
    }
}

/// A face's vertex indices; `None` when one is negative or not a whole
/// number.
struct PlyFace(Option<Vec<u32>>);

impl PropertyAccess for PlyFace {
    fn new() -> Self {
        PlyFace(Some(Vec::new()))
    }

    fn set_property(&mut self, name: &str, property: Property) {
        if name != "vertex_indices" && name != "vertex_index" {
            return;
        }
        fn all<T: Copy>(list: Vec<T>, f: impl Fn(T) -> Option<u32>) -> Option<Vec<u32>> {
            list.into_iter().map(f).collect()
        }
        self.0 = match property {
            Property::ListChar(l) => all(l, |i| u32::try_from(i).ok()),
            Property::ListUChar(l) => all(l, |i| Some(i.into())),
            Property::ListShort(l) => all(l, |i| u32::try_from(i).ok()),
            Property::ListUShort(l) => all(l, |i| Some(i.into())),
            Property::ListInt(l) => all(l, |i| u32::try_from(i).ok()),
            Property::ListUInt(l) => Some(l),
            _ => None,
        };
    }
}

/// Reads the PLY behind `reader`.
pub(super) fn read(
    path: &Path,
    mut reader: FileReader<'_>,
    bounds: &Bounds,
) -> Result<MeshFile, MeshFileError> {
    let header = Parser::<PlyVertex>::new()
        .read_header(&mut reader)
        .map_err(|e| MeshFileError::new(path, MeshPlace::Line(reader.line()), first_line(&e)))?;
    let element_error = |name: &str, message: String| {
        MeshFileError::new(
            path,
            MeshPlace::Element {
                name: name.into(),
                index: None,
            },
            message,
        )
    };
    let vertex_def = header
        .elements
        .get("vertex")
        .ok_or_else(|| element_error("vertex", "the header declares no `vertex` element".into()))?;
    if let Some(axis) = ["x", "y", "z"]
        .into_iter()
        .find(|p| !vertex_def.properties.contains_key(*p))
    {
        return Err(element_error(
            "vertex",
            format!("the header declares no `{axis}` property"),
        ));
    }
    bounds
        .check_vertices(vertex_def.count)
        .map_err(|m| element_error("vertex", m))?;
    let face_def = header
        .elements
        .get("face")
        .ok_or_else(|| element_error("face", "the header declares no `face` element".into()))?;
    if !["vertex_indices", "vertex_index"]
        .iter()
        .any(|p| face_def.properties.contains_key(*p))
    {
        return Err(element_error(
            "face",
            "the header declares no `vertex_indices` list".into(),
        ));
    }
    bounds
        .check_triangles(face_def.count)
        .map_err(|m| element_error("face", m))?;

    let mut vertices = Vec::new();
    let mut faces = Vec::new();
    for def in header.elements.values() {
        match def.name.as_str() {
            "vertex" => vertices = payload::<PlyVertex>(path, &mut reader, def, &header)?,
            "face" => faces = payload::<PlyFace>(path, &mut reader, def, &header)?,
            _ => {
                payload::<DefaultElement>(path, &mut reader, def, &header)?;
            }
        }
    }
    let vertices: Vec<Vec3> = vertices.into_iter().map(|v| Vec3::from(v.0)).collect();
    check_finite(&vertices).map_err(|i| {
        MeshFileError::new(
            path,
            MeshPlace::Element {
                name: "vertex".into(),
                index: Some(i),
            },
            "a coordinate is not a finite number",
        )
    })?;
    let triangles = fan(path, &faces, vertices.len(), bounds)?;
    let name = path
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    Ok(MeshFile {
        parts: vec![MeshPart {
            name,
            vertices,
            triangles,
            material: None,
        }],
        warnings: Vec::new(),
    })
}

/// The elements of `def`, read with `E`. An error is placed at the line
/// reached for ASCII files, at the element for binary ones.
fn payload<E: PropertyAccess>(
    path: &Path,
    reader: &mut FileReader<'_>,
    def: &ElementDef,
    header: &Header,
) -> Result<Vec<E>, MeshFileError> {
    Parser::<E>::new()
        .read_payload_for_element(reader, def, header)
        .map_err(|e| {
            let (place, message) = match header.encoding {
                Encoding::Ascii => (
                    MeshPlace::Line(reader.line()),
                    format!("in element `{}`: {}", def.name, first_line(&e)),
                ),
                _ => (
                    MeshPlace::Element {
                        name: def.name.clone(),
                        index: None,
                    },
                    first_line(&e),
                ),
            };
            MeshFileError::new(path, place, message)
        })
}

/// Faces as triangle fans, every index checked against `vertex_count`.
fn fan(
    path: &Path,
    faces: &[PlyFace],
    vertex_count: usize,
    bounds: &Bounds,
) -> Result<Vec<[u32; 3]>, MeshFileError> {
    let face_error = |index: usize, message: String| {
        MeshFileError::new(
            path,
            MeshPlace::Element {
                name: "face".into(),
                index: Some(index),
            },
            message,
        )
    };
    let mut triangles = Vec::with_capacity(faces.len());
    for (index, face) in faces.iter().enumerate() {
        let Some(indices) = &face.0 else {
            return Err(face_error(index, "a vertex index is negative".into()));
        };
        if let Some(bad) = indices.iter().find(|&&i| i as usize >= vertex_count) {
            return Err(face_error(
                index,
                format!("vertex index {bad} is out of range for {vertex_count} vertices"),
            ));
        }
        let [first, rest @ ..] = indices.as_slice() else {
            return Err(face_error(index, "the face has no vertex".into()));
        };
        if rest.len() < 2 {
            return Err(face_error(
                index,
                format!("a face needs at least 3 vertices, found {}", indices.len()),
            ));
        }
        for pair in rest.windows(2) {
            triangles.push([*first, pair[0], pair[1]]);
        }
        bounds
            .check_triangles(triangles.len())
            .map_err(|m| face_error(index, m))?;
    }
    Ok(triangles)
}

/// A `ply-rs-bw` error in one line: its message without its own "Line N:"
/// prefix (its lines count from the start of each element), and the text
/// it could not read, if it quotes it.
fn first_line(e: &std::io::Error) -> String {
    let text = e.to_string();
    let mut lines = text.lines();
    let first = lines.next().unwrap_or_default();
    let message = match first.split_once(": ") {
        Some((prefix, rest)) if prefix.starts_with("Line ") => rest,
        _ => first,
    };
    let quoted = lines.find_map(|l| l.trim().strip_prefix("String: "));
    match quoted {
        Some(quoted) => format!("{message} (read {})", quoted.trim()),
        None => message.to_string(),
    }
}
