//! `--screenshot`: the window photographs itself once the render is done (or
//! after a delay) and closes, so CI can check the real window under Xvfb and
//! the README's picture is made by the project's own tooling.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use anyhow::Result;

use crate::output::save_png;

/// When and where to take the screenshot.
#[derive(Debug, Clone)]
pub struct ScreenshotPlan {
    pub path: PathBuf,
    /// Take it this long after the window opened; `None`: once the render
    /// is finished and on screen (or an error is shown).
    pub after: Option<Duration>,
}

/// What became of the screenshot, for the process's exit status.
pub type ScreenshotOutcome = Arc<Mutex<Option<Result<PathBuf, String>>>>;

/// Writes the window's pixels to `path` as an RGB PNG.
pub fn save(image: &egui::ColorImage, path: &Path) -> Result<()> {
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
