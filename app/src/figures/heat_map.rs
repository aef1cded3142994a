//! Views as images to save: the heat map of a view with a legend bar that
//! carries its numbers (0 on the left, the top of the scale on the right),
//! and two sides' views composed. Shared by `render --view` and `compare
//! --view`; the view's numbers in words are [`crate::reports::view_summary`].

use anyhow::{Result, anyhow};
use image::{Rgb, RgbImage};
use tracer::render::{View, ViewFilm, ViewHeatmap};

use crate::measure::value_difference::{ValueDifference, ValueStats, diverging_colour};

/// Background of the legend strip.
const BACKGROUND: Rgb<u8> = Rgb([32, 32, 32]);
const INK: Rgb<u8> = Rgb([230, 230, 230]);
/// Gap between the image, the bar and the numbers, in pixels.
const GAP: u32 = 4;
/// Size of a font pixel.
const DOT: u32 = 2;

/// A view as an RGB image: the heat map of a scalar view or the colours of
/// normals and objects. `None` for the shaded view.
pub(crate) fn view_image(film: &ViewFilm, view: View, heat: &ViewHeatmap) -> Option<RgbImage> {
    let rgba = film.to_rgba8(view, heat)?;
    tracer::render::rgba_to_rgb_image(film.width(), film.height(), &rgba)
}

/// The view of two sides on one shared scale, and the signed difference
/// of their values on its own: A | B | A - B (red where A is larger, blue
/// where B is, as in the window), each scale's legend with its numbers
/// under it; with the difference's statistics. Colour views (normals,
/// objects) get the largest channel difference instead, without numbers.
pub(crate) fn compose_sides(
    a: &ViewFilm,
    b: &ViewFilm,
    view: View,
    heat: &ViewHeatmap,
) -> Result<(RgbImage, Option<ValueStats>)> {
    let size = |f: &ViewFilm| (f.width(), f.height());
    if size(a) != size(b) {
        return Err(anyhow!("the two sides differ in size"));
    }
    let missing = || anyhow!("the view {} has no image", view.name());
    let (ia, ib) = (
        view_image(a, view, heat).ok_or_else(missing)?,
        view_image(b, view, heat).ok_or_else(missing)?,
    );
    let (w, h) = ia.dimensions();
    let mut pair = RgbImage::from_pixel(2 * w + GAP, h, BACKGROUND);
    image::imageops::replace(&mut pair, &ia, 0, 0);
    image::imageops::replace(&mut pair, &ib, i64::from(w + GAP), 0);
    let (pair, difference, stats) = if view.is_scalar() {
        let difference = ValueDifference::of(&a.values(view), &b.values(view))
            .ok_or_else(|| anyhow!("the two sides differ in size"))?;
        let rgba = difference.rgba8();
        let image = tracer::render::rgba_to_rgb_image(w, h, &rgba).ok_or_else(missing)?;
        let top = format_number(difference.scale);
        let signed = legend_under(&image, diverging_legend, &format!("-{top}"), &top);
        (with_legend(&pair, heat), signed, Some(difference.stats))
    } else {
        let diff = tracer::metrics::diff_heatmap(&ia, &ib, 8.0)?;
        (pair, diff, None)
    };
    let mut out = RgbImage::from_pixel(3 * w + 2 * GAP, pair.height(), BACKGROUND);
    image::imageops::replace(&mut out, &pair, 0, 0);
    image::imageops::replace(&mut out, &difference, i64::from(2 * (w + GAP)), 0);
    Ok((out, stats))
}

/// The diverging palette over 0..=1 (-scale..+scale).
fn diverging_legend(t: f32) -> Rgb<u8> {
    Rgb(diverging_colour(2.0 * t - 1.0))
}

/// `image` with a legend strip under it: the palette from 0 to the scale's
/// top, with both numbers written at its ends.
pub(crate) fn with_legend(image: &RgbImage, heat: &ViewHeatmap) -> RgbImage {
    let top = format_number(heat.top);
    let top = if heat.log { format!("{top} log") } else { top };
    legend_under(image, |t| tracer::render::HEAT_PALETTE.colour(t), "0", &top)
}

/// `image` with a strip of `palette` (over 0..=1) under it and the labels
/// `left` and `right` at its ends.
fn legend_under(
    image: &RgbImage,
    palette: impl Fn(f32) -> Rgb<u8>,
    left: &str,
    right: &str,
) -> RgbImage {
    let (w, h) = image.dimensions();
    let bar = (h / 16).clamp(6, 20);
    let text = 5 * DOT;
    let mut out = RgbImage::from_pixel(w, h + GAP + bar + GAP + text + GAP, BACKGROUND);
    image::imageops::replace(&mut out, image, 0, 0);
    for x in 0..w {
        let t = x as f32 / (w.max(2) - 1) as f32;
        let colour = palette(t);
        for y in h + GAP..h + GAP + bar {
            out.put_pixel(x, y, colour);
        }
    }
    let y = h + GAP + bar + GAP;
    draw_text(&mut out, left, 0, y);
    draw_text(&mut out, right, w.saturating_sub(text_width(right)), y);
    out
}

