//! A/B comparison: render one scene with two settings, measure both, and
//! say how the images differ (MSE, PSNR, FLIP and a heat map). B may also
//! be a reference image (another renderer's output, an earlier figure).
//! The command line and the window share it.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use anyhow::{Context, Result};
use image::{Rgb, RgbImage};
use tracer::metrics::{self, Palette};
use tracer::render::{Budget, Encoding, RenderSettings, Sampling};
use tracer::stats::RenderStats;
use tracer::world::World;

use crate::describe::side_labels;
use crate::measure::benchmark::{self, Case, Event, Measurement, RunOptions, Stop, Structures};

/// How the difference panel is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Heatmap {
    /// FLIP's per-pixel perceptual error, 0 to 1, in magma.
    Flip,
    /// The largest channel difference times [`ABSOLUTE_GAIN`], black to
    /// white: shows any difference, even one nobody would notice.
    Absolute,
}

/// Gain of [`Heatmap::Absolute`]: a difference of 32 levels is full red.
pub(crate) const ABSOLUTE_GAIN: f32 = 8.0;

impl Heatmap {
    /// The colour scale, for a legend.
    pub(crate) fn palette(self) -> Palette {
        match self {
            Heatmap::Flip => Palette::Magma,
            Heatmap::Absolute => Palette::Heat,
        }
    }

    /// What the legend's ends mean.
    pub(crate) fn legend(self) -> String {
        match self {
            Heatmap::Flip => "FLIP error, 0 (black) to 1 (pale yellow)".into(),
            Heatmap::Absolute => format!(
                "largest channel difference, 0 (black) to {:.0} levels or more (white)",
                255.0 / ABSOLUTE_GAIN
            ),
        }
    }
}

/// How far apart two images are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metrics {
    /// Mean squared error in 8-bit units.
    pub mse: f64,
    /// Peak signal-to-noise ratio in dB; infinite for identical images.
    pub psnr: f64,
    /// Mean FLIP error, 0 to 1.
    pub flip: f32,
}

/// The metrics of `a` against `b` and the heat map of their difference.
pub(crate) fn measure(a: &RgbImage, b: &RgbImage, heatmap: Heatmap) -> Result<(Metrics, RgbImage)> {
    let mismatch = || "the two sides differ in size";
    let mse = metrics::mse(a, b).with_context(mismatch)?;
    let flip = metrics::flip_map(a, b).with_context(mismatch)?;
    let metrics = Metrics {
        mse,
        psnr: metrics::psnr(a, b).with_context(mismatch)?,
        flip: flip.mean,
    };
    let map = match heatmap {
        Heatmap::Flip => flip.image,
        Heatmap::Absolute => metrics::diff_heatmap(a, b, ABSOLUTE_GAIN).with_context(mismatch)?,
    };
    Ok((metrics, map))
}

/// A finished comparison.
#[derive(Debug, Clone)]
pub struct RenderComparison {
    pub(crate) a: Measurement,
    pub(crate) b: Measurement,
    /// What differs, as each side has it (see [`side_labels`]).
    pub(crate) labels: (String, String),
    pub(crate) metrics: Metrics,
    pub(crate) heatmap: RgbImage,
}

impl RenderComparison {
    /// A's frame time over B's: above 1 when B is faster.
    pub(crate) fn time_ratio(&self) -> f64 {
        self.a.median().as_secs_f64() / self.b.median().as_secs_f64().max(1e-9)
    }
}

/// How both sides of a comparison render.
#[derive(Debug, Clone, Copy, Default)]
pub struct SideOptions {
    /// Worker threads; `None` uses every core.
    pub(crate) threads: Option<usize>,
    /// Measure the per-pixel views in the same frames (each side is still
    /// rendered once).
    pub(crate) views: bool,
    /// B, adaptive, stops at A's samples or A's time.
    pub(crate) b_matches: Option<Match>,
}

