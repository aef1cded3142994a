//! The windows over the image: the ray tree of a pinned pixel, the
//! benchmark matrix, the studies, the report's export, the help; and what
//! the measuring windows share ([`background`]).

pub(crate) mod background;
pub(crate) mod benchmark;
pub(crate) mod help;
pub(crate) mod ray_tree;
pub(crate) mod report;
pub(crate) mod studies;

use benchmark::BenchWindow;
use ray_tree::Inspector;
use report::ReportExport;
use studies::StudiesWindow;

use super::editor::Editor;
use super::image::active_overlay::ActiveOverlay;
use super::image::pixel_views::PixelViews;
use super::image::structure_overlay::StructureOverlay;

/// The tools a user opens beside the render, and what they draw over it.
#[derive(Default)]
pub(crate) struct ToolsAndOverlays {
    pub(crate) bench: BenchWindow,
    pub(crate) studies: StudiesWindow,
    /// Export report...: the lab report measured in the background.
    pub(crate) report: ReportExport,
    /// The pinned pixel's ray tree.
    pub(crate) inspector: Inspector,
    /// The acceleration structure drawn over the image.
    pub(crate) overlay: StructureOverlay,
    /// Adaptive sampling's active pixels tinted over the image.
    pub(crate) active: ActiveOverlay,
    /// Which per-pixel view the images show.
    pub(crate) views: PixelViews,
    pub(crate) help_open: bool,
    /// The scene editor and its selection.
    pub(crate) editor: Editor,
}
