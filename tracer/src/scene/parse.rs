//! The NFF/P3F parser.

use std::path::Path;

use super::{ParseError, Scene};

/// Bounds that protect against hostile or mistaken input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Largest width or height accepted by `resolution`.
    pub max_resolution: u32,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_resolution: 16384,
        }
    }
}

/// Parses scene text; `file` only labels errors and sets `base_dir`.
pub fn parse_scene(text: &str, file: Option<&Path>, limits: &Limits) -> Result<Scene, ParseError> {
    todo!("{text} {file:?} {limits:?}")
}

/// Reads and parses a scene file.
pub fn parse_scene_file(path: &Path, limits: &Limits) -> Result<Scene, ParseError> {
    todo!("{path:?} {limits:?}")
}
