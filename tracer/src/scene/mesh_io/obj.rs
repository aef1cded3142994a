//! Wavefront OBJ through `tobj`: polygons fanned into triangles, one part
//! per object or group, MTL diffuse and specular colours where present.

use std::cell::RefCell;
use std::io::BufReader;
use std::path::{Path, PathBuf};

use glam::Vec3;

use super::{Bounds, FileReader, MeshFile, MeshFileError, MeshPart, MeshPlace, check_finite};
use crate::scene::Material;

/// Reads the OBJ behind `reader`; MTL libraries it names are looked up
/// beside `path`.
pub(super) fn read(
    path: &Path,
    mut reader: FileReader<'_>,
    bounds: &Bounds,
) -> Result<MeshFile, MeshFileError> {
    let options = tobj::LoadOptions {
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..tobj::LoadOptions::default()
    };
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    let mtl_problems = RefCell::new(Vec::new());
    let load_mtl = |name: &Path| {
        let result = read_mtl(&dir.join(name), bounds.max_bytes);
        if let Err(message) = &result {
            mtl_problems.borrow_mut().push(message.clone());
        }
        result.map_err(|_| tobj::LoadError::OpenFileFailed)
    };
    // tobj is not known to panic, but a reader of foreign files must never
    // take the window down: a panic becomes an error at the line reached.
    let loaded = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut reader, &options, load_mtl)
    }));
    let at_line =
        |message: String| MeshFileError::new(path, MeshPlace::Line(reader.line()), message);
    let (models, materials) = match loaded {
        Ok(Ok(loaded)) => loaded,
        Ok(Err(e)) => return Err(at_line(describe(&e))),
        Err(_) => return Err(at_line("the OBJ reader failed on this line".into())),
    };
    let mut warnings: Vec<String> = mtl_problems.into_inner();
    let materials = materials.unwrap_or_else(|e| {
        if warnings.is_empty() {
            warnings.push(format!("MTL materials: {e}"));
        }
        Vec::new()
    });
    if !warnings.is_empty() {
        warnings.push("parts without their MTL material are neutral grey".into());
    }

    let whole_file = |message: String| MeshFileError::new(path, MeshPlace::File, message);
    let triangles: usize = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
    bounds.check_triangles(triangles).map_err(whole_file)?;
    let mut parts = Vec::with_capacity(models.len());
    for model in models {
        let part_error =
            |message: String| whole_file(format!("object or group `{}`: {message}", model.name));
        let vertices: Vec<Vec3> = model
            .mesh
            .positions
            .chunks_exact(3)
            .map(|p| Vec3::new(p[0], p[1], p[2]))
            .collect();
        bounds.check_vertices(vertices.len()).map_err(part_error)?;
        check_finite(&vertices)
            .map_err(|i| part_error(format!("vertex {} is not a finite number", i + 1)))?;
        let count = vertices.len();
        let triangles: Vec<[u32; 3]> = model
            .mesh
            .indices
            .chunks_exact(3)
            .map(|t| [t[0], t[1], t[2]])
            .collect();
        if let Some(bad) = triangles.iter().flatten().find(|&&i| i as usize >= count) {
            return Err(part_error(format!(
                "a face refers to vertex {} of {count}",
                u64::from(*bad) + 1
            )));
        }
        let material = model
            .mesh
            .material_id
            .and_then(|id| materials.get(id))
            .map(from_mtl);
        parts.push(MeshPart {
            name: model.name,
            vertices,
            triangles,
            material,
        });
    }
    Ok(MeshFile { parts, warnings })
}

/// An MTL library, refused above `max_bytes`; the error names the file.
fn read_mtl(
    file: &PathBuf,
    max_bytes: u64,
) -> Result<
    (
        Vec<tobj::Material>,
        std::collections::HashMap<String, usize>,
    ),
    String,
> {
    let problem = |why: String| format!("cannot read MTL file {}: {why}", file.display());
    let opened = std::fs::File::open(file).map_err(|e| problem(e.to_string()))?;
    let size = opened.metadata().map_err(|e| problem(e.to_string()))?.len();
    if size > max_bytes {
        return Err(problem(format!(
            "{size} bytes is above the limit of {max_bytes}"
        )));
    }
    tobj::load_mtl_buf(&mut BufReader::new(opened)).map_err(|e| problem(describe(&e)))
}

/// A material from MTL colours. The tracer's specular weight also weights
/// the mirror reflection, so MTL's `Ks` (a highlight strength, often 0.5)
/// is taken at a quarter lest every OBJ turn into a half mirror.
fn from_mtl(m: &tobj::Material) -> Material {
    let neutral = super::framing::neutral_material();
    let colour = |c: Option<[f32; 3]>| c.map(Vec3::from).filter(|c| c.is_finite());
    let dissolve = m
        .dissolve
        .filter(|d| d.is_finite())
        .unwrap_or(1.0)
        .clamp(0.0, 1.0);
    Material {
        diffuse: colour(m.diffuse)
            .unwrap_or(neutral.diffuse)
            .clamp(Vec3::ZERO, Vec3::ONE),
        kd: 1.0,
        specular: colour(m.specular)
            .unwrap_or(neutral.specular)
            .clamp(Vec3::ZERO, Vec3::ONE),
        ks: if m.specular.is_some() {
            0.25
        } else {
            neutral.ks
        },
        shine: m
            .shininess
            .filter(|s| s.is_finite())
            .unwrap_or(neutral.shine)
            .clamp(1.0, 1000.0),
        transmittance: 1.0 - dissolve,
        ior: m
            .optical_density
            .filter(|n| n.is_finite() && *n >= 1.0)
            .unwrap_or(1.0),
    }
}

/// What a tobj error means, in the terms of the file.
fn describe(e: &tobj::LoadError) -> String {
    use tobj::LoadError as E;
    match e {
        E::PositionParseError => "a vertex position (`v`) needs three numbers".into(),
        E::NormalParseError => "a normal (`vn`) needs three numbers".into(),
        E::TexcoordParseError => "a texture coordinate (`vt`) needs one to three numbers".into(),
        E::ColorParseError => "a vertex colour needs three numbers".into(),
        E::FaceParseError => {
            "a face (`f`) needs vertex indices such as `1`, `1/2`, `1//3` or `-1`".into()
        }
        E::FaceVertexOutOfBounds => {
            "a face in the object or group ending here refers to a vertex that is not defined"
                .into()
        }
        E::FaceTexCoordOutOfBounds | E::FaceNormalOutOfBounds | E::FaceColorOutOfBounds => {
            "a face in the object or group ending here refers to a texture coordinate or normal \
             that is not defined"
                .into()
        }
        E::InvalidPolygon => "a face needs at least three vertices".into(),
        E::MaterialParseError => "a material statement is incomplete".into(),
        E::InvalidObjectName => "an object or group statement has no name".into(),
        E::ReadError => "the file cannot be read here (not text?)".into(),
        other => other.to_string(),
    }
}
