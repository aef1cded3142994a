//! Measuring renders: a list of cases (settings), each rendered a number of
//! times with progress reports and cancellation, and the course report's
//! timing matrix (Figure 5.1) as such a list. The command line and the
//! window share it; nothing here prints.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use anyhow::{Context, Result, bail};
use image::RgbImage;
use tracer::accel::{AccelInfo, AccelKind, SceneIndex};
use tracer::render::{
    Encoding, JobOptions, JobState, LensOverride, RenderJob, RenderSettings, Sampling, ViewFilm,
};
use tracer::scene::{Lens, Scene, Viewpoint};
use tracer::stats::RenderStats;
use tracer::world::World;

use crate::describe::describe;

/// One configuration to measure.
#[derive(Debug, Clone, PartialEq)]
pub struct Case {
    /// What the row is called in reports and progress messages.
    pub label: String,
    pub settings: RenderSettings,
    /// How the kept image is encoded (does not change the timing).
    pub(crate) encoding: Encoding,
}

impl Case {
    /// A case of a scene seen from `view`, labelled with [`describe`].
    pub(crate) fn new(settings: RenderSettings, view: &Viewpoint, encoding: Encoding) -> Self {
        Self {
            label: describe(&settings, view),
            settings,
            encoding,
        }
    }

    /// A file name for the case's image, unique within a matrix, e.g.
    /// `grid_soft_aa4_dof`.
    pub fn file_stem(&self) -> String {
        let s = &self.settings;
        let mut stem = s.accel.name().to_string();
        if s.soft_shadows {
            stem.push_str("_soft");
        }
        if s.antialiasing {
            stem.push_str(&format!("_aa{}", s.samples));
        }
        if s.depth_of_field {
            stem.push_str("_dof");
        }
        stem
    }
}

/// The settings of a benchmark frame of `scene`: one sample per pixel
/// with hard shadows, the scene's size and structure, unless the caller
/// asks for more; anti-aliasing samples uniformly, as the course's table
/// did, whatever the scene suggests. `workbench bench` and the web page's
/// `?bench` measure the same frame.
pub(crate) fn frame_settings(scene: &Scene) -> RenderSettings {
    let mut settings = RenderSettings::from_scene(scene);
    settings.antialiasing = false;
    settings.depth_of_field = false;
    settings.sampling = Sampling::Uniform;
    settings
}

/// The sampling column of the course's timing matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SamplingColumn {
    /// One sample per pixel.
    Single,
    /// Jittered N x N anti-aliasing.
    Antialiasing,
    /// Anti-aliasing and depth of field (the course only measured DOF with AA).
    AntialiasingDof,
}

impl SamplingColumn {
    /// The column `settings` belong in (depth of field without
    /// anti-aliasing, which the course did not measure, counts as DOF).
    pub(crate) fn of(settings: &RenderSettings) -> SamplingColumn {
        match (settings.antialiasing, settings.depth_of_field) {
            (_, true) => SamplingColumn::AntialiasingDof,
            (true, false) => SamplingColumn::Antialiasing,
            (false, false) => SamplingColumn::Single,
        }
    }
}

/// The course measured its matrix with N = 4 (4 x 4 samples per pixel); a
/// scene's own `spp` is its everyday choice, not the benchmark's.
pub(crate) const MATRIX_SAMPLES: u32 = 4;

/// Aperture (pixels) of the matrix's depth-of-field rows when the scene
/// has none, so those rows blur and sample a lens as the course's did.
pub(crate) const MATRIX_APERTURE: f32 = 8.0;

