//! Writing images so that a crash or a full disk never leaves a truncated
//! file behind: write a temporary file beside the target, then rename.

use std::path::Path;

use anyhow::{Context, Result};

/// Writes `image` as PNG to `path` atomically.
pub fn save_png(image: &image::RgbImage, path: &Path) -> Result<()> {
    let file_name = path
        .file_name()
        .with_context(|| format!("{} is not a file path", path.display()))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(file_name);
    tmp_name.push(".tmp");
    let tmp = path.with_file_name(tmp_name);
    let write = || -> Result<()> {
        let mut file = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
        image.write_to(&mut file, image::ImageFormat::Png)?;
        let file = file.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)?;
        Ok(())
    };
    write().map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        e.context(format!("cannot write image {}", path.display()))
    })
}
