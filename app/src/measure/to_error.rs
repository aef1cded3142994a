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
pub(crate) struct ToErrorPlan {
    /// The settings both sides share (size, shadows, lens, structure...);
    /// their N is the uniform sampling whose error is the target, and
    /// their adaptive sampling (if any) gives the minimum and maximum.
    pub(crate) base: RenderSettings,
    /// N of the uniform reference.
    pub(crate) reference_samples: u32,
    /// The MSE to reach (8-bit units); `None`: uniform N x N's, with its
    /// FLIP as well.
    pub(crate) target_mse: Option<f64>,
    /// Adaptive sampling's threshold, if fixed; `None` searches the largest
    /// that reaches the target.
    pub(crate) noise_threshold: Option<f32>,
    /// Timed frames of each side, alternated.
    pub(crate) runs: usize,
    pub(crate) threads: Option<usize>,
    pub(crate) encoding: Encoding,
}

/// One way of sampling, measured.
#[derive(Debug, Clone)]
pub(crate) struct MeasuredSampling {
    pub(crate) settings: RenderSettings,
    /// Its image against the reference.
    pub(crate) metrics: Metrics,
    /// Samples per pixel, on average and at most.
    pub(crate) spp_mean: f64,
    pub(crate) spp_max: u32,
    /// Render time of each timed frame (structure build excluded).
    pub(crate) times: Vec<Duration>,
}

impl MeasuredSampling {
    pub(crate) fn median(&self) -> Duration {
        median(&self.times)
    }
}

/// A render tried while looking for the cheapest setting that reaches the
/// target.
#[derive(Debug, Clone)]
pub(crate) struct Attempt {
    /// "uniform N = 3", "adaptive T = 0.02".
    pub(crate) label: String,
    pub(crate) metrics: Metrics,
    pub(crate) spp_mean: f64,
    pub(crate) time: Duration,
    pub(crate) reached: bool,
}

/// What [`measure`] found.
#[derive(Debug, Clone)]
pub(crate) struct ToError {
    pub(crate) reference_samples: u32,
    pub(crate) reference_time: Duration,
    pub(crate) target_mse: f64,
    /// The FLIP to reach too, when the target is uniform N x N's error.
    pub(crate) target_flip: Option<f32>,
    /// The cheapest uniform N that reaches the target.
    pub(crate) uniform: MeasuredSampling,
    /// The largest threshold that reaches it; `None` if none down to
    /// [`SMALLEST_THRESHOLD`] does.
    pub(crate) adaptive: Option<MeasuredSampling>,
    /// Every render tried, in order.
    pub(crate) attempts: Vec<Attempt>,
}

impl ToError {
    /// Adaptive's median time over uniform's.
    pub(crate) fn time_ratio(&self) -> Option<f64> {
        let adaptive = self.adaptive.as_ref()?;
        Some(adaptive.median().as_secs_f64() / self.uniform.median().as_secs_f64().max(1e-9))
    }
}

