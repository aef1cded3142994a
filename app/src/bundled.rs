//! The scenes, lessons and skybox embedded in the binary (see `build.rs`).

/// A scene file compiled into the binary.
#[derive(Debug, Clone, Copy)]
pub struct BundledScene {
    /// File stem, e.g. `balls_medium`.
    pub name: &'static str,
    /// File name, e.g. `balls_medium.p3f`.
    pub file: &'static str,
    /// The file's first comment line.
    pub description: &'static str,
    pub text: &'static str,
}

/// A lesson file compiled into the binary (see [`crate::lessons`]).
#[derive(Debug, Clone, Copy)]
pub struct BundledLesson {
    /// File stem, e.g. `camera`: the name `workbench lesson check` takes.
    pub name: &'static str,
    pub text: &'static str,
}

include!(concat!(env!("OUT_DIR"), "/bundled.rs"));

/// The scene the window opens when it has none to restore.
pub const DEFAULT_SCENE: &str = "showcase";

/// A bundled scene by name.
pub fn find(name: &str) -> Option<&'static BundledScene> {
    SCENES.iter().find(|s| s.name == name)
}
