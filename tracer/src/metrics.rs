//! Image comparison: mean squared error, PSNR and a difference heat map on
//! 8-bit RGB images. Used by the golden-image tests and for comparing two
//! renders (A/B) of the same scene.

use image::{Rgb, RgbImage};

/// Why two images cannot be compared.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("images differ in size: {a:?} and {b:?}")]
pub struct SizeMismatch {
    pub a: (u32, u32),
    pub b: (u32, u32),
}

fn same_size(a: &RgbImage, b: &RgbImage) -> Result<(), SizeMismatch> {
    if a.dimensions() == b.dimensions() {
        Ok(())
    } else {
        Err(SizeMismatch {
            a: a.dimensions(),
            b: b.dimensions(),
        })
    }
}

/// Mean squared error over every channel of every pixel, in 8-bit units
/// (0 for identical images, at most 255^2). Empty images have an MSE of 0.
pub fn mse(a: &RgbImage, b: &RgbImage) -> Result<f64, SizeMismatch> {
    same_size(a, b)?;
    let samples = a.as_raw().len();
    if samples == 0 {
        return Ok(0.0);
    }
    let sum: u64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(&x, &y)| {
            let d = u64::from(x.abs_diff(y));
            d * d
        })
        .sum();
    Ok(sum as f64 / samples as f64)
}

/// Peak signal-to-noise ratio in decibels, `10 log10(255^2 / MSE)`:
/// infinite for identical images, about 48 dB for an error of one level
/// everywhere, below 30 dB for visible differences.
pub fn psnr(a: &RgbImage, b: &RgbImage) -> Result<f64, SizeMismatch> {
    let mse = mse(a, b)?;
    if mse == 0.0 {
        return Ok(f64::INFINITY);
    }
    Ok(10.0 * (255.0 * 255.0 / mse).log10())
}

/// A heat map of where two images differ: black where they agree, through
/// red and yellow to white for the largest differences. `gain` scales the
/// per-pixel difference (the largest channel difference) before mapping,
/// so small errors become visible (e.g. 8: a difference of 32 is full red).
pub fn diff_heatmap(a: &RgbImage, b: &RgbImage, gain: f32) -> Result<RgbImage, SizeMismatch> {
    same_size(a, b)?;
    let gain = if gain.is_finite() && gain > 0.0 {
        gain
    } else {
        1.0
    };
    Ok(RgbImage::from_fn(a.width(), a.height(), |x, y| {
        let (p, q) = (a.get_pixel(x, y).0, b.get_pixel(x, y).0);
        let d = (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap_or(0);
        heat((f32::from(d) / 255.0 * gain).min(1.0))
    }))
}

/// Black -> red -> yellow -> white as `t` goes from 0 to 1.
fn heat(t: f32) -> Rgb<u8> {
    let channel = |start: f32| ((t * 3.0 - start).clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    Rgb([channel(0.0), channel(1.0), channel(2.0)])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(w: u32, h: u32, v: u8) -> RgbImage {
        RgbImage::from_pixel(w, h, Rgb([v, v, v]))
    }

    #[test]
    fn identical_images_have_zero_error_and_infinite_psnr() {
        let a = flat(4, 3, 77);
        assert_eq!(mse(&a, &a), Ok(0.0));
        assert_eq!(psnr(&a, &a), Ok(f64::INFINITY));
        let empty = RgbImage::new(0, 0);
        assert_eq!(mse(&empty, &empty), Ok(0.0));
    }

    #[test]
    fn error_of_one_level_everywhere() {
        let (a, b) = (flat(5, 5, 10), flat(5, 5, 11));
        assert_eq!(mse(&a, &b), Ok(1.0));
        let db = psnr(&a, &b).unwrap();
        assert!((db - 48.1308).abs() < 1e-3, "{db}");
    }

    #[test]
    fn one_wrong_channel_counts_a_third_of_a_pixel() {
        let a = flat(2, 1, 0);
        let mut b = a.clone();
        b.put_pixel(0, 0, Rgb([6, 0, 0]));
        // 36 over 6 samples.
        assert_eq!(mse(&a, &b), Ok(6.0));
        assert!(psnr(&a, &b).unwrap() < psnr(&a, &flat(2, 1, 1)).unwrap());
    }

    #[test]
    fn sizes_must_match() {
        let err = mse(&flat(2, 2, 0), &flat(2, 3, 0)).unwrap_err();
        assert_eq!(err.b, (2, 3));
        assert!(psnr(&flat(1, 1, 0), &flat(2, 1, 0)).is_err());
        assert!(diff_heatmap(&flat(1, 1, 0), &flat(2, 1, 0), 1.0).is_err());
    }

    #[test]
    fn heatmap_is_black_where_equal_and_bright_where_different() {
        let a = flat(3, 1, 100);
        let mut b = a.clone();
        b.put_pixel(1, 0, Rgb([100, 110, 100]));
        b.put_pixel(2, 0, Rgb([0, 255, 100]));
        let map = diff_heatmap(&a, &b, 4.0).unwrap();
        assert_eq!(map.get_pixel(0, 0).0, [0, 0, 0]);
        let small = map.get_pixel(1, 0).0;
        assert!(small[0] > 0 && small[2] == 0, "{small:?}");
        assert_eq!(map.get_pixel(2, 0).0, [255, 255, 255]);
        // A bad gain falls back to 1 rather than producing NaN colours.
        let plain = diff_heatmap(&a, &b, f32::NAN).unwrap();
        assert_eq!(plain, diff_heatmap(&a, &b, 1.0).unwrap());
    }
}