/// Adaptive B against A at equal cost: B's budget is what A's finished
/// render took (the command line's `--b-matches`, the window's compare
/// header alike).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Match {
    /// B stops when its samples reach A's total.
    Samples,
    /// B stops when it has rendered as long as A did.
    Time,
}

impl Match {
    /// B's budget from the statistics of A's finished render.
    pub(crate) fn budget(self, a: &RenderStats) -> Budget {
        match self {
            Match::Samples => Budget::Samples(a.samples_taken()),
            Match::Time => Budget::Time(a.render_time),
        }
    }

    /// `settings` (adaptive) stopped at `budget`; an error for uniform
    /// sampling, which has no budget.
    pub(crate) fn apply(settings: &mut RenderSettings, budget: Budget) -> Result<()> {
        match &mut settings.sampling {
            Sampling::Adaptive(a) if settings.antialiasing || settings.depth_of_field => {
                a.budget = Some(budget);
                Ok(())
            }
            _ => anyhow::bail!(
                "matching B to A needs B adaptive: --sampling adaptive with anti-aliasing \
                 or depth of field"
            ),
        }
    }
}

/// Renders `a` over the first world then `b` over the second once each
/// (progress reported as cases 0 and 1) and compares them; the worlds are
/// one, or the scene with each side's edits. B traces the structure built
/// for A when its shapes are A's. `None` when `cancel` stopped it.
pub fn run(
    worlds: [&Arc<World>; 2],
    a: Case,
    b: Case,
    sides: SideOptions,
    heatmap: Heatmap,
    cancel: &AtomicBool,
    on_event: &mut dyn FnMut(Event),
) -> Result<Option<RenderComparison>> {
    let options = RunOptions {
        runs: 1,
        threads: sides.threads,
    };
    let stop = Stop {
        now: cancel,
        after_frame: &AtomicBool::new(false),
    };
    let same_shapes = Arc::ptr_eq(worlds[0], worlds[1]) || worlds[0].shapes == worlds[1].shapes;
    let mut structures = Structures::default();
    let mut measured: Vec<Measurement> = Vec::new();
    for (i, (world, mut case)) in worlds.into_iter().zip([a, b]).enumerate() {
        if i == 1 && !same_shapes {
            structures = Structures::default();
        }
        // B's budget is what A took: A renders first, alone.
        if let (Some(matches), Some(a)) = (sides.b_matches, measured.first()) {
            Match::apply(&mut case.settings, matches.budget(&a.stats))?;
        }
        let cases = [case];
        let outcome = benchmark::run_cases(
            world,
            &cases,
            options,
            &mut structures,
            stop,
            sides.views,
            &mut |event| on_event(event.offset(i)),
        )?;
        if outcome.cancelled {
            return Ok(None);
        }
        measured.extend(outcome.measurements);
    }
    let Ok([a, b]) = <[Measurement; 2]>::try_from(measured) else {
        return Ok(None);
    };
    // After the renders: B's label names the budget A's render set.
    let labels = side_labels(
        &a.case.settings,
        &b.case.settings,
        [&worlds[0].view, &worlds[1].view],
    );
    let (metrics, heatmap) = measure(&a.image, &b.image, heatmap)?;
    Ok(Some(RenderComparison {
        a,
        b,
        labels,
        metrics,
        heatmap,
    }))
}

/// A reference image read for side B, at the size it is compared at.
#[derive(Debug, Clone)]
pub(crate) struct FittedReference {
    pub(crate) image: RgbImage,
    /// The file's own size, when it was resized to fit the render.
    pub(crate) resized_from: Option<(u32, u32)>,
}

