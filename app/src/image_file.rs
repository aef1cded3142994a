//! Writing files so that a crash or a full disk never leaves a truncated
//! file behind: write a temporary file beside the target, then rename.
//! PNG for what is shown; OpenEXR for the linear film, for HDR tools.

use std::io::{BufWriter, Write};
use std::path::Path;

use anyhow::{Context, Result};

/// Writes `image` as PNG to `path` atomically.
pub(crate) fn save_png(image: &image::RgbImage, path: &Path) -> Result<()> {
    write_atomically(path, |file| {
        image.write_to(file, image::ImageFormat::Png)?;
        Ok(())
    })
    .with_context(|| format!("cannot write image {}", path.display()))
}

/// Writes linear float `image` as OpenEXR (32-bit float channels) to
/// `path` atomically: values above 1 and below the 8-bit step survive.
pub(crate) fn save_exr(image: &image::Rgb32FImage, path: &Path) -> Result<()> {
    write_atomically(path, |file| {
        image.write_to(file, image::ImageFormat::OpenExr)?;
        Ok(())
    })
    .with_context(|| format!("cannot write image {}", path.display()))
}

/// Whether `path` names an OpenEXR file (by its extension, any case).
pub(crate) fn is_exr(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// Runs `write` on a temporary file beside `path`, syncs it and renames
/// it over `path`; the temporary file is removed if anything fails. Every
/// file the workbench writes (images, the lab report) goes through it.
pub(crate) fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<std::fs::File>) -> Result<()>,
) -> Result<()> {
    let file_name = path
        .file_name()
        .with_context(|| format!("{} is not a file path", path.display()))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(file_name);
    tmp_name.push(".tmp");
    let tmp = path.with_file_name(tmp_name);
    let attempt = || -> Result<()> {
        let mut file = BufWriter::new(std::fs::File::create(&tmp)?);
        write(&mut file)?;
        file.flush()?;
        let file = file.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)?;
        Ok(())
    };
    attempt().inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The film's float values, HDR ones included, come back exactly.
    #[test]
    fn exr_round_trips_linear_values() {
        let dir = tracer::scratch::Scratch::new("output-exr");
        let path = dir.join("film.EXR");
        assert!(is_exr(&path) && !is_exr(&dir.join("film.png")));
        let values = [[0.0, 0.5, 1.0], [4.25, 0.001, 1e-6], [1234.5, 0.25, 2.0]];
        let image =
            image::Rgb32FImage::from_fn(3, 2, |x, y| image::Rgb(values[((x + y) % 3) as usize]));
        save_exr(&image, &path).unwrap();
        let back = image::open(&path).unwrap().to_rgb32f();
        assert_eq!(back, image);
    }
}
