//! Time to a given error: a uniform reference with many samples, then the
//! time and samples uniform and adaptive sampling each take to come within
//! a target error of it (MSE and FLIP), so "adaptive reaches the error of
//! uniform 4 x 4 in 40% of its time" is one measurement. Nothing here
//! prints.

use std::sync::Arc;
use std::time::Duration;

use anyhow::{Context, Result, bail};
use image::RgbImage;
use tracer::accel::SceneIndex;
use tracer::render::{AdaptiveSampling, Encoding, MAX_SAMPLES, RenderSettings, Sampling, render};
use tracer::world::World;

use crate::measure::ab::{self, Heatmap, Metrics};
use crate::measure::benchmark::median;

/// What to measure.
#[derive(Debug, Clone)]
pub struct ToErrorPlan {
    /// The settings both sides share (size, shadows, lens, structure...);
    /// their N is the uniform sampling whose error is the target, and
    /// their adaptive sampling (if any) gives the minimum and maximum.
    pub base: RenderSettings,
    /// N of the uniform reference.
    pub reference_samples: u32,
    /// The MSE to reach (8-bit units); `None`: uniform N x N's, with its
    /// FLIP as well.
    pub target_mse: Option<f64>,
    /// Adaptive sampling's threshold, if fixed; `None` searches the largest
    /// that reaches the target.
    pub noise_threshold: Option<f32>,
    /// Timed frames of each side, alternated.
    pub runs: usize,
    pub threads: Option<usize>,
    pub encoding: Encoding,
}

/// One way of sampling, measured.
#[derive(Debug, Clone)]
pub struct MeasuredSampling {
    pub settings: RenderSettings,
    /// Its image against the reference.
    pub metrics: Metrics,
    /// Samples per pixel, on average and at most.
    pub spp_mean: f64,
    pub spp_max: u32,
    /// Render time of each timed frame (structure build excluded).
    pub times: Vec<Duration>,
}

impl MeasuredSampling {
    pub fn median(&self) -> Duration {
        median(&self.times)
    }
}

/// A render tried while looking for the cheapest setting that reaches the
/// target.
#[derive(Debug, Clone)]
pub struct Attempt {
    /// "uniform N = 3", "adaptive T = 0.02".
    pub label: String,
    pub metrics: Metrics,
    pub spp_mean: f64,
    pub time: Duration,
    pub reached: bool,
}

/// What [`measure`] found.
#[derive(Debug, Clone)]
pub struct ToError {
    pub reference_samples: u32,
    pub reference_time: Duration,
    pub target_mse: f64,
    /// The FLIP to reach too, when the target is uniform N x N's error.
    pub target_flip: Option<f32>,
    /// The cheapest uniform N that reaches the target.
    pub uniform: MeasuredSampling,
    /// The largest threshold that reaches it; `None` if none down to
    /// [`SMALLEST_THRESHOLD`] does.
    pub adaptive: Option<MeasuredSampling>,
    /// Every render tried, in order.
    pub attempts: Vec<Attempt>,
}

impl ToError {
    /// Adaptive's median time over uniform's.
    pub fn time_ratio(&self) -> Option<f64> {
        let adaptive = self.adaptive.as_ref()?;
        Some(adaptive.median().as_secs_f64() / self.uniform.median().as_secs_f64().max(1e-9))
    }
}

/// The threshold the search starts from: halved until the target is met,
/// or doubled while it is.
pub const FIRST_THRESHOLD: f32 = 0.08;
/// The search gives up below this threshold.
pub const SMALLEST_THRESHOLD: f32 = 1e-4;
/// The search stops doubling at this threshold: an error of the whole
/// display range, past which no pixel refines beyond the minimum.
pub const LARGEST_THRESHOLD: f32 = 1.0;
/// Bisections of the last halving's bracket (on a log scale): four leave
/// the threshold found within 2^(1/16), 4.4%, of the largest that reaches
/// the target. With two (19%), on balls_medium at 512 x 512, the
/// threshold found left an MSE 7% below uniform's (1.936 against 2.083):
/// adaptive sampling was timed doing more than the comparison asks.
const NARROWING_STEPS: usize = 4;

