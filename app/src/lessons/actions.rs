//! What a lesson's start, a step's setup or a solution does to the state,
//! each value with its place in the lesson file: read by `format`, applied
//! by `state`, so neither needs the other.

use tracer::render::View;

use crate::cli::SettingsArgs;

/// A value with the place in the lesson file it was read from, so a
/// problem found later (an edit the scene refuses) still names its line.
#[derive(Debug, Clone, PartialEq)]
pub struct Located<T> {
    pub value: T,
    pub line: usize,
    pub column: usize,
}

/// What a lesson's start, a step's setup or a solution does to the state.
#[derive(Debug, Clone, Default)]
pub struct Actions {
    /// Side A's settings, as `workbench render` flags; their `--set` lines
    /// edit A's scene.
    pub settings: Option<Located<SettingsArgs>>,
    /// Scene edits of side A in the `--set` language, in order.
    pub edits: Vec<Located<String>>,
    /// Compare mode on, side B being A with these flags over it (their
    /// `--set` lines edit B's scene).
    pub compare: Option<Located<SettingsArgs>>,
    /// Scene edits of side B alone, in the `--set` language, after
    /// `compare`: B's scene differs from A's, the point of the layout.
    pub compare_edits: Vec<Located<String>>,
    /// The pixel pinned for the ray tree and the observer.
    pub pixel: Option<(u32, u32)>,
    /// The answer typed or picked (solutions only).
    pub answer: Option<String>,
    /// The image view to show (window layout).
    pub view: Option<View>,
    /// The observer view on or off (window layout).
    pub observer: Option<bool>,
}
