//! Meshes from the files people have: Wavefront OBJ (with its MTL colours,
//! through `tobj`) and PLY (ASCII and binary, through `ply-rs-bw`). A mesh
//! file becomes triangles and materials the scene document can hold; a bare
//! one is framed into a whole scene by [`frame`].
//!
//! Every problem is a [`MeshFileError`] naming the file and the line (OBJ,
//! ASCII PLY) or element (PLY) where it was found; nothing a file says is
//! trusted before it has been checked against [`Limits`].

mod framing;
mod obj;
mod ply;
mod tracked;

#[cfg(test)]
mod tests;

use std::io::Read;
use std::path::{Path, PathBuf};

use glam::Vec3;

use crate::scene::{Limits, Material};

pub use framing::{FRAMING_NOTE, frame};

/// One part of a mesh file: the triangles drawn with one material.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshPart {
    /// The OBJ object or group name, or the file's stem for PLY.
    pub name: String,
    /// The vertex positions, in the file's coordinates.
    pub vertices: Vec<Vec3>,
    /// Zero-based, range-checked indices into `vertices`.
    pub triangles: Vec<[u32; 3]>,
    /// The MTL material of an OBJ part, when the file names one.
    pub material: Option<Material>,
}

/// What a mesh file holds, ready to become scene objects.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshFile {
    /// The parts in file order: OBJ objects or groups, or one part for PLY.
    pub parts: Vec<MeshPart>,
    /// Things the user should know that did not stop the load (a missing
    /// MTL file).
    pub warnings: Vec<String>,
}

impl MeshFile {
    /// Triangles over all parts.
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.triangles.len()).sum()
    }

    /// Multiplies every vertex by `scale`, then adds `offset` (the `mesh_file`
    /// command's optional transform).
    pub fn transform(&mut self, scale: f32, offset: Vec3) {
        for part in &mut self.parts {
            for v in &mut part.vertices {
                *v = *v * scale + offset;
            }
        }
    }
}

/// The mesh formats the workbench reads, told apart by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (`.obj`), with MTL materials.
    Obj,
    /// Stanford PLY (`.ply`), ASCII or binary.
    Ply,
}

impl MeshFormat {
    /// The format of `path` by its extension (any case), `None` for other files.
    pub fn of(path: &Path) -> Option<MeshFormat> {
        let ext = path.extension()?.to_str()?;
        if ext.eq_ignore_ascii_case("obj") {
            Some(MeshFormat::Obj)
        } else if ext.eq_ignore_ascii_case("ply") {
            Some(MeshFormat::Ply)
        } else {
            None
        }
    }
}

/// Where in a mesh file a problem is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MeshPlace {
    /// The file as a whole (it cannot be opened, is too large, holds no
    /// triangle).
    File,
    /// A 1-based line of an OBJ or ASCII PLY file.
    Line(u64),
    /// A PLY element: its name and 0-based index (or the whole element
    /// list when `None`).
    Element {
        /// The element's name, e.g. "vertex".
        name: String,
        /// Which one, 0-based; `None` for the whole list.
        index: Option<usize>,
    },
}

impl std::fmt::Display for MeshPlace {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MeshPlace::File => Ok(()),
            MeshPlace::Line(line) => write!(f, ":{line}"),
            MeshPlace::Element {
                name,
                index: Some(i),
            } => write!(f, ": {name} {i}"),
            MeshPlace::Element { name, index: None } => write!(f, ": element `{name}`"),
        }
    }
}

/// Why a mesh file could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{place}: {message}", file.display())]
pub struct MeshFileError {
    /// The mesh file.
    pub file: PathBuf,
    /// Where in it the fault is.
    pub place: MeshPlace,
    /// What is wrong.
    pub message: String,
}

impl MeshFileError {
    fn new(file: &Path, place: MeshPlace, message: impl Into<String>) -> Self {
        Self {
            file: file.to_path_buf(),
            place,
            message: message.into(),
        }
    }
}

/// How much of a file has been read, for a progress message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LoadProgress {
    /// Bytes read so far.
    pub bytes_read: u64,
    /// The file's size in bytes.
    pub total_bytes: u64,
}

/// Reads an OBJ or PLY file (by extension). `max_triangles` bounds the
/// triangles over all parts (what is left of [`Limits::max_primitives`]);
/// `on_progress` is called every few megabytes.
pub fn load_mesh_file(
    path: &Path,
    limits: &Limits,
    max_triangles: usize,
    on_progress: &mut dyn FnMut(LoadProgress),
) -> Result<MeshFile, MeshFileError> {
    let error = |place, message: String| MeshFileError::new(path, place, message);
    let format = MeshFormat::of(path).ok_or_else(|| {
        error(
            MeshPlace::File,
            "not a mesh file: the name must end in .obj or .ply".into(),
        )
    })?;
    let file = std::fs::File::open(path)
        .map_err(|e| error(MeshPlace::File, format!("cannot read the mesh file: {e}")))?;
    let metadata = file
        .metadata()
        .map_err(|e| error(MeshPlace::File, format!("cannot read the mesh file: {e}")))?;
    if !metadata.is_file() {
        return Err(error(MeshPlace::File, "not a regular file".into()));
    }
    let size = metadata.len();
    if size > limits.max_file_bytes {
        return Err(error(
            MeshPlace::File,
            format!(
                "size in bytes {size} exceeds the limit of {}",
                limits.max_file_bytes
            ),
        ));
    }
    let bounds = Bounds {
        max_vertices: limits.max_mesh_vertices,
        max_triangles: max_triangles.min(limits.max_mesh_triangles),
        max_bytes: limits.max_file_bytes,
    };
    // Never more than the size checked above, even if the file grows.
    let reader = tracked::Tracked::new(file.take(size), size, on_progress);
    let mesh = match format {
        MeshFormat::Obj => obj::read(path, reader, &bounds)?,
        MeshFormat::Ply => ply::read(path, reader, &bounds)?,
    };
    if mesh.triangle_count() == 0 {
        return Err(error(MeshPlace::File, "the file holds no triangle".into()));
    }
    Ok(mesh)
}

/// The mesh file as the readers see it: at most the size checked, counted.
type FileReader<'p> = tracked::Tracked<'p, std::io::Take<std::fs::File>>;

/// What the readers may accept.
struct Bounds {
    max_vertices: usize,
    max_triangles: usize,
    /// Largest MTL file read beside an OBJ.
    max_bytes: u64,
}

impl Bounds {
    /// An error when `triangles` exceed the bound.
    fn check_triangles(&self, triangles: usize) -> Result<(), String> {
        if triangles > self.max_triangles {
            return Err(format!(
                "triangle count {triangles} exceeds the limit of {}",
                self.max_triangles
            ));
        }
        Ok(())
    }

    fn check_vertices(&self, vertices: usize) -> Result<(), String> {
        if vertices > self.max_vertices {
            return Err(format!(
                "vertex count {vertices} exceeds the limit of {}",
                self.max_vertices
            ));
        }
        Ok(())
    }
}

/// Checks that every coordinate is finite: a scanned mesh with a NaN
/// vertex would poison the bounds and the acceleration structure.
fn check_finite(vertices: &[Vec3]) -> Result<(), usize> {
    match vertices.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(i),
        None => Ok(()),
    }
}