/// A compact number for a legend: 3 significant digits, k and M suffixes.
pub(crate) fn format_number(v: f32) -> String {
    let (v, suffix) = match v.abs() {
        a if a >= 1e6 => (v / 1e6, "M"),
        a if a >= 1e4 => (v / 1e3, "k"),
        _ => (v, ""),
    };
    let digits = match v.abs() {
        a if a >= 100.0 => 0,
        a if a >= 10.0 => 1,
        a if a >= 1.0 => 2,
        _ => 3,
    };
    let text = format!("{v:.digits$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    };
    format!("{text}{suffix}")
}

fn text_width(text: &str) -> u32 {
    text.chars().count() as u32 * 4 * DOT
}

/// Writes `text` with a 3x5 pixel font at `(x, y)` (top-left); characters
/// without a glyph are blank.
fn draw_text(image: &mut RgbImage, text: &str, x: u32, y: u32) {
    for (i, c) in text.chars().enumerate() {
        let rows = glyph(c);
        for (row, bits) in rows.iter().enumerate() {
            for col in 0..3 {
                if bits & (0b100 >> col) == 0 {
                    continue;
                }
                for dy in 0..DOT {
                    for dx in 0..DOT {
                        let px = x + i as u32 * 4 * DOT + col * DOT + dx;
                        let py = y + row as u32 * DOT + dy;
                        if px < image.width() && py < image.height() {
                            image.put_pixel(px, py, INK);
                        }
                    }
                }
            }
        }
    }
}

/// Rows of a 3x5 glyph, high bit on the left.
fn glyph(c: char) -> [u8; 5] {
    match c {
        '0' => [0b111, 0b101, 0b101, 0b101, 0b111],
        '1' => [0b010, 0b110, 0b010, 0b010, 0b111],
        '2' => [0b111, 0b001, 0b111, 0b100, 0b111],
        '3' => [0b111, 0b001, 0b111, 0b001, 0b111],
        '4' => [0b101, 0b101, 0b111, 0b001, 0b001],
        '5' => [0b111, 0b100, 0b111, 0b001, 0b111],
        '6' => [0b111, 0b100, 0b111, 0b101, 0b111],
        '7' => [0b111, 0b001, 0b010, 0b010, 0b010],
        '8' => [0b111, 0b101, 0b111, 0b101, 0b111],
        '9' => [0b111, 0b101, 0b111, 0b001, 0b111],
        '.' => [0, 0, 0, 0, 0b010],
        '-' => [0, 0, 0b111, 0, 0],
        'k' => [0b100, 0b101, 0b110, 0b101, 0b101],
        'M' => [0b101, 0b111, 0b111, 0b101, 0b101],
        'l' => [0b110, 0b010, 0b010, 0b010, 0b111],
        'o' => [0, 0b111, 0b101, 0b101, 0b111],
        'g' => [0b111, 0b101, 0b111, 0b001, 0b111],
        _ => [0; 5],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        assert_eq!(format_number(0.0), "0");
        assert_eq!(format_number(12.5), "12.5");
        assert_eq!(format_number(123.4), "123");
        assert_eq!(format_number(0.25), "0.25");
        assert_eq!(format_number(45_000.0), "45k");
        assert_eq!(format_number(2_500_000.0), "2.5M");
    }

    #[test]
    fn the_legend_runs_under_the_image_with_its_numbers() {
        let image = RgbImage::from_pixel(64, 32, Rgb([9, 9, 9]));
        let heat = ViewHeatmap {
            top: 40.0,
            log: false,
        };
        let out = with_legend(&image, &heat);
        assert_eq!(out.width(), 64);
        assert!(out.height() > 32 + 6);
        assert_eq!(out.get_pixel(0, 0), &Rgb([9, 9, 9]));
        let bar = 32 + GAP;
        let palette = tracer::render::HEAT_PALETTE;
        assert_eq!(out.get_pixel(0, bar), &palette.colour(0.0));
        assert_eq!(out.get_pixel(63, bar), &palette.colour(1.0));
        // Both numbers are written: ink at the left and at the right end.
        let text_rows = (out.height() - 5 * DOT - GAP)..(out.height() - GAP);
        let inked = |xs: std::ops::Range<u32>| {
            xs.flat_map(|x| text_rows.clone().map(move |y| (x, y)))
                .any(|(x, y)| *out.get_pixel(x, y) == INK)
        };
        assert!(inked(0..8) && inked(48..64));
        assert!(!inked(20..40));
    }
}
