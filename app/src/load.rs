//! Loading a scene, from a file or from the scenes embedded in the binary,
//! into a world ready to render, with the context a user needs when it fails.

use std::cell::RefCell;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use web_time::Instant;

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
use tracer::scene::edit::Edit;
use tracer::scene::mesh_io::{self, LoadProgress, MeshFormat};
use tracer::scene::{Limits, Scene, parse_scene, parse_scene_file};
use tracer::skybox::{Skybox, SkyboxError};
use tracer::world::World;

use crate::bundled;

/// Where a scene comes from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum SceneSource {
    /// A file on disk.
    File(PathBuf),
    /// A scene embedded in the binary, by name.
    Bundled(String),
    /// A scene written in memory, as P3F text, under a name: a lesson's
    /// step set up on the web page, which has no files to write it to.
    Written { name: String, text: String },
}

impl SceneSource {
    /// A short name for titles and lists.
    pub fn label(&self) -> String {
        match self {
            SceneSource::File(path) => path.file_name().map_or_else(
                || path.display().to_string(),
                |n| n.to_string_lossy().into(),
            ),
            SceneSource::Bundled(name) | SceneSource::Written { name, .. } => name.clone(),
        }
    }

    /// Whether this is a bare OBJ or PLY mesh, framed into a scene when
    /// loaded (see [`mesh_io::frame`]).
    pub(crate) fn is_bare_mesh(&self) -> bool {
        matches!(self, SceneSource::File(path) if MeshFormat::of(path).is_some())
    }
}

/// A scene ready to render: where it came from, the parsed document, the
/// world built from it and how long that took. The one shape of a loaded
/// scene, made by [`Loaded::read`] (the window, the lessons) or
/// [`Loaded::for_command`] (the headless commands).
#[derive(Clone)]
pub struct Loaded {
    pub source: SceneSource,
    pub scene: Scene,
    pub world: Arc<World>,
    /// How long parsing and preparing took.
    pub(crate) load_time: Duration,
}

impl Loaded {
    /// Reads and prepares `source`, with `--set` edits applied to the scene
    /// before the world is built from it (see [`apply_edits`]), reporting
    /// how much of a large mesh file has been read. Warnings from preparing
    /// the world stay in `World::warnings` for the caller to show.
    pub fn read(
        source: SceneSource,
        edits: &[String],
        on_progress: &mut dyn FnMut(LoadProgress),
    ) -> Result<Self> {
        let start = Instant::now();
        let (mut scene, warnings) = read_source(&source, on_progress)?;
        apply_edits(&mut scene, edits)?;
        let mut world = match &source {
            SceneSource::Bundled(_) | SceneSource::Written { .. } => {
                World::build_with_skybox(&scene, embedded_skybox)
            }
            SceneSource::File(_) => build_with_sky(&scene),
        };
        world.warnings.extend(warnings);
        Ok(Self {
            source,
            scene,
            world: Arc::new(world),
            load_time: start.elapsed(),
        })
    }

    /// Parses a scene file (or frames a bare mesh) for the headless
    /// commands, with `--set` edits applied before the world is built;
    /// warnings, and progress while a large mesh is read, go to stderr.
    pub(crate) fn for_command(path: &Path, edits: &[String]) -> Result<Self> {
        if is_lesson_file(path) {
            let path = path.display();
            anyhow::bail!(
                "{path} is a lesson, not a scene: open it in the window with \
                 `workbench --lesson {path}` (or Ctrl+O), test it with \
                 `workbench lesson check {path}`, see a step's state with \
                 `workbench lesson explain {path} --step N`"
            );
        }
        let source = SceneSource::File(path.to_path_buf());
        let mut progress = MeshProgress::new(path);
        let loaded = Self::read(source, edits, &mut |p| progress.show(p))?;
        progress.finish(&loaded.world, loaded.load_time);
        if loaded.source.is_bare_mesh() {
            eprintln!("note: {}: {}", path.display(), mesh_io::FRAMING_NOTE);
        }
        for warning in &loaded.world.warnings {
            eprintln!("warning: {}: {warning}", path.display());
        }
        Ok(loaded)
    }

