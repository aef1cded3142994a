//! Two sides' view values compared pixel by pixel: the signed difference
//! A - B on a diverging palette (red where A is larger, blue where B is),
//! and statistics that mean something for a count or a distance (the two
//! means, their ratio, the mean and largest |A - B|), where image metrics
//! (MSE, PSNR, FLIP) of two heat maps' colours would not.

use tracer::render::NO_VALUE;

/// The pixelwise difference of two sides' values of one view.
#[derive(Debug, Clone, PartialEq)]
pub struct ValueDifference {
    /// A - B per pixel; `None` where either side has no value.
    pub values: Vec<Option<f32>>,
    /// The palette's ends are -scale and +scale: the 99th percentile of
    /// |A - B|, so a few extreme pixels do not leave the rest dark (larger
    /// differences take the end colours).
    pub(crate) scale: f32,
    pub stats: ValueStats,
}

/// Both sides' values summed up over the pixels where both have one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ValueStats {
    /// Pixels where both sides have a value.
    pub pixels: usize,
    pub mean_a: f32,
    pub mean_b: f32,
    /// Mean A over mean B (infinite when B's mean is 0 and A's is not).
    pub(crate) ratio: f32,
    pub(crate) mean_abs_difference: f32,
    pub(crate) max_abs_difference: f32,
}

impl ValueDifference {
    /// The difference of `a` and `b`, values of the same view on images of
    /// the same size; `None` when they differ in size.
    pub(crate) fn of(a: &[Option<f32>], b: &[Option<f32>]) -> Option<ValueDifference> {
        if a.len() != b.len() {
            return None;
        }
        let values: Vec<Option<f32>> = a.iter().zip(b).map(|(a, b)| Some((*a)? - (*b)?)).collect();
        let (mut sum_a, mut sum_b, mut sum_abs, mut max_abs, mut pixels) =
            (0f64, 0f64, 0f64, 0f32, 0usize);
        for ((a, b), d) in a.iter().zip(b).zip(&values) {
            if let (Some(a), Some(b), Some(d)) = (a, b, d) {
                sum_a += f64::from(*a);
                sum_b += f64::from(*b);
                sum_abs += f64::from(d.abs());
                max_abs = max_abs.max(d.abs());
                pixels += 1;
            }
        }
        let mut magnitudes: Vec<f32> = values.iter().flatten().map(|d| d.abs()).collect();
        magnitudes.sort_unstable_by(f32::total_cmp);
        let p99 = magnitudes.len().checked_sub(1).map_or(0.0, |last| {
            magnitudes[(last as f32 * 0.99).round() as usize]
        });
        let n = pixels.max(1) as f64;
        let (mean_a, mean_b) = ((sum_a / n) as f32, (sum_b / n) as f32);
        let ratio = if mean_a == mean_b {
            1.0
        } else {
            mean_a / mean_b
        };
        Some(ValueDifference {
            values,
            scale: if p99 > 0.0 { p99 } else { max_abs },
            stats: ValueStats {
                pixels,
                mean_a,
                mean_b,
                ratio,
                mean_abs_difference: (sum_abs / n) as f32,
                max_abs_difference: max_abs,
            },
        })
    }

    /// The difference as RGBA8 pixels on [`diverging_colour`]; pixels
    /// without a value get the views' [`NO_VALUE`] colour.
    pub(crate) fn rgba8(&self) -> Vec<u8> {
        self.values
            .iter()
            .flat_map(|d| match d {
                Some(d) => {
                    let [r, g, b] = diverging_colour(*d / self.scale.max(f32::MIN_POSITIVE));
                    [r, g, b, 255]
                }
                None => NO_VALUE,
            })
            .collect()
    }
}

/// The colour of `t` in -1..=1 (clamped; NaN is 0): blue at -1, a dark grey
/// at 0 (equal sides recede), red at +1.
pub(crate) fn diverging_colour(t: f32) -> [u8; 3] {
    const ZERO: [f32; 3] = [30.0, 30.0, 34.0];
    const POSITIVE: [f32; 3] = [255.0, 80.0, 50.0];
    const NEGATIVE: [f32; 3] = [60.0, 140.0, 255.0];
    let t = if t.is_nan() { 0.0 } else { t.clamp(-1.0, 1.0) };
    let end = if t >= 0.0 { POSITIVE } else { NEGATIVE };
    let s = t.abs();
    [0, 1, 2].map(|i| (ZERO[i] + (end[i] - ZERO[i]) * s + 0.5) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_difference_is_signed_and_its_statistics_skip_missing_pixels() {
        let a = [Some(4.0), Some(2.0), None, Some(6.0)];
        let b = [Some(1.0), Some(4.0), Some(3.0), Some(6.0)];
        let d = ValueDifference::of(&a, &b).unwrap();
        assert_eq!(d.values, vec![Some(3.0), Some(-2.0), None, Some(0.0)]);
        assert_eq!(d.scale, 3.0);
        let s = d.stats;
        assert_eq!(s.pixels, 3);
        assert_eq!((s.mean_a, s.mean_b), (4.0, 11.0 / 3.0));
        assert!((s.ratio - 12.0 / 11.0).abs() < 1e-6);
        assert_eq!(s.mean_abs_difference, 5.0 / 3.0);
        assert_eq!(s.max_abs_difference, 3.0);
        let rgba = d.rgba8();
        assert_eq!(&rgba[0..4], &[255, 80, 50, 255], "A larger: red");
        assert_eq!(rgba[8..12], NO_VALUE);
        assert_eq!(&rgba[12..16], &[30, 30, 34, 255], "equal: dark");
        let blue = &rgba[4..8];
        assert!(
            blue[2] > blue[0] && blue[2] > 100,
            "B larger: blue {blue:?}"
        );
        assert!(ValueDifference::of(&a, &b[..2]).is_none());
    }

    #[test]
    fn the_scale_is_the_99th_percentile_of_the_magnitudes() {
        // 200 pixels differing by 1, one by 1000.
        let a: Vec<Option<f32>> = (0..201)
            .map(|i| Some(if i == 0 { 1000.0 } else { 1.0 }))
            .collect();
        let b = vec![Some(0.0); 201];
        let d = ValueDifference::of(&a, &b).unwrap();
        assert_eq!(d.scale, 1.0);
        assert_eq!(d.stats.max_abs_difference, 1000.0);
        assert_eq!(
            &d.rgba8()[..4],
            &[255, 80, 50, 255],
            "beyond the scale: the end colour"
        );
    }

    #[test]
    fn identical_sides_have_ratio_one_and_no_difference() {
        let a = [Some(0.0), Some(0.0)];
        let d = ValueDifference::of(&a, &a).unwrap();
        assert_eq!(d.stats.ratio, 1.0);
        assert_eq!(d.scale, 0.0);
        assert_eq!(d.rgba8()[..3], [30, 30, 34]);
    }
}
