//! Loading a scene, from a file or from the scenes embedded in the binary,
//! into a world ready to render, with the context a user needs when it fails.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result};
use serde::{Deserialize, Serialize};
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
}

impl SceneSource {
    /// A short name for titles and lists.
    pub fn label(&self) -> String {
        match self {
            SceneSource::File(path) => path.file_name().map_or_else(
                || path.display().to_string(),
                |n| n.to_string_lossy().into(),
            ),
            SceneSource::Bundled(name) => name.clone(),
        }
    }
}

/// Reads and prepares `source`. Warnings from preparing the world stay in
/// `World::warnings` for the caller to show.
pub fn load_source(source: &SceneSource) -> Result<(Scene, World)> {
    match source {
        SceneSource::File(path) => {
            // The parse error already names the file, line and column.
            let scene = parse_scene_file(path, &Limits::default())?;
            let world = World::build(&scene);
            Ok((scene, world))
        }
        SceneSource::Bundled(name) => {
            let bundled =
                bundled::find(name).with_context(|| format!("no bundled scene called `{name}`"))?;
            let scene = parse_scene(
                bundled.text,
                Some(Path::new(bundled.file)),
                &Limits::default(),
            )?;
            let world = World::build_with_skybox(&scene, embedded_skybox);
            Ok((scene, world))
        }
    }
}

/// The embedded skybox, whatever folder name the scene gives.
fn embedded_skybox(name: &str) -> Result<Skybox, SkyboxError> {
    match bundled::SKYBOX {
        Some(faces) => Skybox::from_encoded(faces),
        None => Err(SkyboxError::MissingFolder(PathBuf::from(name))),
    }
}

/// A parsed scene and the world built from it.
pub struct Loaded {
    pub scene: Scene,
    pub world: Arc<World>,
}

/// Parses a scene file for the headless commands; warnings go to stderr.
pub fn load_scene(path: &Path) -> Result<Loaded> {
    let (scene, world) = load_source(&SceneSource::File(path.to_path_buf()))?;
    for warning in &world.warnings {
        eprintln!("warning: {}: {warning}", path.display());
    }
    Ok(Loaded {
        scene,
        world: Arc::new(world),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The repository's `scenes/` folder.
    fn scenes_dir() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
    }

    /// The window opens the default scene from the binary, where no
    /// `assets/` folder need exist next to it: its `env ../assets/skybox`
    /// must get the embedded sky, the same one the file on disk finds.
    #[test]
    fn the_bundled_default_scene_has_the_same_sky_as_its_file() {
        let bundled = SceneSource::Bundled(bundled::DEFAULT_SCENE.into());
        let (scene, world) = load_source(&bundled).unwrap();
        assert!(scene.env.is_some(), "the default scene should use a skybox");
        assert!(world.warnings.is_empty(), "{:?}", world.warnings);
        assert!(world.skybox.is_some());

        let file = scenes_dir().join(format!("{}.p3f", bundled::DEFAULT_SCENE));
        let (_, from_file) = load_source(&SceneSource::File(file)).unwrap();
        assert!(from_file.warnings.is_empty(), "{:?}", from_file.warnings);
        assert_eq!(world.skybox, from_file.skybox);
    }

    /// Every scene in the picker opens without a warning (no missing sky,
    /// no degenerate primitive).
    #[test]
    fn every_bundled_scene_loads_without_warnings() {
        assert!(!bundled::SCENES.is_empty());
        for scene in bundled::SCENES {
            let (_, world) = load_source(&SceneSource::Bundled(scene.name.into()))
                .unwrap_or_else(|e| panic!("{}: {e:#}", scene.name));
            assert!(
                world.warnings.is_empty(),
                "{}: {:?}",
                scene.name,
                world.warnings
            );
        }
    }
}
