//! Loading a scene file into a world ready to render, with the context a
//! user needs when it fails.

use std::path::Path;
use std::sync::Arc;

use anyhow::Result;
use tracer::scene::{Limits, Scene, parse_scene_file};
use tracer::world::World;

/// A parsed scene and the world built from it.
pub struct Loaded {
    pub scene: Scene,
    pub world: Arc<World>,
}

/// Parses `path` and prepares it for rendering; warnings go to stderr.
pub fn load_scene(path: &Path) -> Result<Loaded> {
    // The parse error already names the file, line and column.
    let scene = parse_scene_file(path, &Limits::default())?;
    let world = World::build(&scene);
    for warning in &world.warnings {
        eprintln!("warning: {}: {warning}", path.display());
    }
    Ok(Loaded {
        scene,
        world: Arc::new(world),
    })
}
