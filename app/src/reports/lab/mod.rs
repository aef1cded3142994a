//! The lab report: the course's experiments on one scene, measured with the
//! workbench's runners and written as one self-contained HTML page. The
//! command line (`workbench report`) and the window both call [`measure`]
//! then [`page`]; one module per section writes its part of the page.

mod acceleration;
pub(crate) mod course;
pub(crate) mod html;
pub(crate) mod machine;
mod pixel;
mod run;
mod sampling;
mod statistics;
mod svg;
mod whitted;

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use anyhow::{Context, Result};
use tracer::accel::AccelKind;
use tracer::render::{AdaptiveSampling, Encoding, RenderSettings, Sampling};
use tracer::scene::Scene;
use tracer::world::World;

use crate::describe::millis;
use crate::measure::benchmark::{
    self, Case, Event, Measurement, RunOptions, SamplingColumn, Stop, Structures,
};
use crate::measure::study::{self, Param, Study, StudyEvent, StudyOutcome, Subject, values};
use crate::reports::bench_table::{self, Columns, Format};

pub(crate) use machine::Machine;
pub(crate) use pixel::PixelExplained;

/// What to report on and how to measure it.
#[derive(Clone)]
pub(crate) struct Request {
    /// The scene's name as the user gave it (a path, or the window's label).
    pub(crate) scene_name: String,
    pub(crate) scene: Arc<Scene>,
    pub(crate) world: Arc<World>,
    /// The settings every experiment starts from: the scene's, with the
    /// user's changes; N is the matrix's (the course's 4 unless chosen).
    pub(crate) base: RenderSettings,
    /// The `--set` edits applied to the scene, in words.
    pub(crate) edits: Vec<String>,
    /// Frames per timed configuration.
    pub(crate) runs: usize,
    pub(crate) threads: Option<usize>,
    pub(crate) encoding: Encoding,
    /// The pixel to explain; `None` lets the report choose one.
    pub(crate) pixel: Option<(u32, u32)>,
    /// Lower resolution and fewer runs (see [`QUICK_SIDE`], [`QUICK_RUNS`]).
    pub(crate) quick: bool,
}

/// The longer side of a quick report's images, in pixels.
pub(crate) const QUICK_SIDE: u32 = 128;
/// Frames per timed configuration in a quick report (at most).
pub(crate) const QUICK_RUNS: usize = 3;

impl Request {
    /// The settings and runs actually measured: the quick report's lower
    /// resolution and fewer runs applied.
    pub(crate) fn measured(&self) -> (RenderSettings, usize) {
        // A report's frames stop at N x N and sample uniformly, as the
        // course's did, with shadows on but where section 2 turns them off,
        // whatever a window was doing.
        let mut base = RenderSettings {
            keep_refining: false,
            sampling: tracer::render::Sampling::Uniform,
            shadows: true,
            ..self.base.clone()
        };
        let mut runs = self.runs.max(1);
        if self.quick {
            let longer = base.width.max(base.height);
            if longer > QUICK_SIDE {
                let scale = |v: u32| {
                    ((u64::from(v) * u64::from(QUICK_SIDE) / u64::from(longer)) as u32).max(1)
                };
                base.width = scale(base.width);
                base.height = scale(base.height);
                // The lens is in pixels: keep its blur the same share of the
                // image, the timing table's own lens too when the scene has
                // none (its depth-of-field rows are blurred all the same).
                let lens = match base.chosen_lens(&self.scene.view).aperture {
                    open if open > 0.0 => open,
                    _ => benchmark::MATRIX_APERTURE,
                };
                base.lens_override.aperture = Some(lens * QUICK_SIDE as f32 / longer as f32);
            }
            runs = runs.min(QUICK_RUNS);
        }
        (base, runs)
    }

    /// The worker threads the frames run on.
    pub(crate) fn threads_used(&self) -> usize {
        match self.threads {
            Some(n) if n > 0 => n,
            _ => rayon::current_num_threads(),
        }
    }
}