/// The threshold the search starts from: halved until the target is met,
/// or doubled while it is.
pub(crate) const FIRST_THRESHOLD: f32 = 0.08;
/// The search gives up below this threshold.
pub(crate) const SMALLEST_THRESHOLD: f32 = 1e-4;
/// The search stops doubling at this threshold: an error of the whole
/// display range, past which no pixel refines beyond the minimum.
pub(crate) const LARGEST_THRESHOLD: f32 = 1.0;
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
pub(crate) fn measure(
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
pub(crate) fn default_reference_samples(n: u32) -> u32 {
    (4 * n).min(MAX_SAMPLES)
}

#[cfg(test)]
mod tests {
    use tracer::scene::{Limits, parse_scene};

    use super::*;

    /// Two spheres on a floor at 32 x 24: the edges alias, so fewer
    /// samples or a larger threshold leave a larger error.
    const SCENE: &str = "\
v from 0 -6 2 at 0 0 0.6 up 0 0 1 angle 40 hither 0.01 resolution 32 24
l 3 -3 6 1 1 1
f 0.6 0.6 0.6 1 1 1 1 0 10 0 1
box -5 -5 -0.2 5 5 0
f 0.9 0.1 0.1 0.8 1 1 1 0.3 40 0 1
s -0.6 0 0.8 0.8
s 0.9 1.6 0.5 0.5
";

    /// Renders a search may need: the uniform Ns below the reference, ten
    /// halvings from 0.08 down to 1e-4, four doublings up to 1, four
    /// narrowings.
    const MOST_ATTEMPTS: usize = 5 + 10 + 4 + 4;

    fn plan(samples: u32, target_mse: Option<f64>) -> (Arc<World>, ToErrorPlan) {
        let scene = parse_scene(SCENE, None, &Limits::default()).unwrap();
        let plan = ToErrorPlan {
            base: RenderSettings {
                samples,
                ..RenderSettings::from_scene(&scene)
            },
            reference_samples: 6,
            target_mse,
            noise_threshold: None,
            runs: 1,
            threads: Some(1),
            encoding: Encoding::default(),
        };
        (Arc::new(World::build(&scene)), plan)
    }

    /// `measure`, with the renders it tried as `on_attempt` heard them; a
    /// search that goes on past every render it may need fails here
    /// rather than rendering for ever.
    fn run(world: &Arc<World>, plan: &ToErrorPlan) -> (ToError, Vec<Attempt>) {
        let mut heard = Vec::new();
        let found = measure(world, plan, &mut |a| {
            assert!(heard.len() < MOST_ATTEMPTS, "endless search: {heard:?}");
            heard.push(a.clone());
        })
        .unwrap();
        (found, heard)
    }

    /// The thresholds tried, in order, with whether each reached the target.
    fn thresholds(attempts: &[Attempt]) -> Vec<(f32, bool)> {
        let tried: Vec<_> = attempts
            .iter()
            .filter_map(|a| {
                let t = a.label.strip_prefix("adaptive T = ")?;
                Some((t.parse().unwrap(), a.reached))
            })
            .collect();
        let uniform = attempts
            .iter()
            .filter(|a| a.label.starts_with("uniform N = "))
            .count();
        assert_eq!(tried.len() + uniform, attempts.len(), "{attempts:?}");
        tried
    }

    /// Whether `m` reaches the target `found` names, worked out apart.
    fn reaches(found: &ToError, m: &Metrics) -> bool {
        m.mse <= found.target_mse && found.target_flip.is_none_or(|f| m.flip <= f)
    }

    /// The last four thresholds each bisect, on a log scale, the bracket
    /// between the largest that reached the target and the smallest above
    /// it that missed, as the tries before them left it (labels keep five
    /// decimals).
    fn assert_narrowed(tried: &[(f32, bool)]) {
        let (search, narrowing) = tried.split_at(tried.len() - NARROWING_STEPS);
        let mut low = search
            .iter()
            .filter(|t| t.1)
            .map(|t| t.0)
            .fold(0.0, f32::max);
        let mut high = search
            .iter()
            .filter(|t| !t.1 && t.0 > low)
            .map(|t| t.0)
            .fold(f32::INFINITY, f32::min);
        assert!(low > 0.0 && high.is_finite(), "{tried:?}");
        for &(t, reached) in narrowing {
            assert!(
                (t - (low * high).sqrt()).abs() < 2e-5,
                "{t} in {low}..{high}: {tried:?}"
            );
            if reached {
                low = t;
            } else {
                high = t;
            }
        }
    }

    #[test]
    fn a_target_the_first_threshold_misses_is_searched_by_halving() {
        // Uniform 3 x 3's error: adaptive 0.08 is coarser than that.
        let (world, plan) = plan(3, None);
        let (found, heard) = run(&world, &plan);
        assert_eq!(found.attempts.len(), heard.len());
        assert_eq!(heard[0].label, "uniform N = 3");
        assert_eq!(found.uniform.settings.samples, 3);
        assert_eq!(found.target_mse, heard[0].metrics.mse);
        assert_eq!(found.target_flip, Some(heard[0].metrics.flip));
        for a in &heard[1..] {
            assert_eq!(a.reached, reaches(&found, &a.metrics), "{a:?}");
        }
        let tried = thresholds(&heard);
        // Halved from the first threshold until one reaches it, never
        // doubled.
        let first_hit = tried.iter().position(|t| t.1).unwrap();
        assert!(first_hit >= 1, "{tried:?}");
        for (i, &(t, reached)) in tried[..=first_hit].iter().enumerate() {
            let halved = FIRST_THRESHOLD / 2f32.powi(i as i32);
            assert!((t - halved).abs() < 6e-6, "{tried:?}");
            assert_eq!(reached, i == first_hit, "{tried:?}");
        }
        assert_eq!(tried.len(), first_hit + 1 + NARROWING_STEPS, "{tried:?}");
        assert_narrowed(&tried);
        // The one found is the largest tried that reached the target.
        let adaptive = found.adaptive.as_ref().unwrap();
        let best = tried
            .iter()
            .filter(|t| t.1)
            .map(|t| t.0)
            .fold(0.0, f32::max);
        let threshold = adaptive.settings.adaptive().unwrap().noise_threshold;
        assert!((threshold - best).abs() < 1e-5, "{threshold} {tried:?}");
        assert!(reaches(&found, &adaptive.metrics));
    }

    #[test]
    fn a_target_the_first_threshold_meets_is_searched_by_doubling() {
        // An MSE between adaptive 0.08's and 0.16's (N = 4: at least 4
        // samples a pixel, at most 64): 0.08 reaches it, 0.16 does not.
        let (world, mut plan) = plan(4, Some(1e9));
        let mut mse_at = |t| {
            plan.noise_threshold = Some(t);
            run(&world, &plan).0.adaptive.unwrap().metrics.mse
        };
        let (fine, coarse) = (mse_at(0.08), mse_at(0.16));
        assert!(fine < coarse, "{fine} {coarse}");
        plan.noise_threshold = None;
        plan.target_mse = Some((fine + coarse) / 2.0);
        let (found, heard) = run(&world, &plan);
        assert_eq!(found.target_flip, None);
        for a in &heard {
            assert_eq!(a.reached, reaches(&found, &a.metrics), "{a:?}");
        }
        let tried = thresholds(&heard);
        let first_miss = tried.iter().position(|t| !t.1).unwrap();
        assert!(first_miss >= 1, "{tried:?}");
        for (i, &(t, _)) in tried[..=first_miss].iter().enumerate() {
            let doubled = (FIRST_THRESHOLD * 2f32.powi(i as i32)).min(LARGEST_THRESHOLD);
            assert_eq!(t, doubled, "{tried:?}");
        }
        assert_eq!(tried.len(), first_miss + 1 + NARROWING_STEPS, "{tried:?}");
        assert_narrowed(&tried);
    }

    #[test]
    fn an_mse_target_takes_the_smallest_uniform_n_that_reaches_it() {
        // Uniform 3 x 3's MSE: N = 1 and 2 miss it, N = 3 reaches it.
        let (world, plan3) = plan(3, None);
        let (three, _) = run(&world, &plan3);
        let (world, plan) = plan(3, Some(three.target_mse));
        let (found, heard) = run(&world, &plan);
        let uniform: Vec<_> = heard
            .iter()
            .filter(|a| a.label.starts_with("uniform N = "))
            .map(|a| (a.label.as_str(), a.reached))
            .collect();
        assert_eq!(
            uniform,
            [
                ("uniform N = 1", false),
                ("uniform N = 2", false),
                ("uniform N = 3", true)
            ]
        );
        assert!(heard[..2].iter().all(|a| a.metrics.mse > found.target_mse));
        assert_eq!(found.uniform.settings.samples, 3);
        assert_eq!(found.uniform.metrics.mse, three.uniform.metrics.mse);
    }

    #[test]
    fn a_target_any_render_meets_doubles_up_to_the_largest_threshold() {
        let (world, plan) = plan(2, Some(1e9));
        let (found, heard) = run(&world, &plan);
        let tried = thresholds(&heard);
        assert_eq!(
            tried,
            [
                (0.08, true),
                (0.16, true),
                (0.32, true),
                (0.64, true),
                (1.0, true)
            ]
        );
        let adaptive = found.adaptive.unwrap().settings;
        assert_eq!(adaptive.adaptive().unwrap().noise_threshold, 1.0);
    }

    #[test]
    fn the_reference_must_take_more_samples_than_uniform() {
        let (world, mut plan) = plan(3, None);
        plan.reference_samples = 3;
        let error = measure(&world, &plan, &mut |_| {}).unwrap_err();
        assert!(error.to_string().contains("N = 3"), "{error}");
        plan.reference_samples = 4;
        plan.noise_threshold = Some(0.05);
        assert!(measure(&world, &plan, &mut |_| {}).is_ok());
    }

    #[test]
    fn the_time_ratio_is_adaptive_median_over_uniform_median() {
        let (world, mut plan) = plan(2, None);
        plan.noise_threshold = Some(1e-9);
        let (mut found, _) = run(&world, &plan);
        let ms = Duration::from_millis;
        found.uniform.times = vec![ms(9), ms(4), ms(5)];
        assert_eq!(found.uniform.median(), ms(5));
        found.adaptive.as_mut().unwrap().times = vec![ms(2)];
        assert!((found.time_ratio().unwrap() - 0.4).abs() < 1e-12);
        found.adaptive = None;
        assert_eq!(found.time_ratio(), None);
    }

    #[test]
    fn each_side_keeps_the_base_settings_but_its_sampling() {
        let knobs = AdaptiveSampling {
            noise_threshold: 0.5,
            min_spp: 8,
            max_spp: 36,
            budget: None,
        };
        let base = RenderSettings {
            width: 40,
            antialiasing: false,
            samples: 5,
            sampling: Sampling::Adaptive(knobs),
            keep_refining: true,
            ..RenderSettings::default()
        };
        let u = uniform(&base, 3);
        assert!(u.antialiasing && !u.keep_refining);
        assert_eq!((u.width, u.samples, u.sampling), (40, 3, Sampling::Uniform));
        let a = adaptive(&base, 0.02);
        assert!(a.antialiasing && !a.keep_refining);
        assert_eq!((a.width, a.samples), (40, 5));
        let expected = AdaptiveSampling {
            noise_threshold: 0.02,
            ..knobs
        };
        assert_eq!(a.sampling, Sampling::Adaptive(expected));
        // A uniform base: N's minimum and maximum.
        let base = RenderSettings {
            samples: 3,
            sampling: Sampling::Uniform,
            ..base
        };
        let a = adaptive(&base, 0.02);
        assert_eq!(
            a.sampling,
            Sampling::Adaptive(AdaptiveSampling::for_samples(3, 0.02))
        );
    }

    #[test]
    fn the_default_reference_takes_four_times_n_up_to_the_most() {
        assert_eq!(default_reference_samples(3), 12);
        assert_eq!(default_reference_samples(MAX_SAMPLES / 2), MAX_SAMPLES);
    }
}
