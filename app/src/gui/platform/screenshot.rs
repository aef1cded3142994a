//! `--screenshot`: the window photographs itself once the render is done (or
//! after a delay) and closes, so CI can check the real window under Xvfb and
//! the README's picture is made by the project's own tooling.

use std::path::Path;
use std::sync::{Arc, Mutex};

use anyhow::Result;

use tracer::render::Snapshot;

use crate::describe::si;
use crate::image_file::save_png;
use crate::reports::render_stats::sample_progress;

pub(crate) use crate::cli::ScreenshotPlan;

/// What became of the screenshot, for the process's exit status: the line
/// to print, or why it failed.
pub(crate) type ScreenshotOutcome = Arc<Mutex<Option<Result<String, String>>>>;

/// The render a screenshot shows, in a line: what the statistics panel says
/// of it, so a script can compare the window's speed with a headless render.
pub(crate) fn describe(shown: &Snapshot) -> String {
    let s = &shown.stats;
    format!(
        "{} x {}, {}, {} rays in {:.3} s ({} rays/s)",
        s.width,
        s.height,
        sample_progress(s),
        si(s.counters.total_rays() as f64),
        s.render_time.as_secs_f64(),
        si(s.rays_per_second())
    )
}

/// Where the image is on the screenshot, in its pixels (`rect` in points,
/// `pixels_per_point` the display's scale): a test then probes the image
/// where the layout put it, not where it used to be.
pub(crate) fn describe_rect(rect: egui::Rect, pixels_per_point: f32) -> String {
    let r = rect * pixels_per_point;
    format!(
        "drawn at {:.0},{:.0} to {:.0},{:.0}",
        r.min.x, r.min.y, r.max.x, r.max.y
    )
}

/// Writes the window's pixels to `path` as an RGB PNG.
pub(crate) fn save(image: &egui::ColorImage, path: &Path) -> Result<()> {
    let [width, height] = image.size;
    let rgb: Vec<u8> = image
        .pixels
        .iter()
        .flat_map(|c| [c.r(), c.g(), c.b()])
        .collect();
    let rgb = image::RgbImage::from_raw(width as u32, height as u32, rgb)
        .ok_or_else(|| anyhow::anyhow!("the screenshot has the wrong size"))?;
    save_png(&rgb, path)
}
