//! The windows over the image: the ray tree of a pinned pixel, the
//! benchmark matrix, the studies, the report's export, the help; and what
//! the measuring windows share ([`background`]).

pub mod background;
pub mod benchmark;
pub mod help;
pub mod ray_tree;
pub mod report;
pub mod studies;

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
pub struct ToolsAndOverlays {
    pub bench: BenchWindow,
    pub studies: StudiesWindow,
    /// Export report...: the lab report measured in the background.
    pub report: ReportExport,
    /// The pinned pixel's ray tree.
    pub inspector: Inspector,
    /// The acceleration structure drawn over the image.
    pub overlay: StructureOverlay,
    /// Adaptive sampling's active pixels tinted over the image.
    pub active: ActiveOverlay,
    /// Which per-pixel view the images show.
    pub views: PixelViews,
    pub help_open: bool,
    /// The scene editor and its selection.
    pub editor: Editor,
}
