//! Image comparison: mean squared error, PSNR, NVIDIA's perceptual FLIP and
//! heat maps of where images differ, on 8-bit RGB images. Used by the
//! golden-image tests and for comparing two renders (A/B) of the same scene.

mod flip;

use image::{Rgb, RgbImage};

/// Why two images cannot be compared.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("images differ in size: {a:?} and {b:?}")]
pub struct SizeMismatch {
    /// The first image's (width, height).
    pub a: (u32, u32),
    /// The second image's (width, height).
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
        Palette::Heat.colour(f32::from(d) / 255.0 * gain)
    }))
}

/// The colour scales of the heat maps, public so a viewer or an exported
/// image can draw the matching legend.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Palette {
    /// Black -> red -> yellow -> white: [`diff_heatmap`].
    Heat,
    /// FLIP's own magma scale (black -> purple -> orange -> pale yellow):
    /// [`flip_map`].
    Magma,
}

impl Palette {
    /// The colour of `t` in 0..=1 (clamped; NaN is 0).
    pub fn colour(self, t: f32) -> Rgb<u8> {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        match self {
            Palette::Heat => {
                let channel = |start: f32| ((t * 3.0 - start).clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
                Rgb([channel(0.0), channel(1.0), channel(2.0)])
            }
            Palette::Magma => {
                let lut = &flip::MAGMA_LUT;
                let i = (t * (lut.len() - 1) as f32 + 0.5) as usize;
                Rgb(lut[i.min(lut.len() - 1)])
            }
        }
    }
}

/// Per-pixel FLIP errors in 0..=1, row-major, by the port of NVIDIA's
/// reference code (the `flip` module). Images are taken as sRGB-encoded,
/// as they are displayed.
fn flip_errors(a: &RgbImage, b: &RgbImage) -> Result<Vec<f32>, SizeMismatch> {
    same_size(a, b)?;
    Ok(flip::error_map(a, b, flip::DEFAULT_PIXELS_PER_DEGREE))
}

/// Mean FLIP error (NVIDIA's perceptual difference, 0 for identical images,
/// up to 1): unlike MSE it weighs what a viewer notices at a normal viewing
/// distance (67 pixels per degree), so sampling noise counts less than a
/// moved edge. Empty images have a FLIP of 0.
pub fn flip(a: &RgbImage, b: &RgbImage) -> Result<f32, SizeMismatch> {
    Ok(mean(&flip_errors(a, b)?))
}

/// FLIP's mean and its error map drawn with [`Palette::Magma`].
#[derive(Debug, Clone, PartialEq)]
pub struct FlipMap {
    /// Mean FLIP error, 0 (identical) to 1.
    pub mean: f32,
    /// Per-pixel error, dark where the images agree.
    pub image: RgbImage,
}

/// [`flip`] with the per-pixel error map, to show where the difference is.
pub fn flip_map(a: &RgbImage, b: &RgbImage) -> Result<FlipMap, SizeMismatch> {
    let errors = flip_errors(a, b)?;
    let width = a.width() as usize;
    let image = RgbImage::from_fn(a.width(), a.height(), |x, y| {
        Palette::Magma.colour(errors[y as usize * width + x as usize])
    });
    Ok(FlipMap {
        mean: mean(&errors),
        image,
    })
}

fn mean(values: &[f32]) -> f32 {
    if values.is_empty() {
        return 0.0;
    }
    (values.iter().map(|&v| f64::from(v)).sum::<f64>() / values.len() as f64) as f32
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
        assert!(flip(&flat(1, 1, 0), &flat(2, 1, 0)).is_err());
        assert!(flip_map(&flat(1, 1, 0), &flat(1, 2, 0)).is_err());
    }

    /// A grey ramp with a darker disc: something with edges for FLIP.
    fn picture(w: u32, h: u32, disc: u8) -> RgbImage {
        RgbImage::from_fn(w, h, |x, y| {
            let (dx, dy) = (x as f32 - w as f32 / 2.0, y as f32 - h as f32 / 2.0);
            let v = if dx * dx + dy * dy < (w * w / 16) as f32 {
                disc
            } else {
                (x * 255 / w.max(1)) as u8
            };
            Rgb([v, v / 2, 255 - v])
        })
    }