/// The settings of one plain frame: `base` with `accel`, hard shadows and
/// one sample per pixel, the Whitted image the others are compared with.
fn plain(base: &RenderSettings, accel: AccelKind) -> RenderSettings {
    RenderSettings {
        accel,
        shadows: true,
        soft_shadows: false,
        antialiasing: false,
        depth_of_field: false,
        keep_refining: false,
        ..base.clone()
    }
}

/// Everything measured for the page.
pub(crate) struct Lab {
    pub(crate) request: Request,
    /// The settings measured (quick ones lowered) and runs per timing.
    pub(crate) base: RenderSettings,
    pub(crate) runs: usize,
    pub(crate) threads: usize,
    pub(crate) machine: Machine,
    /// The course's timing matrix with a BVH row for each of its rows, in
    /// [`benchmark::matrix`]'s order.
    pub(crate) matrix: Vec<Measurement>,
    /// One frame of each matrix configuration over the BVH, and the plain
    /// frame over none and the grid, with per-pixel views: blocked shadow
    /// rays, the deepest bounce, tests per pixel.
    pub(crate) views: Vec<Measurement>,
    /// Plain frames at depth 0 without shadows (local shading only), then
    /// with hard shadows at depth 0, 1 and the scene's, timed as the matrix.
    pub(crate) whitted: Vec<Measurement>,
    /// The scene's depth with every transmittance set to 0, when something
    /// refracts: reflection without refraction, timed as the others.
    pub(crate) opaque: Option<Measurement>,
    /// Error against samples: the `spp` study with its reference.
    pub(crate) samples: StudyOutcome,
    /// Error against time with adaptive sampling: the `noise-threshold`
    /// study, against a reference of the `spp` study's N.
    pub(crate) adaptive: StudyOutcome,
    /// The grid multiplier study.
    pub(crate) grid: StudyOutcome,
    pub(crate) pixel: PixelExplained,
}

impl Lab {
    /// The timing matrix's row of `accel` with or without soft shadows,
    /// sampled as `sampling`.
    pub(crate) fn row(
        &self,
        accel: AccelKind,
        soft: bool,
        sampling: SamplingColumn,
    ) -> Option<&Measurement> {
        self.matrix.iter().find(|m| {
            let s = &m.case.settings;
            s.accel == accel && s.soft_shadows == soft && SamplingColumn::of(s) == sampling
        })
    }
}

/// How far the measuring has come, for a progress bar.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportProgress {
    /// 0..=1 of the whole report's work (estimated as samples traced).
    pub(crate) fraction: f32,
    /// What is being measured, in words.
    pub(crate) doing: String,
}

/// The report's stages, each with its estimated work (samples traced).
struct Plan {
    matrix: Vec<Case>,
    views: Vec<Case>,
    whitted: Vec<Case>,
    samples: Study,
    /// Over [`Plan::adaptive_base`].
    adaptive: Study,
    grid: Study,
}

fn work(cases: &[Case], runs: usize) -> f64 {
    cases
        .iter()
        .map(|c| {
            let s = &c.settings;
            f64::from(s.width) * f64::from(s.height) * f64::from(s.samples_per_pixel())
        })
        .sum::<f64>()
        * runs as f64
}

/// The samples `study` traces over `base`: its points, and its reference
/// when `with_reference` (a study that reuses another's renders none).
fn study_work(study: &Study, base: &RenderSettings, with_reference: bool) -> f64 {
    let pixels = f64::from(base.width) * f64::from(base.height);
    let per_point: f64 = study
        .values
        .iter()
        .map(|&v| match (study.param, base.adaptive()) {
            (Param::Spp, _) => v * v,
            // An estimate: twice the minimum, about what a threshold of
            // 0.01 spends on the bundled scenes.
            (Param::NoiseThreshold, Some(a)) => 2.0 * f64::from(a.min_spp),
            _ => 1.0,
        })
        .sum();
    let reference = if with_reference && study.param.has_reference() {
        f64::from(study.reference_samples(base)).powi(2)
    } else {
        0.0
    };
    pixels * (per_point * study.options.runs as f64 * study.structures.len() as f64 + reference)
}

