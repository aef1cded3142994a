//! `mesh_file PATH [scale S] [translate X Y Z]`: an OBJ or PLY file's
//! triangles as objects of the scene (see `docs/MESH_FILE.md`).

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::Parser;
use crate::scene::lexer::Pos;
use crate::scene::mesh_io::load_mesh_file;
use crate::scene::{ParseError, ParseErrorKind, Primitive};

impl Parser<'_, '_> {
    /// Loads the file (relative to the scene file's folder), applies the
    /// optional transform (scale first), and adds one mesh object per part:
    /// with the material in force, or, before any `f`, the part's MTL
    /// material (the default white without one). A missing, unreadable or
    /// broken file is an error at the path token.
    pub(super) fn mesh_file(&mut self, pos: Pos) -> Result<(), ParseError> {
        let path_pos = self.cursor.here();
        let name = self.cursor.expect("the mesh file path")?.text;
        let mut scale = 1.0;
        let mut offset = Vec3::ZERO;
        let mut seen = (false, false);
        while let Some(word) = self.cursor.peek() {
            match word.text {
                "scale" if !seen.0 => {
                    self.cursor.next_token();
                    let scale_pos = self.cursor.here();
                    scale = self.cursor.number("the mesh scale")?;
                    if scale == 0.0 {
                        return Err(self.invalid(scale_pos, "mesh scale", "must not be zero"));
                    }
                    seen.0 = true;
                }
                "translate" if !seen.1 => {
                    self.cursor.next_token();
                    offset = self.cursor.vec3("the mesh translation")?;
                    seen.1 = true;
                }
                _ => break,
            }
        }
        let path = self.resolve(name);
        let budget = self.limits.max_primitives.saturating_sub(self.primitives);
        let mut mesh = load_mesh_file(&path, self.limits, budget, &mut |_| {}).map_err(|e| {
            self.cursor
                .error_at(path_pos, ParseErrorKind::MeshFile(e.to_string()))
        })?;
        for warning in &mesh.warnings {
            let message = format!("{}: {warning}", path.display());
            let located = self.cursor.warning_at(path_pos, &message);
            self.scene.warnings.push(located);
        }
        mesh.transform(scale, offset);
        if !(mesh.parts.iter())
            .flat_map(|p| &p.vertices)
            .all(|v| v.is_finite())
        {
            let why = "the scaled and translated vertices overflow";
            return Err(self.invalid(path_pos, "mesh transform", why));
        }
        let in_force = self.material;
        let mut white = None;
        for part in mesh.parts {
            let material = match (in_force, part.material, white) {
                (Some(index), _, _) => index,
                (None, None, Some(index)) => index,
                (None, mtl, _) => {
                    let index = self.push_material(mtl.unwrap_or_default(), pos)?;
                    if mtl.is_none() {
                        white = Some(index);
                    }
                    index
                }
            };
            // The file's colours belong to its parts, not to later objects.
            self.material = in_force;
            let mesh = Primitive::Mesh {
                vertices: part.vertices,
                triangles: part.triangles,
            };
            self.push_object_with(mesh, material, pos)?;
        }
        Ok(())
    }

    /// `name` relative to the scene file's folder (the working folder for
    /// text that did not come from a file).
    fn resolve(&self, name: &str) -> PathBuf {
        let name = Path::new(name);
        match self.cursor.file().and_then(Path::parent) {
            Some(dir) if name.is_relative() => dir.join(name),
            _ => name.to_path_buf(),
        }
    }
}