    /// This scene with more `--set` edits (one side of a comparison), and
    /// the edits in words (see [`with_edits`]).
    pub(crate) fn edited(&self, lines: &[String]) -> Result<(Loaded, Vec<String>)> {
        let (scene, world, described) = with_edits(&self.scene, &self.world, lines)?;
        let edited = Loaded {
            source: self.source.clone(),
            scene,
            world,
            load_time: self.load_time,
        };
        Ok((edited, described))
    }
}

/// `scene` and its `world` with more `--set` edits, and the edits in
/// words. The world follows each edit ([`World::update`]) instead of being
/// built again: the skybox and the untouched shapes are kept.
pub(crate) fn with_edits(
    scene: &Scene,
    world: &Arc<World>,
    lines: &[String],
) -> Result<(Scene, Arc<World>, Vec<String>)> {
    let mut scene = scene.clone();
    if lines.is_empty() {
        return Ok((scene, world.clone(), Vec::new()));
    }
    let mut world = (**world).clone();
    let described = apply_edits_then(&mut scene, lines, |scene, edit| world.update(scene, edit))?;
    Ok((scene, Arc::new(world), described))
}

/// The scene document of `source`, and what reading a bare mesh warned of.
fn read_source(
    source: &SceneSource,
    on_progress: &mut dyn FnMut(LoadProgress),
) -> Result<(Scene, Vec<String>)> {
    match source {
        SceneSource::File(path) if source.is_bare_mesh() => {
            let limits = Limits::default();
            // The error already names the file and the line or element.
            let mesh = mesh_io::load_mesh_file(path, &limits, limits.max_primitives, on_progress)?;
            let warnings = mesh.warnings.clone();
            let mut scene = mesh_io::frame(mesh);
            scene.base_dir = path.parent().map(Path::to_path_buf);
            Ok((scene, warnings))
        }
        // The parse error already names the file, line and column.
        SceneSource::File(path) => Ok((parse_scene_file(path, &Limits::default())?, Vec::new())),
        SceneSource::Bundled(name) => {
            let bundled =
                bundled::find(name).with_context(|| format!("no bundled scene called `{name}`"))?;
            let scene = parse_scene(
                bundled.text,
                Some(Path::new(bundled.file)),
                &Limits::default(),
            )?;
            Ok((scene, Vec::new()))
        }
        SceneSource::Written { name, text } => Ok((
            parse_scene(text, Some(Path::new(name)), &Limits::default())?,
            Vec::new(),
        )),
    }
}

/// Applies `--set` lines to `scene` in order, each read against the scene
/// the earlier ones left (so `object 0 t 0.5` may follow `object 0 ior
/// 1.5`); returns each edit in words (`sphere #5 ior 1.33`). The error
/// quotes the line and says what is wrong, naming the valid range or the
/// fields.
pub(crate) fn apply_edits(scene: &mut Scene, lines: &[String]) -> Result<Vec<String>> {
    apply_edits_then(scene, lines, |_, _| {})
}

/// [`apply_edits`], calling `then` with the scene after each edit.
fn apply_edits_then(
    scene: &mut Scene,
    lines: &[String],
    mut then: impl FnMut(&Scene, &Edit),
) -> Result<Vec<String>> {
    let mut described = Vec::with_capacity(lines.len());
    for line in lines {
        let edit = Edit::parse_in(line, scene)
            .and_then(|edit| {
                let words = edit.describe(scene);
                edit.apply(scene)?;
                described.push(words);
                Ok(edit)
            })
            .map_err(|e| anyhow::anyhow!("--set '{line}': {e}"))?;
        then(scene, &edit);
    }
    Ok(described)
}