/// Reads a PNG, JPEG or OpenEXR image to compare a render with. EXR holds
/// linear floats: they are encoded with `encoding`, as the render is.
pub(crate) fn read_reference(path: &Path, encoding: Encoding) -> Result<RgbImage> {
    let image = image::open(path)
        .with_context(|| format!("cannot read the reference image {}", path.display()))?;
    Ok(match image {
        image::DynamicImage::ImageRgb32F(_) | image::DynamicImage::ImageRgba32F(_) => {
            let linear = image.to_rgb32f();
            RgbImage::from_fn(linear.width(), linear.height(), |x, y| {
                Rgb(linear.get_pixel(x, y).0.map(|v| encoding.encode(v)))
            })
        }
        other => other.to_rgb8(),
    })
}

/// `image` at `size` (the render's): resized when `fit`, else refused with
/// what to do when the sizes differ.
pub(crate) fn fit_reference(
    image: RgbImage,
    size: (u32, u32),
    fit: bool,
) -> Result<FittedReference> {
    let own = image.dimensions();
    if own == size {
        return Ok(FittedReference {
            image,
            resized_from: None,
        });
    }
    if !fit {
        anyhow::bail!(
            "the reference image is {}x{} but the render is {}x{}: render at its size \
             (--width {} --height {}) or resize it with --fit",
            own.0,
            own.1,
            size.0,
            size.1,
            own.0,
            own.1
        );
    }
    let image = image::imageops::resize(
        &image,
        size.0,
        size.1,
        image::imageops::FilterType::Triangle,
    );
    Ok(FittedReference {
        image,
        resized_from: Some(own),
    })
}

/// A render compared with a reference image.
#[derive(Debug, Clone)]
pub(crate) struct ImageComparison {
    pub(crate) a: Measurement,
    pub(crate) reference: FittedReference,
    pub(crate) metrics: Metrics,
    pub(crate) heatmap: RgbImage,
}

/// Renders `a` once and compares it with `reference` (fitted to A's size
/// by [`fit_reference`] first, so a mismatch costs no render). `None` when
/// `cancel` stopped it.
pub(crate) fn run_against_image(
    world: &Arc<World>,
    a: Case,
    reference: FittedReference,
    threads: Option<usize>,
    heatmap: Heatmap,
    cancel: &AtomicBool,
    on_event: &mut dyn FnMut(Event),
) -> Result<Option<ImageComparison>> {
    let options = RunOptions { runs: 1, threads };
    let outcome = benchmark::run(world, &[a], options, cancel, on_event)?;
    let Some(a) = outcome
        .measurements
        .into_iter()
        .next()
        .filter(|_| !outcome.cancelled)
    else {
        return Ok(None);
    };
    let (metrics, heatmap) = measure(&a.image, &reference.image, heatmap)?;
    Ok(Some(ImageComparison {
        a,
        reference,
        metrics,
        heatmap,
    }))
}

/// Gap between panels, in pixels.
const GAP: u32 = 4;
const BACKGROUND: Rgb<u8> = Rgb([32, 32, 32]);