/// The course report's timing table (Figure 5.1) over `accels`: for each structure,
/// hard then soft shadows, each with one sample, AA, and AA with DOF; the
/// course measured none and grid (12 rows), the workbench adds BVH (18).
/// Everything else (size, N, light size, lens, depth, seed) comes from
/// `base` rendering `view`: set its `samples` to [`MATRIX_SAMPLES`] for the
/// course's N.
pub(crate) fn matrix(
    base: &RenderSettings,
    view: &Viewpoint,
    accels: &[AccelKind],
    encoding: Encoding,
) -> Vec<Case> {
    let open = base.chosen_lens(view).aperture > 0.0;
    let mut cases = Vec::new();
    for &accel in accels {
        for soft_shadows in [false, true] {
            for sampling in [
                SamplingColumn::Single,
                SamplingColumn::Antialiasing,
                SamplingColumn::AntialiasingDof,
            ] {
                let dof = sampling == SamplingColumn::AntialiasingDof;
                let settings = RenderSettings {
                    accel,
                    soft_shadows,
                    antialiasing: sampling != SamplingColumn::Single,
                    depth_of_field: dof,
                    lens_override: if dof && !open {
                        LensOverride {
                            aperture: Some(MATRIX_APERTURE),
                            ..base.lens_override
                        }
                    } else {
                        base.lens_override
                    },
                    ..base.clone()
                };
                cases.push(Case::new(settings, view, encoding));
            }
        }
    }
    cases
}

/// `base` with each structure in turn: today's `workbench bench` table.
pub(crate) fn structures(
    base: &RenderSettings,
    accels: &[AccelKind],
    encoding: Encoding,
) -> Vec<Case> {
    accels
        .iter()
        .map(|&accel| {
            let settings = RenderSettings {
                accel,
                ..base.clone()
            };
            Case {
                label: accel.name().to_string(),
                settings,
                encoding,
            }
        })
        .collect()
}

/// How to run the cases.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RunOptions {
    /// Frames per case (at least one).
    pub(crate) runs: usize,
    /// Worker threads; `None` uses every core.
    pub(crate) threads: Option<usize>,
}

/// What the runner reports while it works, for a progress bar or a table
/// that fills in.
#[derive(Debug)]
pub enum Event<'a> {
    /// Frame `run` of case `case` is `fraction` (0..=1) done.
    Rendering {
        case: usize,
        run: usize,
        fraction: f32,
    },
    /// Every frame of case `case` is done.
    Measured {
        case: usize,
        measurement: &'a Measurement,
    },
}

impl Event<'_> {
    /// The event as the runner of more cases tells it, this case being
    /// its `first + case`.
    pub(crate) fn offset(self, first: usize) -> Self {
        match self {
            Event::Rendering {
                case,
                run,
                fraction,
            } => Event::Rendering {
                case: first + case,
                run,
                fraction,
            },
            Event::Measured { case, measurement } => Event::Measured {
                case: first + case,
                measurement,
            },
        }
    }
}

/// A case's results.
#[derive(Debug, Clone)]
pub struct Measurement {
    pub case: Case,
    /// Render time of each frame (the structure's build excluded), in run
    /// order.
    pub times: Vec<Duration>,
    /// The last frame's statistics (every frame does the same work).
    pub(crate) stats: RenderStats,
    /// The structure traced against, with its build time and memory.
    pub(crate) index: AccelInfo,
    /// The lens chosen for the scene (its view's, or the settings'
    /// override), seen through only with depth of field on: what the
    /// tables say the case rendered with.
    pub(crate) lens: Lens,
    /// The last frame's image.
    pub image: RgbImage,
    /// The last frame's per-pixel views, when the run measured them
    /// ([`run_cases`] with `views`).
    pub(crate) views: Option<ViewFilm>,
}

impl Measurement {
    /// The median frame time: what the reports call the frame time.
    pub(crate) fn median(&self) -> Duration {
        median(&self.times)
    }

    pub(crate) fn min(&self) -> Duration {
        self.times.iter().copied().min().unwrap_or_default()
    }

    pub(crate) fn max(&self) -> Duration {
        self.times.iter().copied().max().unwrap_or_default()
    }

    /// Median absolute deviation from the median: a spread that one
    /// disturbed frame on a shared machine does not inflate.
    pub(crate) fn mad(&self) -> Duration {
        let m = self.median();
        let deviations: Vec<Duration> = self.times.iter().map(|&t| t.abs_diff(m)).collect();
        median(&deviations)
    }

    /// Rays of every kind in one frame.
    pub(crate) fn rays(&self) -> u64 {
        self.stats.counters.total_rays()
    }

    /// Rays per second at the median frame time.
    pub(crate) fn rays_per_second(&self) -> f64 {
        self.rays() as f64 / self.median().as_secs_f64().max(1e-9)
    }