impl Plan {
    fn new(request: &Request, base: &RenderSettings, runs: usize) -> Result<Plan> {
        let options = RunOptions {
            runs,
            threads: request.threads,
        };
        let encoding = request.encoding;
        let view = &request.scene.view;
        let matrix = benchmark::matrix(base, view, &AccelKind::ALL, encoding);
        // Blocked shadow rays and bounces do not depend on the structure:
        // the BVH's frames give them; none and the grid add their tests.
        let mut views: Vec<Case> = matrix
            .iter()
            .filter(|c| c.settings.accel == AccelKind::Bvh)
            .cloned()
            .collect();
        for accel in [AccelKind::None, AccelKind::Grid] {
            views.push(Case::new(plain(base, accel), view, encoding));
        }
        let mut depths = vec![0, 1, base.max_depth];
        depths.retain(|&d| d <= base.max_depth);
        depths.dedup();
        let local = Case {
            label: "local shading only".into(),
            settings: RenderSettings {
                max_depth: 0,
                shadows: false,
                ..plain(base, AccelKind::Bvh)
            },
            encoding,
        };
        let whitted = std::iter::once(local)
            .chain(depths.into_iter().map(|max_depth| Case {
                label: format!("depth {max_depth}"),
                settings: RenderSettings {
                    max_depth,
                    ..plain(base, AccelKind::Bvh)
                },
                encoding,
            }))
            .collect();
        let (spp_values, threshold_values, grid_values) = if request.quick {
            ("1..3", "0.01..0.04:x2", "0.5..4:x2")
        } else {
            ("1..6", "0.0025..0.04:x2", "0.25..8:x2")
        };
        let samples = Study {
            param: Param::Spp,
            values: values::parse(spp_values)?,
            structures: vec![AccelKind::Bvh],
            options,
            encoding,
            reference_samples: None,
        };
        let adaptive = Study {
            param: Param::NoiseThreshold,
            values: values::parse(threshold_values)?,
            reference_samples: Some(samples.reference_samples(base)),
            ..samples.clone()
        };
        let grid = Study {
            param: Param::GridM,
            values: values::parse(grid_values)?,
            structures: vec![AccelKind::Grid],
            options,
            encoding,
            reference_samples: None,
        };
        Ok(Plan {
            matrix,
            views,
            whitted,
            samples,
            adaptive,
            grid,
        })
    }

    /// The adaptive study's settings: `base` sampled adaptively from 4
    /// samples a pixel up to the `spp` study's reference (its N x N), so
    /// the two studies' errors are against the same image and adaptive
    /// sampling can reach any error uniform sampling does.
    fn adaptive_base(&self, base: &RenderSettings) -> RenderSettings {
        let most = self.samples.reference_samples(base).pow(2);
        RenderSettings {
            sampling: Sampling::Adaptive(AdaptiveSampling {
                noise_threshold: 0.0,
                min_spp: 4.min(most),
                max_spp: most,
                budget: None,
            }),
            ..base.clone()
        }
    }
}

/// Reports stage fractions as fractions of the whole.
struct Tracker<'a> {
    weights: Vec<f64>,
    stage: usize,
    on_progress: &'a mut dyn FnMut(&ReportProgress),
}