    #[test]
    fn flip_is_zero_for_identical_images_and_grows_with_the_difference() {
        let a = picture(32, 24, 40);
        assert_eq!(flip(&a, &a), Ok(0.0));
        let small = flip(&a, &picture(32, 24, 60)).unwrap();
        let large = flip(&a, &picture(32, 24, 250)).unwrap();
        assert!(
            small > 0.0 && small < large && large <= 1.0,
            "{small} {large}"
        );
        let empty = RgbImage::new(0, 0);
        assert_eq!(flip(&empty, &empty), Ok(0.0));
        // Images smaller than FLIP's filters still compare.
        assert!(flip(&flat(1, 1, 0), &flat(1, 1, 255)).unwrap() > 0.0);
        assert!(flip(&flat(1, 5, 0), &flat(1, 5, 9)).unwrap() > 0.0);
    }

    #[test]
    fn flip_map_is_dark_where_equal_and_bright_where_different() {
        let a = picture(32, 32, 40);
        let b = picture(32, 32, 250);
        let map = flip_map(&a, &b).unwrap();
        assert_eq!(map.mean, flip(&a, &b).unwrap());
        assert_eq!(map.image.dimensions(), (32, 32));
        let brightness = |p: &Rgb<u8>| p.0.iter().map(|&c| u32::from(c)).sum::<u32>();
        // The disc changed, the corner did not.
        assert!(brightness(map.image.get_pixel(16, 16)) > brightness(map.image.get_pixel(0, 0)));
        assert_eq!(*map.image.get_pixel(0, 0), Palette::Magma.colour(0.0));
        let same = flip_map(&a, &a).unwrap();
        assert_eq!(same.mean, 0.0);
    }

    #[test]
    fn palettes_run_from_dark_to_bright_and_clamp() {
        for palette in [Palette::Heat, Palette::Magma] {
            let sum = |t: f32| {
                palette
                    .colour(t)
                    .0
                    .iter()
                    .map(|&c| u32::from(c))
                    .sum::<u32>()
            };
            assert!(sum(0.0) < sum(0.5) && sum(0.5) < sum(1.0), "{palette:?}");
            assert_eq!(palette.colour(-3.0), palette.colour(0.0));
            assert_eq!(palette.colour(7.0), palette.colour(1.0));
            assert_eq!(palette.colour(f32::NAN), palette.colour(0.0));
        }
        assert_eq!(Palette::Heat.colour(0.0).0, [0, 0, 0]);
        assert_eq!(Palette::Heat.colour(1.0).0, [255, 255, 255]);
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

    #[test]
    fn magma_takes_the_step_nearest_t_times_255() {
        // 0.5 -> 127.5, rounded up to 128; 0.75 -> 191.25, to 191.
        assert_eq!(Palette::Magma.colour(0.5).0, flip::MAGMA_LUT[128]);
        assert_eq!(Palette::Magma.colour(0.75).0, flip::MAGMA_LUT[191]);
    }

    #[test]
    fn heatmap_maps_the_largest_channel_difference_times_the_gain() {
        let a = flat(2, 1, 100);
        let mut b = a.clone();
        // Differences 10, 3, 0: the largest, 10, times 4 over 255, is
        // 3 * 40 / 255 of the way to white, 0.47 of red: 120.
        b.put_pixel(0, 0, Rgb([110, 97, 100]));
        let map = diff_heatmap(&a, &b, 4.0).unwrap();
        assert_eq!(map.get_pixel(0, 0).0, [120, 0, 0]);
        assert_eq!(map.get_pixel(1, 0).0, [0, 0, 0]);
        // A gain of 0 or below falls back to 1: 3 * 10 / 255 of red, 30.
        for gain in [0.0, -4.0] {
            let map = diff_heatmap(&a, &b, gain).unwrap();
            assert_eq!(map.get_pixel(0, 0).0, [30, 0, 0], "gain {gain}");
        }
    }

    #[test]
    fn flip_map_draws_each_pixels_error_where_it_is() {
        // Not square, so an index off by rows or columns shows.
        let (a, b) = (picture(24, 16, 40), picture(24, 16, 250));
        let errors = flip::error_map(&a, &b, flip::DEFAULT_PIXELS_PER_DEGREE);
        let map = flip_map(&a, &b).unwrap();
        for (i, &e) in errors.iter().enumerate() {
            let (x, y) = ((i % 24) as u32, (i / 24) as u32);
            assert_eq!(
                *map.image.get_pixel(x, y),
                Palette::Magma.colour(e),
                "({x}, {y})"
            );
        }
    }
}