    /// Ray-primitive intersection tests per ray: the work a structure
    /// failed to avoid.
    pub(crate) fn tests_per_ray(&self) -> f64 {
        self.per_ray(self.stats.counters.intersection_tests)
    }

    /// Grid cells or BVH nodes visited per ray: what the structure itself
    /// costs to walk.
    pub(crate) fn steps_per_ray(&self) -> f64 {
        self.per_ray(self.stats.counters.nodes_visited)
    }

    /// `row` (a JSON object) with the timing figures every report gives:
    /// runs, frame times, build time, memory, rays and rays per second,
    /// times in seconds.
    pub(crate) fn with_timing_json(&self, mut row: serde_json::Value) -> serde_json::Value {
        let secs = |d: Duration| serde_json::json!(d.as_secs_f64());
        if let Some(fields) = row.as_object_mut() {
            let times: Vec<f64> = self.times.iter().map(Duration::as_secs_f64).collect();
            fields.extend([
                ("runs".to_string(), serde_json::json!(self.times.len())),
                ("seconds".to_string(), serde_json::json!(times)),
                ("median_seconds".to_string(), secs(self.median())),
                ("min_seconds".to_string(), secs(self.min())),
                ("max_seconds".to_string(), secs(self.max())),
                ("build_seconds".to_string(), secs(self.index.build_time)),
                (
                    "memory_bytes".to_string(),
                    serde_json::json!(self.index.memory_bytes),
                ),
                ("rays".to_string(), serde_json::json!(self.rays())),
                (
                    "rays_per_second".to_string(),
                    serde_json::json!(self.rays_per_second()),
                ),
            ]);
        }
        row
    }

    fn per_ray(&self, count: u64) -> f64 {
        count as f64 / self.rays().max(1) as f64
    }
}

/// The middle duration (the mean of the two middle ones for an even
/// count); zero for none.
pub(crate) fn median(values: &[Duration]) -> Duration {
    let mut sorted = values.to_vec();
    sorted.sort_unstable();
    match sorted.len() {
        0 => Duration::ZERO,
        n if n % 2 == 1 => sorted[n / 2],
        n => (sorted[n / 2 - 1] + sorted[n / 2]) / 2,
    }
}

/// The cases measured so far, and whether the run stopped early.
#[derive(Debug, Clone, Default)]
pub(crate) struct BenchOutcome {
    pub(crate) measurements: Vec<Measurement>,
    pub(crate) cancelled: bool,
}

/// How often a waiting runner looks at the render and the cancel flag.
/// Frame times come from the render itself, so polling does not skew them.
const POLL: Duration = Duration::from_millis(10);

/// Structures built over one world, kept so that every case (and every
/// later run over the same world) tracing against the same structure uses
/// the one already built.
#[derive(Default)]
pub(crate) struct Structures {
    built: Vec<Arc<SceneIndex>>,
}

impl Structures {
    /// The structure `accel` (with cell multiplier `grid_multiplier` for a
    /// grid) over `world`, built on first use.
    pub(crate) fn get(
        &mut self,
        world: &World,
        accel: AccelKind,
        grid_multiplier: f32,
    ) -> Arc<SceneIndex> {
        if let Some(index) = self
            .built
            .iter()
            .find(|i| i.matches(accel, grid_multiplier))
        {
            return index.clone();
        }
        let index = Arc::new(SceneIndex::build(&world.shapes, accel, grid_multiplier));
        self.built.push(index.clone());
        index
    }
}

/// When a run stops before its last case.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stop<'a> {
    /// Stop at once: the frame under way is abandoned between tiles.
    pub(crate) now: &'a AtomicBool,
    /// Stop when the frame under way is done: that frame counts, and the
    /// case it belongs to is reported with the frames it has.
    pub(crate) after_frame: &'a AtomicBool,
}