/// The world of a scene from disk: an `env` folder that cannot be loaded
/// falls back to the bundled sky (not the flat background), with a warning.
/// The bundled sky is painted y-up; it is stood upright on the camera's
/// `up`, so a z-up course scene shows sky, not ground, above its horizon.
pub(crate) fn build_with_sky(scene: &Scene) -> World {
    let problem = RefCell::new(None);
    let mut world = World::build_with_skybox(scene, |name| {
        let dir = scene
            .base_dir
            .as_deref()
            .unwrap_or(Path::new("."))
            .join(name);
        Skybox::load(&dir).or_else(|e| {
            let bundled = embedded_skybox(name).map(|sky| sky.upright(scene.view.up));
            if bundled.is_ok() {
                *problem.borrow_mut() = Some(e);
                bundled
            } else {
                Err(e)
            }
        })
    });
    if let Some(e) = problem.into_inner() {
        world
            .warnings
            .push(format!("{e}; using the bundled sky instead"));
    }
    world
}

/// The embedded skybox, whatever folder name the scene gives.
fn embedded_skybox(name: &str) -> Result<Skybox, SkyboxError> {
    match bundled::SKYBOX {
        Some(faces) => Skybox::from_rgb8(faces),
        None => Err(SkyboxError::MissingFolder(PathBuf::from(name))),
    }
}

/// Progress of reading a large mesh on stderr: a line updated in place on
/// a terminal, and the size and time once read.
struct MeshProgress<'a> {
    path: &'a Path,
    terminal: bool,
    shown: bool,
}

impl<'a> MeshProgress<'a> {
    fn new(path: &'a Path) -> Self {
        Self {
            path,
            terminal: std::io::stderr().is_terminal(),
            shown: false,
        }
    }

    fn show(&mut self, p: LoadProgress) {
        let percent = p.bytes_read as f64 * 100.0 / p.total_bytes.max(1) as f64;
        let mib = |b: u64| b as f64 / f64::from(1 << 20);
        let line = format!(
            "reading {}: {percent:.0}% ({:.0} of {:.0} MiB)",
            self.path.display(),
            mib(p.bytes_read),
            mib(p.total_bytes)
        );
        if self.terminal {
            eprint!("\r{line}");
        } else if !self.shown {
            eprintln!("{line}");
        }
        self.shown = true;
    }

    /// Says how large the mesh was and how long it took, when progress
    /// was shown at all.
    fn finish(&self, world: &World, took: Duration) {
        if !self.shown {
            return;
        }
        if self.terminal {
            eprint!("\r");
        }
        eprintln!(
            "read {}: {} triangles in {:.2} s",
            self.path.display(),
            world.counts.triangles,
            took.as_secs_f64()
        );
    }
}

