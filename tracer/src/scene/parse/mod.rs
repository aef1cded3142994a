//! The NFF/P3F parser: entry points and the command dispatch. The commands
//! themselves live in the submodules, grouped by what they declare.

mod appearance;
mod cursor;
mod mesh_file;
mod shapes;
mod viewpoint;

use std::io::Read;
use std::path::Path;

use self::cursor::{Cursor, looks_numeric};
use super::lexer::{Pos, Token};
use super::{Limits, Object, ParseError, ParseErrorKind, Primitive, Scene, rules};

/// Every command word: the parser tells a misspelt `v` field from the next
/// command by it, and the scene-file guide is checked against it. `#`
/// comments are removed by the lexer.
#[rustfmt::skip]
pub const COMMANDS: [&str; 18] = [
    "v", "b", "bclr", "env", "l", "al", "f", "s", "pl", "p", "pp", "c", "box", "mesh", "mesh_file",
    "accel", "spp", "adaptive",
];

/// Every field of the camera (`v`) block, as [`ParseErrorKind::UnknownViewField`]
/// lists them and the scene-file guide documents them.
#[rustfmt::skip]
pub const VIEW_FIELDS: [&str; 8] = [
    "from", "at", "up", "angle", "hither", "resolution", "aperture", "focal",
];

/// Parses scene text; `file` only labels errors and sets `base_dir` (its
/// folder, `.` for a bare file name). The first problem found is returned,
/// pointing at the offending token; nothing is allocated from a count before
/// it has been checked against `limits` and against the rest of the input.
pub fn parse_scene(text: &str, file: Option<&Path>, limits: &Limits) -> Result<Scene, ParseError> {
    let size = u64::try_from(text.len()).unwrap_or(u64::MAX);
    if size > limits.max_file_bytes {
        return Err(file_error(file, too_large(size, limits)));
    }
    let mut parser = Parser::new(text, file, limits);
    let commands = parser.commands()?;
    if !parser.view_given && parser.scene.objects.is_empty() {
        let what = if commands == 0 {
            "the file holds no command (only comments or blank lines)"
        } else {
            "it has no camera (`v`) and no objects"
        };
        return Err(file_error(file, ParseErrorKind::EmptyScene(what)));
    }
    let mut scene = parser.scene;
    scene.base_dir = file.map(|f| match f.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.to_path_buf(),
        _ => Path::new(".").to_path_buf(),
    });
    Ok(scene)
}

/// Parses `text` as commands on a fresh document, without asking for a
/// camera or an object: the P3F pieces an edit carries (`object 3 shape s
/// 0 0 0 1`, `light 0 add l 1 2 3`), checked as a file's would be.
pub(crate) fn parse_fragment(text: &str) -> Result<Scene, ParseError> {
    let limits = Limits::default();
    let mut parser = Parser::new(text, None, &limits);
    parser.commands()?;
    Ok(parser.scene)
}

/// Reads and parses a scene file. Bytes that are not UTF-8 (a Latin-1
/// comment, say) are replaced rather than rejected.
pub fn parse_scene_file(path: &Path, limits: &Limits) -> Result<Scene, ParseError> {
    let io_error = |e: std::io::Error| file_error(Some(path), ParseErrorKind::Io(e.to_string()));
    let file = std::fs::File::open(path).map_err(io_error)?;
    // Refuse a file known to be too large before reading any of it.
    let known_size = file
        .metadata()
        .ok()
        .filter(|m| m.is_file())
        .map(|m| m.len());
    if let Some(size) = known_size.filter(|&size| size > limits.max_file_bytes) {
        return Err(file_error(Some(path), too_large(size, limits)));
    }
    let mut bytes = Vec::new();
    // Read one byte past the limit to notice a too-large (or growing) file
    // without reading all of it.
    file.take(limits.max_file_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io_error)?;
    let size = u64::try_from(bytes.len()).unwrap_or(u64::MAX);
    if size > limits.max_file_bytes {
        return Err(file_error(Some(path), too_large(size, limits)));
    }
    parse_scene(&String::from_utf8_lossy(&bytes), Some(path), limits)
}

/// An error about the file as a whole, at line 0, column 0.
fn file_error(file: Option<&Path>, kind: ParseErrorKind) -> ParseError {
    ParseError {
        file: file.map(Path::to_path_buf),
        line: 0,
        column: 0,
        command: None,
        kind,
    }
}

fn too_large(size: u64, limits: &Limits) -> ParseErrorKind {
    ParseErrorKind::AboveLimit {
        what: "size in bytes",
        found: format!("{size}+"),
        limit: limits.max_file_bytes,
    }
}

/// The state while commands are read: the document so far and the material
/// in force.
struct Parser<'a, 'l> {
    cursor: Cursor<'a>,
    limits: &'l Limits,
    scene: Scene,
    /// Index of the material for following objects; `None` before any `f`.
    material: Option<u32>,
    /// Primitives so far, polygons and meshes counted as their triangles.
    primitives: usize,
    /// Whether a `v` command came: a file with neither a camera nor an
    /// object is refused as empty.
    view_given: bool,
}