/// Renders every case `options.runs` times, in order. Structures are built
/// once and shared by the cases that use them. Setting `cancel` stops the
/// frame under way between tiles; the cases finished by then are returned
/// with `cancelled` set. Blocks: a window runs it on a thread of its own.
pub fn run(
    world: &Arc<World>,
    cases: &[Case],
    options: RunOptions,
    cancel: &AtomicBool,
    on_event: &mut dyn FnMut(Event),
) -> Result<BenchOutcome> {
    let stop = Stop {
        now: cancel,
        after_frame: &AtomicBool::new(false),
    };
    let structures = &mut Structures::default();
    run_cases(world, cases, options, structures, stop, false, on_event)
}

/// [`run`] with structures kept by the caller (a study measures one world
/// in several runs) and a stop that can wait for the frame under way.
pub(crate) fn run_with(
    world: &Arc<World>,
    cases: &[Case],
    options: RunOptions,
    structures: &mut Structures,
    stop: Stop,
    on_event: &mut dyn FnMut(Event),
) -> Result<BenchOutcome> {
    run_cases(world, cases, options, structures, stop, false, on_event)
}

/// The runner behind [`run`] and [`run_with`], measuring the per-pixel
/// views in the same frames or not: a comparison of views renders each
/// side once (the frame times then include the views' bookkeeping).
pub(crate) fn run_cases(
    world: &Arc<World>,
    cases: &[Case],
    options: RunOptions,
    structures: &mut Structures,
    stop: Stop,
    views: bool,
    on_event: &mut dyn FnMut(Event),
) -> Result<BenchOutcome> {
    let mut outcome = BenchOutcome::default();
    for (case_no, case) in cases.iter().enumerate() {
        let settings = &case.settings;
        let index = structures.get(world, settings.accel, settings.grid_multiplier);
        let mut times = Vec::new();
        let mut last = None;
        for run in 0..options.runs.max(1) {
            let job = RenderJob::start(
                world.clone(),
                Some(index.clone()),
                settings.clone(),
                JobOptions {
                    threads: options.threads,
                    views,
                    ..JobOptions::default()
                },
            )
            .map_err(|e| anyhow::anyhow!("{}: {e}", case.label))?;
            let samples = u64::from(settings.width)
                * u64::from(settings.height)
                * u64::from(settings.samples_per_pixel());
            while !job.is_finished() {
                if stop.now.load(Ordering::Relaxed) {
                    job.cancel();
                }
                let fraction = job.stats().counters.eye_rays as f32 / samples.max(1) as f32;
                on_event(Event::Rendering {
                    case: case_no,
                    run,
                    fraction: fraction.min(1.0),
                });
                std::thread::sleep(POLL);
            }
            let (film, view_film, stats, state) = job.wait_with_views();
            match state {
                JobState::Failed(message) => bail!("{}: render failed: {message}", case.label),
                JobState::Cancelled => {
                    outcome.cancelled = true;
                    return Ok(outcome);
                }
                _ => {}
            }
            times.push(stats.render_time);
            last = Some((film, view_film, stats));
            if stop.after_frame.load(Ordering::Relaxed) {
                break;
            }
        }
        let (film, views, stats) = last.context("no frame was rendered")?;
        let measurement = Measurement {
            case: case.clone(),
            times,
            stats,
            index: index.info().clone(),
            lens: case.settings.chosen_lens(&world.view),
            image: film.to_image(case.encoding),
            views,
        };
        on_event(Event::Measured {
            case: case_no,
            measurement: &measurement,
        });
        outcome.measurements.push(measurement);
        if stop.now.load(Ordering::Relaxed) || stop.after_frame.load(Ordering::Relaxed) {
            outcome.cancelled = true;
            break;
        }
    }
    Ok(outcome)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_matrix_has_the_seed_reports_shape() {
        let base = RenderSettings::default();
        let pinhole = Viewpoint::default();
        let cases = matrix(&base, &pinhole, &AccelKind::ALL, Encoding::Linear);
        assert_eq!(cases.len(), 18);
        // The course's order: structure, then shadows, then sampling.
        let first: Vec<String> = cases[..6].iter().map(Case::file_stem).collect();
        assert_eq!(
            first,
            [
                "none",
                "none_aa4",
                "none_aa4_dof",
                "none_soft",
                "none_soft_aa4",
                "none_soft_aa4_dof"
            ]
        );
        assert_eq!(cases[6].settings.accel, AccelKind::Grid);
        assert_eq!(cases[17].file_stem(), "bvh_soft_aa4_dof");
        let dof = &cases[2].settings;
        assert!(dof.antialiasing && dof.chosen_lens(&pinhole).aperture == MATRIX_APERTURE);
        // A scene's own lens is kept.
        let open = Viewpoint {
            aperture: 3.0,
            ..Viewpoint::default()
        };
        let dof = &matrix(&base, &open, &AccelKind::ALL, Encoding::Linear)[2].settings;
        assert_eq!(dof.chosen_lens(&open).aperture, 3.0);
        assert_eq!(
            matrix(&base, &open, &[AccelKind::Grid], Encoding::Linear).len(),
            6
        );
    }

    fn world() -> Arc<World> {
        let text = "v\nfrom 0 -5 1\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0.01\n\
                    resolution 12 8\nl 2 -2 4\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";
        let scene =
            tracer::scene::parse_scene(text, None, &tracer::scene::Limits::default()).unwrap();
        Arc::new(World::build(&scene))
    }

    #[test]
    fn the_runner_reports_each_case_and_shares_structures() {
        let world = world();
        let base = RenderSettings {
            width: 12,
            height: 8,
            ..RenderSettings::default()
        };
        let cases = matrix(&base, &world.view, &[AccelKind::Grid], Encoding::Linear);
        let mut measured = Vec::new();
        let mut fractions_ok = true;
        let options = RunOptions {
            runs: 2,
            threads: Some(1),
        };
        let outcome = run(
            &world,
            &cases,
            options,
            &AtomicBool::new(false),
            &mut |e| match e {
                Event::Rendering { fraction, .. } => {
                    fractions_ok &= (0.0..=1.0).contains(&fraction)
                }
                Event::Measured { case, measurement } => {
                    measured.push((case, measurement.times.len()))
                }
            },
        )
        .unwrap();
        assert!(!outcome.cancelled && fractions_ok);
        assert_eq!(measured, (0..6).map(|c| (c, 2)).collect::<Vec<_>>());
        let m = &outcome.measurements[4];
        assert_eq!(m.image.dimensions(), (12, 8));
        assert_eq!(m.stats.counters.eye_rays, 12 * 8 * 16);
        assert_eq!(m.index.kind, AccelKind::Grid);
        // One grid, built once, for all six rows.
        let build = outcome.measurements[0].index.build_time;
        assert!(
            outcome
                .measurements
                .iter()
                .all(|m| m.index.build_time == build)
        );
    }

    #[test]
    fn a_cancelled_run_stops_early() {
        let cases = structures(
            &RenderSettings::default(),
            &[AccelKind::None, AccelKind::Bvh],
            Encoding::Linear,
        );
        let options = RunOptions {
            runs: 3,
            threads: Some(1),
        };
        let outcome = run(
            &world(),
            &cases,
            options,
            &AtomicBool::new(true),
            &mut |_| {},
        )
        .unwrap();
        assert!(outcome.cancelled);
        assert!(outcome.measurements.is_empty());
    }

    #[test]
    fn statistics_of_the_frame_times() {
        let ms = Duration::from_millis;
        let m = |times: Vec<Duration>| Measurement {
            case: Case::new(
                RenderSettings::default(),
                &Viewpoint::default(),
                Encoding::Linear,
            ),
            times,
            stats: RenderStats::default(),
            index: SceneIndex::build(&[], AccelKind::None, 1.0).info().clone(),
            lens: Lens::PINHOLE,
            image: RgbImage::new(1, 1),
            views: None,
        };
        let odd = m(vec![ms(30), ms(10), ms(20), ms(100), ms(25)]);
        assert_eq!(odd.median(), ms(25));
        assert_eq!((odd.min(), odd.max()), (ms(10), ms(100)));
        // Deviations 5, 15, 5, 75, 0: median 5.
        assert_eq!(odd.mad(), ms(5));
        let even = m(vec![ms(10), ms(20)]);
        assert_eq!(even.median(), ms(15));
        assert_eq!(m(vec![]).median(), Duration::ZERO);
    }
}