impl Tracker<'_> {
    fn report(&mut self, fraction: f32, doing: &str) {
        let total: f64 = self.weights.iter().sum::<f64>().max(1.0);
        let before: f64 = self.weights[..self.stage].iter().sum();
        let now = before + self.weights[self.stage] * f64::from(fraction.clamp(0.0, 1.0));
        (self.on_progress)(&ReportProgress {
            fraction: (now / total) as f32,
            doing: doing.to_string(),
        });
    }

    /// The runner's events of `cases`, `runs` frames each, as progress.
    fn cases(&mut self, cases: &[Case], runs: usize, event: Event) {
        if let Event::Rendering {
            case,
            run,
            fraction,
        } = event
        {
            let done = (case * runs + run) as f32 + fraction;
            let label = format!("{} (run {}/{runs})", cases[case].label, run + 1);
            self.report(done / (cases.len() * runs).max(1) as f32, &label);
        }
    }

    fn study(&mut self, study: &Study, event: StudyEvent) {
        let points = study.len().max(1) as f32;
        match event {
            StudyEvent::Preparing { what, fraction } => self.report(fraction / points, what),
            StudyEvent::Rendering {
                point, fraction, ..
            } => self.report(
                (point as f32 + fraction) / points,
                &format!("{} study, point {}/{}", study.param, point + 1, points),
            ),
            StudyEvent::Measured { .. } => {}
        }
    }
}

/// Measures everything the page shows. `cancel` stops it between tiles:
/// the result is then `None` and nothing is kept. Blocks: a window runs it
/// on a thread of its own.
pub(crate) fn measure(
    request: &Request,
    cancel: &AtomicBool,
    on_progress: &mut dyn FnMut(&ReportProgress),
) -> Result<Option<Lab>> {
    let (base, runs) = request.measured();
    base.validate()?;
    let plan = Plan::new(request, &base, runs)?;
    let world = &request.world;
    let options = RunOptions {
        runs,
        threads: request.threads,
    };
    let single = RunOptions { runs: 1, ..options };
    let mut tracker = Tracker {
        weights: vec![
            work(&plan.matrix, runs),
            work(&plan.views, 1),
            work(&plan.whitted, runs),
            // The scene made opaque: one more plain frame.
            f64::from(base.width) * f64::from(base.height) * runs as f64,
            study_work(&plan.samples, &base, true),
            study_work(&plan.adaptive, &plan.adaptive_base(&base), false),
            study_work(&plan.grid, &base, true),
            // The chosen pixel and the observer figure: about one frame.
            f64::from(base.width) * f64::from(base.height),
        ],
        stage: 0,
        on_progress,
    };
    let stop = Stop {
        now: cancel,
        after_frame: &AtomicBool::new(false),
    };
    let structures = &mut Structures::default();
    let timed = |cases: &[Case],
                 options: RunOptions,
                 views: bool,
                 tracker: &mut Tracker,
                 structures: &mut Structures|
     -> Result<Option<Vec<Measurement>>> {
        let outcome =
            benchmark::run_cases(world, cases, options, structures, stop, views, &mut |e| {
                tracker.cases(cases, options.runs, e)
            })?;
        Ok((!outcome.cancelled).then_some(outcome.measurements))
    };
    let Some(matrix) = timed(&plan.matrix, options, false, &mut tracker, structures)? else {
        return Ok(None);
    };
    tracker.stage += 1;
    let Some(views) = timed(&plan.views, single, true, &mut tracker, structures)? else {
        return Ok(None);
    };
    tracker.stage += 1;
    let Some(whitted) = timed(&plan.whitted, options, false, &mut tracker, structures)? else {
        return Ok(None);
    };
    tracker.stage += 1;
    let opaque = match opaque_world(request)? {
        None => None,
        Some(world) => {
            let cases = [Case {
                label: format!("depth {} without refraction", base.max_depth),
                settings: plain(&base, AccelKind::Bvh),
                encoding: request.encoding,
            }];
            let outcome = benchmark::run_cases(
                &world,
                &cases,
                options,
                &mut Structures::default(),
                stop,
                false,
                &mut |e| tracker.cases(&cases, runs, e),
            )?;
            if outcome.cancelled {
                return Ok(None);
            }
            outcome.measurements.into_iter().next()
        }
    };
    let subject = |base: RenderSettings| Subject::Scene {
        world: world.clone(),
        base,
    };
    let plain_base = plain(&base, AccelKind::Bvh);
    let mut studies = Vec::new();
    for (study, base) in [
        (&plan.samples, plain_base.clone()),
        (&plan.adaptive, plan.adaptive_base(&plain_base)),
        (&plan.grid, plain_base.clone()),
    ] {
        tracker.stage += 1;
        // The adaptive study is measured against the spp study's
        // reference: the same image, rendered once.
        let shared = match (study.param, studies.first()) {
            (Param::NoiseThreshold, Some(StudyOutcome { reference, .. })) => reference.clone(),
            _ => None,
        };
        let on_event: &mut dyn FnMut(StudyEvent) = &mut |e| tracker.study(study, e);
        let outcome = match shared {
            Some(reference) => {
                study::run_with_reference(study, &subject(base), reference, stop, on_event)
            }
            None => study::run(study, &subject(base), stop, on_event),
        }
        .with_context(|| format!("the {} study", study.param))?;
        if outcome.cancelled {
            return Ok(None);
        }
        studies.push(outcome);
    }
    let grid = studies.pop().context("the grid study is missing")?;
    let adaptive = studies.pop().context("the adaptive study is missing")?;
    let samples = studies.pop().context("the samples study is missing")?;
    tracker.stage += 1;
    tracker.report(0.0, "choosing and drawing one pixel");
    let pixel = pixel::explain(request, &plain(&base, AccelKind::Bvh), structures)?;
    tracker.report(1.0, "writing the page");
    Ok(Some(Lab {
        request: request.clone(),
        base,
        runs,
        threads: request.threads_used(),
        machine: Machine::this(),
        matrix,
        views,
        whitted,
        opaque,
        samples,
        adaptive,
        grid,
        pixel,
    }))
}