/// A render of `settings` as the measurement sees it.
struct Rendered {
    image: RgbImage,
    spp_mean: f64,
    spp_max: u32,
    time: Duration,
}

struct Renderer<'a> {
    world: &'a Arc<World>,
    index: Arc<SceneIndex>,
    plan: &'a ToErrorPlan,
}

impl Renderer<'_> {
    fn render(&self, settings: &RenderSettings) -> Result<Rendered> {
        let (film, stats) = render(
            self.world.clone(),
            self.index.clone(),
            settings.clone(),
            self.plan.threads,
        )?;
        let (spp_mean, spp_max) = match &stats.adaptive {
            Some(a) => (a.mean_spp(), a.max_spp),
            None => (f64::from(stats.passes_done), stats.passes_done),
        };
        Ok(Rendered {
            image: film.to_image(self.plan.encoding),
            spp_mean,
            spp_max,
            time: stats.render_time,
        })
    }
}

/// Uniform N x N with `base`'s other settings.
fn uniform(base: &RenderSettings, n: u32) -> RenderSettings {
    RenderSettings {
        antialiasing: true,
        samples: n,
        sampling: Sampling::Uniform,
        keep_refining: false,
        ..base.clone()
    }
}

/// Adaptive sampling at `threshold` with `base`'s minimum and maximum (or
/// those N gives).
fn adaptive(base: &RenderSettings, threshold: f32) -> RenderSettings {
    let knobs = match base.sampling {
        Sampling::Adaptive(a) => a,
        Sampling::Uniform => AdaptiveSampling::for_samples(base.samples, threshold),
    };
    RenderSettings {
        antialiasing: true,
        sampling: Sampling::Adaptive(AdaptiveSampling {
            noise_threshold: threshold,
            ..knobs
        }),
        keep_refining: false,
        ..base.clone()
    }
}