/// A | B | heat map side by side on a dark background, with a legend bar of
/// `palette` (0 on the left, 1 on the right) under the heat map. The images
/// must have one size.
pub(crate) fn compose(a: &RgbImage, b: &RgbImage, heat: &RgbImage, palette: Palette) -> RgbImage {
    let (w, h) = a.dimensions();
    let bar = (h / 16).clamp(4, 24);
    let mut out = RgbImage::from_pixel(3 * w + 2 * GAP, h + GAP + bar, BACKGROUND);
    for (i, panel) in [a, b, heat].into_iter().enumerate() {
        image::imageops::replace(&mut out, panel, i64::from(i as u32 * (w + GAP)), 0);
    }
    let left = 2 * (w + GAP);
    for x in 0..w {
        let colour = palette.colour(x as f32 / (w.max(2) - 1) as f32);
        for y in h + GAP..h + GAP + bar {
            out.put_pixel(left + x, y, colour);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_places_the_panels_and_the_legend() {
        let a = RgbImage::from_pixel(10, 8, Rgb([200, 0, 0]));
        let b = RgbImage::from_pixel(10, 8, Rgb([0, 200, 0]));
        let (m, heat) = measure(&a, &b, Heatmap::Absolute).unwrap();
        assert!(m.mse > 0.0 && m.flip > 0.0 && m.psnr.is_finite());
        let out = compose(&a, &b, &heat, Palette::Heat);
        assert_eq!(out.dimensions(), (3 * 10 + 2 * GAP, 8 + GAP + 4));
        assert_eq!(out.get_pixel(0, 0), &Rgb([200, 0, 0]));
        assert_eq!(out.get_pixel(10, 0), &BACKGROUND);
        assert_eq!(out.get_pixel(10 + GAP, 7), &Rgb([0, 200, 0]));
        assert_eq!(out.get_pixel(2 * (10 + GAP), 0), &Rgb([255, 255, 255]));
        // The legend runs from the palette's 0 to its 1.
        let y = 8 + GAP;
        assert_eq!(out.get_pixel(2 * (10 + GAP), y), &Palette::Heat.colour(0.0));
        assert_eq!(
            out.get_pixel(3 * 10 + 2 * GAP - 1, y),
            &Palette::Heat.colour(1.0)
        );
        // Nothing under A and B.
        assert_eq!(out.get_pixel(0, y), &BACKGROUND);
    }

    /// A reference image whose difference from a known image is known:
    /// every channel 10 levels off gives MSE 100 and PSNR 10 log10(255^2/100).
    #[test]
    fn a_reference_image_measures_against_a_known_image() {
        let dir = tracer::scratch::Scratch::new("compare-ref");
        let render = RgbImage::from_pixel(8, 6, Rgb([100, 150, 200]));
        let png = dir.join("ref.png");
        RgbImage::from_pixel(8, 6, Rgb([110, 140, 210]))
            .save(&png)
            .unwrap();
        let reference = read_reference(&png, Encoding::Linear).unwrap();
        let reference = fit_reference(reference, (8, 6), false).unwrap();
        assert_eq!(reference.resized_from, None);
        let (m, _) = measure(&render, &reference.image, Heatmap::Flip).unwrap();
        assert_eq!(m.mse, 100.0);
        assert!((m.psnr - 10.0 * (255.0f64 * 255.0 / 100.0).log10()).abs() < 1e-9);
        assert!(m.flip > 0.0);

        // An EXR reference is encoded as the render is: linear 0.5 is 128.
        let exr = dir.join("ref.exr");
        image::Rgb32FImage::from_pixel(8, 6, Rgb([0.5, 2.0, 0.0]))
            .save(&exr)
            .unwrap();
        let reference = read_reference(&exr, Encoding::Linear).unwrap();
        assert_eq!(reference.get_pixel(3, 3).0, [128, 255, 0]);

        // A size mismatch says what to do, unless asked to fit.
        let error = fit_reference(reference.clone(), (16, 12), false).unwrap_err();
        let text = error.to_string();
        assert!(
            text.contains("8x6 but the render is 16x12") && text.contains("--fit"),
            "{text}"
        );
        let fitted = fit_reference(reference, (16, 12), true).unwrap();
        assert_eq!(fitted.image.dimensions(), (16, 12));
        assert_eq!(fitted.resized_from, Some((8, 6)));
        assert!(read_reference(&dir.join("missing.png"), Encoding::Linear).is_err());
    }

    #[test]
    fn identical_images_measure_zero() {
        let a = RgbImage::from_pixel(6, 6, Rgb([10, 20, 30]));
        let (m, heat) = measure(&a, &a, Heatmap::Flip).unwrap();
        assert_eq!((m.mse, m.flip), (0.0, 0.0));
        assert_eq!(m.psnr, f64::INFINITY);
        assert!(heat.pixels().all(|p| *p == Palette::Magma.colour(0.0)));
        assert!(measure(&a, &RgbImage::new(5, 6), Heatmap::Flip).is_err());
    }
}