/// The request's world with every transmitting object's `t` set to 0
/// (as `--set 'object N t 0'` does), or `None` when nothing transmits.
fn opaque_world(request: &Request) -> Result<Option<Arc<World>>> {
    let scene = &request.scene;
    let lines: Vec<String> = scene
        .objects
        .iter()
        .enumerate()
        .filter(|(_, o)| {
            scene
                .materials
                .get(o.material as usize)
                .is_some_and(|m| m.transmittance > 0.0)
        })
        .map(|(i, _)| format!("object {i} t 0"))
        .collect();
    if lines.is_empty() {
        return Ok(None);
    }
    let (_, opaque, _) = crate::load::with_edits(scene, &request.world, &lines)
        .context("the scene without refraction")?;
    Ok(Some(opaque))
}

/// The page: the seven sections in the course report's order.
pub(crate) fn page(lab: &Lab) -> Result<String> {
    let title = format!("Lab report: {}", lab.request.scene_name);
    let sections = [
        run::section(lab),
        whitted::section(lab)?,
        sampling::section(lab)?,
        acceleration::section(lab)?,
        statistics::section(lab),
        pixel::section(lab)?,
        course::section(lab),
    ];
    Ok(html::page(&title, &sections))
}

/// The timing matrix as `workbench bench --matrix --format json` writes
/// it: the numbers of the page's timing table, for scripts and checks.
pub(crate) fn matrix_json(lab: &Lab) -> String {
    bench_table::table(&lab.matrix, Columns::Matrix, Format::Json)
}

/// Writes `text` to `path` whole or not at all: a temporary file beside it,
/// renamed over it once complete.
pub(crate) fn write_atomically(path: &Path, text: &str) -> Result<()> {
    crate::image_file::write_atomically(path, |file| {
        use std::io::Write as _;
        file.write_all(text.as_bytes())?;
        Ok(())
    })
    .with_context(|| format!("cannot write {}", path.display()))
}

/// How a timed number was measured, said once per table.
fn how_measured(lab: &Lab) -> String {
    format!(
        "Each time is the median of {} frame(s) rendered in a row, with the spread as \
         min..max and the median absolute deviation (MAD), on {} thread(s); build times \
         apart. {}",
        lab.runs,
        lab.threads,
        if lab.request.quick {
            "Quick report: fewer runs and a lower resolution than a full one."
        } else {
            ""
        }
    )
}

/// Milliseconds with one decimal: the page's one format for frame times.
fn ms(d: std::time::Duration) -> String {
    format!("{:.1}", millis(d))
}