/// Whether `path` names a lesson file: TOML, as the window's Open and
/// drop tell a lesson from a scene, and the headless commands refuse one.
pub(crate) fn is_lesson_file(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `source` as the window reads it: no edits, no progress.
    fn read(source: SceneSource) -> Result<Loaded> {
        Loaded::read(source, &[], &mut |_| {})
    }

    /// The repository's `scenes/` folder.
    fn scenes_dir() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
    }

    /// A scene written in memory (a lesson's step on the web page) reads
    /// as its text says, under its name, and its mistakes name it.
    #[test]
    fn a_written_scene_reads_from_its_text_under_its_name() {
        let written = |text: &str| SceneSource::Written {
            name: "shadows.p3f".into(),
            text: text.into(),
        };
        let scene = "v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 resolution 40 30\n\
                     l 0 5 5\nf 1 0 0 1 0 0 0 0 1 0 1\ns 0 0 0 1\ns 2 0 0 1\n";
        let loaded = read(written(scene)).unwrap();
        assert_eq!(loaded.source.label(), "shadows.p3f");
        assert_eq!(loaded.scene.objects.len(), 2);
        assert_eq!(
            (loaded.scene.view.width, loaded.scene.view.height),
            (40, 30)
        );
        let broken = format!("{scene}s 0 0\n");
        let error = format!("{:#}", read(written(&broken)).err().unwrap());
        assert!(error.contains("shadows.p3f:6"), "{error}");
    }

    /// The window opens the default scene from the binary, where no
    /// `assets/` folder need exist next to it: its `env ../assets/skybox`
    /// must get the embedded sky, the same one the file on disk finds.
    #[test]
    fn the_bundled_default_scene_has_the_same_sky_as_its_file() {
        let bundled = SceneSource::Bundled(bundled::DEFAULT_SCENE.into());
        let Loaded { scene, world, .. } = read(bundled).unwrap();
        assert!(scene.env.is_some(), "the default scene should use a skybox");
        assert!(world.warnings.is_empty(), "{:?}", world.warnings);
        assert!(world.skybox.is_some());

        let file = scenes_dir().join(format!("{}.p3f", bundled::DEFAULT_SCENE));
        let from_file = read(SceneSource::File(file)).unwrap().world;
        assert!(from_file.warnings.is_empty(), "{:?}", from_file.warnings);
        assert_eq!(world.skybox, from_file.skybox);
    }

    /// `env` naming a folder that is not there: the bundled sky, not the
    /// flat background, and a warning that says so.
    #[test]
    fn a_missing_sky_folder_falls_back_to_the_bundled_sky() {
        let dir = tracer::scratch::Scratch::new("load-sky");
        let path = dir.join("scene.p3f");
        std::fs::write(&path, "env nowhere\nv from 0 0 5 at 0 0 0\ns 0 0 0 1\n").unwrap();
        let world = read(SceneSource::File(path)).unwrap().world;
        let bundled = embedded_skybox("sky").unwrap();
        assert_eq!(world.skybox, Some(Arc::new(bundled)));
        let warnings = world.warnings.join("; ");
        assert!(warnings.contains("nowhere"), "{warnings}");
        assert!(
            warnings.contains("using the bundled sky instead"),
            "{warnings}"
        );
    }

    /// The fallback sky stands upright on the scene camera's `up`: above
    /// the horizon, in every direction around, the bundled sky's blue; below
    /// it, its ground. For a z-up scene (the course's) and a y-up one.
    #[test]
    fn the_fallback_sky_stands_upright_for_the_camera() {
        let dir = tracer::scratch::Scratch::new("load-sky-up");
        let bundled = embedded_skybox("sky").unwrap();
        for (name, view, up) in [
            (
                "z-up",
                "v from 2.1 1.3 1.7 at 0 0 0 up 0 0 1",
                glam::Vec3::Z,
            ),
            ("y-up", "v from 0 1 5 at 0 0 0 up 0 1 0", glam::Vec3::Y),
        ] {
            let path = dir.join(format!("{name}.p3f"));
            std::fs::write(&path, format!("env skybox\n{view}\ns 0 0 0 1\n")).unwrap();
            let world = read(SceneSource::File(path)).unwrap().world;
            let up = glam::Vec3A::from(up);
            assert_eq!(
                world.background(up),
                bundled.sample(glam::Vec3A::Y),
                "{name}"
            );
            let (side, other) = up.any_orthonormal_pair();
            for k in 0..8 {
                let around = glam::Vec2::from_angle(k as f32 * std::f32::consts::FRAC_PI_4);
                let level = side * around.x + other * around.y;
                let sky = world.background(level + up * 0.6);
                let ground = world.background(level - up * 0.6);
                assert!(sky.z > sky.x + 0.2, "{name}: above the horizon {sky}");
                assert!(ground.z < ground.x, "{name}: below the horizon {ground}");
            }
        }
    }

    /// A bare mesh opens as a framed scene: camera, lights, ground, mesh.
    #[test]
    fn a_bare_obj_opens_framed() {
        let dir = tracer::scratch::Scratch::new("load-obj");
        let path = dir.join("tri.obj");
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        let source = SceneSource::File(path);
        assert!(source.is_bare_mesh());
        let Loaded { scene, world, .. } = read(source).unwrap();
        assert_eq!(scene.lights.len(), 2);
        assert_eq!(world.counts.triangles, 1);
        assert!(world.warnings.is_empty(), "{:?}", world.warnings);
    }

    /// Every scene in the picker opens without a warning (no missing sky,
    /// no degenerate primitive).
    #[test]
    fn every_bundled_scene_loads_without_warnings() {
        assert!(!bundled::SCENES.is_empty());
        for scene in bundled::SCENES {
            let world = read(SceneSource::Bundled(scene.name.into()))
                .unwrap_or_else(|e| panic!("{}: {e:#}", scene.name))
                .world;
            assert!(
                world.warnings.is_empty(),
                "{}: {:?}",
                scene.name,
                world.warnings
            );
        }
    }
}