impl<'a, 'l> Parser<'a, 'l> {
    fn new(text: &'a str, file: Option<&'a Path>, limits: &'l Limits) -> Self {
        Parser {
            cursor: Cursor::new(text, file),
            limits,
            scene: Scene::default(),
            material: None,
            primitives: 0,
            view_given: false,
        }
    }

    /// Reads every command; returns how many there were.
    fn commands(&mut self) -> Result<usize, ParseError> {
        let mut commands = 0usize;
        while let Some(token) = self.cursor.next_token() {
            self.cursor.set_command(Some(token.text));
            self.command(token)?;
            self.cursor.set_command(None);
            commands += 1;
        }
        Ok(commands)
    }
}

impl Parser<'_, '_> {
    fn command(&mut self, token: Token<'_>) -> Result<(), ParseError> {
        match token.text {
            "v" => {
                self.view_given = true;
                self.view(token.pos)
            }
            "b" | "bclr" => self.background(),
            "env" => self.env(),
            "l" => self.point_light(token.pos),
            "al" => self.area_light(token.pos),
            "f" => self.material(token.pos),
            "s" => self.sphere(token.pos),
            "pl" => self.plane(token.pos),
            "p" => self.polygon(token.pos),
            "pp" => self.patch(token.pos),
            "c" => self.cone(token.pos),
            "box" => self.aabox(token.pos),
            "mesh" => self.mesh(token.pos),
            "mesh_file" => self.mesh_file(token.pos),
            "accel" => self.accel(),
            "spp" => self.spp(),
            "adaptive" => self.adaptive(),
            word => {
                // Not inside any command: the error names none.
                self.cursor.set_command(None);
                let kind = if looks_numeric(word) {
                    ParseErrorKind::UnexpectedNumber(word.to_string())
                } else {
                    ParseErrorKind::UnknownCommand(word.to_string())
                };
                Err(self.cursor.error_at(token.pos, kind))
            }
        }
    }

    /// Adds an object with the material in force, pushing the default
    /// material first if no `f` came yet.
    fn push_object(&mut self, primitive: Primitive, pos: Pos) -> Result<(), ParseError> {
        let material = match self.material {
            Some(index) => index,
            None => self.push_material(super::Material::default(), pos)?,
        };
        self.push_object_with(primitive, material, pos)
    }

    /// Adds an object with the material at index `material`.
    fn push_object_with(
        &mut self,
        primitive: Primitive,
        material: u32,
        pos: Pos,
    ) -> Result<(), ParseError> {
        let objects = self.scene.objects.len();
        if objects >= self.limits.max_objects {
            return Err(self.above_limit("object count", objects, self.limits.max_objects, pos));
        }
        let primitives = match &primitive {
            Primitive::Polygon { vertices } | Primitive::Patch { vertices, .. } => {
                vertices.len().saturating_sub(2)
            }
            Primitive::Mesh { triangles, .. } => triangles.len(),
            _ => 1,
        };
        self.check_primitives(primitives, pos)?;
        self.primitives += primitives;
        self.scene.objects.push(Object {
            primitive,
            material,
        });
        self.scene.object_positions.0.push((pos.line, pos.column));
        Ok(())
    }

    /// Whether `more` primitives still fit under [`Limits::max_primitives`];
    /// meshes ask before reserving memory for their triangles.
    fn check_primitives(&self, more: usize, pos: Pos) -> Result<(), ParseError> {
        let total = self.primitives.saturating_add(more);
        if total <= self.limits.max_primitives {
            return Ok(());
        }
        Err(self.cursor.error_at(
            pos,
            ParseErrorKind::AboveLimit {
                what: "primitive count (polygons and meshes as triangles)",
                found: total.to_string(),
                limit: self.limits.max_primitives.try_into().unwrap_or(u64::MAX),
            },
        ))
    }

    /// Adds a material and makes it the one in force.
    fn push_material(&mut self, material: super::Material, pos: Pos) -> Result<u32, ParseError> {
        let count = self.scene.materials.len();
        let index = u32::try_from(count)
            .ok()
            .filter(|_| count < self.limits.max_materials);
        let Some(index) = index else {
            return Err(self.above_limit("material count", count, self.limits.max_materials, pos));
        };
        self.scene.materials.push(material);
        self.material = Some(index);
        Ok(index)
    }

    /// An [`ParseErrorKind::AboveLimit`] for adding one more item to `count`.
    fn above_limit(&self, what: &'static str, count: usize, limit: usize, pos: Pos) -> ParseError {
        self.cursor.error_at(
            pos,
            ParseErrorKind::AboveLimit {
                what,
                found: count.saturating_add(1).to_string(),
                limit: limit.try_into().unwrap_or(u64::MAX),
            },
        )
    }

    /// A broken [`rules`] rule as an error at `pos`.
    fn rule(&self, pos: Pos, rule: Result<(), rules::Invalid>) -> Result<(), ParseError> {
        rule.map_err(|rules::Invalid { what, why }| self.invalid(pos, what, why))
    }

    fn invalid(&self, pos: Pos, what: &'static str, why: impl Into<String>) -> ParseError {
        self.cursor.error_at(
            pos,
            ParseErrorKind::InvalidValue {
                what,
                why: why.into(),
            },
        )
    }
}