/// Renders the reference, finds the cheapest uniform N and the largest
/// adaptive threshold that reach the target, then times both `runs` times,
/// alternated. `on_attempt` hears of every render tried.
pub fn measure(
    world: &Arc<World>,
    plan: &ToErrorPlan,
    on_attempt: &mut dyn FnMut(&Attempt),
) -> Result<ToError> {
    let n = plan.base.samples;
    if plan.reference_samples <= n {
        bail!(
            "the reference (N = {}) must take more samples than the uniform N = {n}",
            plan.reference_samples
        );
    }
    for settings in [
        uniform(&plan.base, plan.reference_samples),
        adaptive(&plan.base, 0.01),
    ] {
        settings.validate()?;
    }
    let renderer = Renderer {
        world,
        index: Arc::new(SceneIndex::build(
            &world.shapes,
            plan.base.accel,
            plan.base.grid_multiplier,
        )),
        plan,
    };
    let reference = renderer
        .render(&uniform(&plan.base, plan.reference_samples))
        .context("cannot render the reference")?;
    let mut attempts = Vec::new();
    let mut attempt =
        |label: String, settings: &RenderSettings, target: &dyn Fn(&Metrics) -> bool| {
            let rendered = renderer.render(settings)?;
            let (metrics, _) = ab::measure(&rendered.image, &reference.image, Heatmap::Flip)?;
            let tried = Attempt {
                label,
                metrics,
                spp_mean: rendered.spp_mean,
                time: rendered.time,
                reached: target(&metrics),
            };
            on_attempt(&tried);
            attempts.push(tried.clone());
            anyhow::Ok((tried, rendered))
        };

    // The target: uniform N x N's error, or the MSE asked for.
    let (target_mse, target_flip, uniform_n, uniform_first) = match plan.target_mse {
        None => {
            let (tried, rendered) =
                attempt(format!("uniform N = {n}"), &uniform(&plan.base, n), &|_| {
                    true
                })?;
            (
                tried.metrics.mse,
                Some(tried.metrics.flip),
                n,
                Some((tried, rendered)),
            )
        }
        Some(mse) => (mse, None, 0, None),
    };
    let reaches = |m: &Metrics| m.mse <= target_mse && target_flip.is_none_or(|f| m.flip <= f);
    let (uniform_n, uniform_measured) = match uniform_first {
        Some((tried, rendered)) => (uniform_n, (tried.metrics, rendered)),
        None => {
            let mut found = None;
            for n in 1..plan.reference_samples {
                let (tried, rendered) = attempt(
                    format!("uniform N = {n}"),
                    &uniform(&plan.base, n),
                    &reaches,
                )?;
                if tried.reached {
                    found = Some((n, (tried.metrics, rendered)));
                    break;
                }
            }
            found.with_context(|| {
                format!(
                    "no uniform N below the reference's {} reaches MSE {target_mse}",
                    plan.reference_samples
                )
            })?
        }
    };

    // Adaptive: halve the threshold until the target is met (or, when
    // the first one meets it, double it until it does not: a target above
    // the first threshold's error is met at less cost), then narrow the
    // step between the last miss and the last hit.
    let mut try_threshold = |t: f32| {
        attempt(
            format!("adaptive T = {t:.5}"),
            &adaptive(&plan.base, t),
            &reaches,
        )
    };
    let adaptive_found = match plan.noise_threshold {
        Some(t) => {
            let (tried, rendered) = try_threshold(t)?;
            tried.reached.then_some((t, tried.metrics, rendered))
        }
        None => {
            let mut missed = None;
            let mut hit = None;
            let mut t = FIRST_THRESHOLD;
            while t >= SMALLEST_THRESHOLD {
                let (tried, rendered) = try_threshold(t)?;
                if tried.reached {
                    hit = Some((t, tried.metrics, rendered));
                    break;
                }
                missed = Some(t);
                t /= 2.0;
            }
            let mut t = FIRST_THRESHOLD;
            while missed.is_none() && t < LARGEST_THRESHOLD {
                t = (t * 2.0).min(LARGEST_THRESHOLD);
                let (tried, rendered) = try_threshold(t)?;
                if tried.reached {
                    hit = Some((t, tried.metrics, rendered));
                } else {
                    missed = Some(t);
                }
            }
            if let (Some(mut high), Some(_)) = (missed, &hit) {
                for _ in 0..NARROWING_STEPS {
                    let low = hit.as_ref().map_or(high, |h| h.0);
                    let t = (low * high).sqrt();
                    let (tried, rendered) = try_threshold(t)?;
                    if tried.reached {
                        hit = Some((t, tried.metrics, rendered));
                    } else {
                        high = t;
                    }
                }
            }
            hit
        }
    };

    // Timing, alternated so both sides see the same machine.
    let uniform_settings = uniform(&plan.base, uniform_n);
    let adaptive_settings = adaptive_found
        .as_ref()
        .map(|(t, _, _)| adaptive(&plan.base, *t));
    let (mut uniform_times, mut adaptive_times) = (Vec::new(), Vec::new());
    for _ in 0..plan.runs.max(1) {
        uniform_times.push(renderer.render(&uniform_settings)?.time);
        if let Some(settings) = &adaptive_settings {
            adaptive_times.push(renderer.render(settings)?.time);
        }
    }
    let (uniform_metrics, uniform_rendered) = uniform_measured;
    Ok(ToError {
        reference_samples: plan.reference_samples,
        reference_time: reference.time,
        target_mse,
        target_flip,
        uniform: MeasuredSampling {
            settings: uniform_settings,
            metrics: uniform_metrics,
            spp_mean: uniform_rendered.spp_mean,
            spp_max: uniform_rendered.spp_max,
            times: uniform_times,
        },
        adaptive: adaptive_found.zip(adaptive_settings).map(
            |((_, metrics, rendered), settings)| MeasuredSampling {
                settings,
                metrics,
                spp_mean: rendered.spp_mean,
                spp_max: rendered.spp_max,
                times: adaptive_times,
            },
        ),
        attempts,
    })
}

/// The largest N a reference may take.
pub fn default_reference_samples(n: u32) -> u32 {
    (4 * n).min(MAX_SAMPLES)
}
