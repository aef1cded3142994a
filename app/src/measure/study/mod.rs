//! Parameter studies: one setting swept over a list of values, for one or
//! more acceleration structures, each point measured as the benchmark
//! measures a row (repeated frames, median, build time apart). The `level`
//! study sweeps the size of a generated scene instead, so that the number
//! of primitives is the x axis; the `spp` study also measures each image's
//! error against a high-N reference of the same scene.

pub(crate) mod analysis;
mod material;
pub(crate) mod values;

use std::fmt;
use std::str::FromStr;
use std::sync::Arc;
use std::sync::atomic::Ordering;

use anyhow::{Context, Result, bail};
use image::RgbImage;
use tracer::accel::AccelKind;
use tracer::generate::{self, GenerateOptions, GeneratorName};
use tracer::render::{Encoding, MAX_DEPTH, MAX_IMAGE_SIDE, MAX_SAMPLES, RenderSettings, Sampling};
use tracer::scene::Scene;
use tracer::scene::edit::{Edit, ObjectChange};
use tracer::world::World;

use crate::describe::millis;
use crate::measure::ab::{self, Heatmap, Metrics};
use crate::measure::benchmark::{self, Case, Event, Measurement, RunOptions, Stop, Structures};

pub(crate) use material::Knob;

/// The setting a study sweeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum Param {
    /// The uniform grid's cell multiplier m.
    GridM,
    /// N, with anti-aliasing on: N x N samples per pixel.
    Spp,
    /// The maximum number of bounces.
    Depth,
    /// The side of the square lights, with soft shadows on.
    LightSize,
    /// The lens diameter in pixels, with depth of field on (0: a pinhole).
    Aperture,
    /// The image width in pixels; the height keeps the scene's aspect.
    Resolution,
    /// The level of a generated scene (its size).
    Level,
    /// Adaptive sampling's noise threshold, with anti-aliasing on.
    NoiseThreshold,
    /// A numeric field of one object's material (`object:5:ior`), edited
    /// as `--set 'object 5 ior V'` would; the structure is built once.
    Material { object: u32, field: Knob },
}

impl Param {
    pub(crate) const ALL: [Param; 8] = [
        Param::GridM,
        Param::Spp,
        Param::Depth,
        Param::LightSize,
        Param::Aperture,
        Param::Resolution,
        Param::Level,
        Param::NoiseThreshold,
    ];

    /// The name on the command line (`--param grid-m`).
    pub(crate) fn name(self) -> &'static str {
        match self {
            Param::GridM => "grid-m",
            Param::Spp => "spp",
            Param::Depth => "depth",
            Param::LightSize => "light-size",
            Param::Aperture => "aperture",
            Param::Resolution => "resolution",
            Param::Level => "level",
            Param::NoiseThreshold => "noise-threshold",
            Param::Material { field, .. } => field.name(),
        }
    }

    /// The x axis of its chart, with the unit.
    pub(crate) fn axis(self) -> &'static str {
        match self {
            Param::GridM => "grid cell multiplier m",
            Param::Spp => "N (N x N samples per pixel)",
            Param::Depth => "maximum depth (bounces)",
            Param::LightSize => "light size (scene units)",
            Param::Aperture => "aperture (pixels)",
            Param::Resolution => "image width (pixels)",
            Param::Level => "primitives",
            Param::NoiseThreshold => "noise threshold (display units)",
            Param::Material { field, .. } => field.axis(),
        }
    }

    /// Whether only whole numbers make sense.
    pub(crate) fn is_integer(self) -> bool {
        matches!(
            self,
            Param::Spp | Param::Depth | Param::Resolution | Param::Level
        )
    }

    /// Why `value` cannot be used, if it cannot.
    pub(crate) fn check(self, value: f64) -> Result<(), String> {
        let name = self.name();
        let shown = values::format(value);
        if self.is_integer() && value.fract() != 0.0 {
            return Err(format!("{name} takes whole numbers, not {shown}"));
        }
        let (low, high) = match self {
            Param::GridM => (f64::MIN_POSITIVE, 1e4),
            Param::Spp => (1.0, f64::from(MAX_SAMPLES)),
            Param::Depth => (0.0, f64::from(MAX_DEPTH)),
            Param::LightSize | Param::Aperture => (0.0, f64::from(f32::MAX)),
            Param::Resolution => (1.0, f64::from(MAX_IMAGE_SIDE)),
            Param::Level => (0.0, f64::from(u32::MAX)),
            Param::NoiseThreshold => (0.0, 1.0),
            // The edit checks its value against the material it changes.
            Param::Material { .. } => (f64::MIN, f64::MAX),
        };
        if !(low..=high).contains(&value) {
            let range = match self {
                Param::GridM => "above 0, at most 10000".to_string(),
                Param::LightSize | Param::Aperture => "0 or more".to_string(),
                _ => format!("{} to {}", values::format(low), values::format(high)),
            };
            return Err(format!("{name} {shown} is out of range ({range})"));
        }
        Ok(())
    }

    /// `settings` with this parameter at `value`, and the feature it
    /// belongs to turned on (anti-aliasing for N, soft shadows for the
    /// light size, depth of field for a non-zero aperture). A level is not
    /// a render setting: it leaves `settings` alone.
    pub(crate) fn apply(self, settings: &mut RenderSettings, value: f64) {
        match self {
            Param::GridM => settings.grid_multiplier = value as f32,
            Param::Spp => {
                settings.antialiasing = true;
                settings.set_samples(value as u32);
            }
            Param::Depth => settings.max_depth = value as u32,
            Param::LightSize => {
                settings.soft_shadows = true;
                settings.light_size = value as f32;
            }
            Param::Aperture => {
                settings.lens_override.aperture = Some(value as f32);
                settings.depth_of_field = value > 0.0;
            }
            Param::Resolution => {
                let aspect = f64::from(settings.height) / f64::from(settings.width.max(1));
                settings.width = value as u32;
                settings.height = ((value * aspect).round() as u32).max(1);
            }
            Param::NoiseThreshold => {
                settings.antialiasing = true;
                settings.sample_adaptively(|knobs| knobs.noise_threshold = value as f32);
            }
            Param::Level | Param::Material { .. } => {}
        }
    }

    /// Whether the study measures each image's error against a uniform
    /// reference with many samples.
    pub(crate) fn has_reference(self) -> bool {
        matches!(self, Param::Spp | Param::NoiseThreshold)
    }

    /// The scene edit of a material study's point (none for the others,
    /// which change settings).
    pub(crate) fn edit(self, value: f64) -> Option<Edit> {
        match self {
            Param::Material { object, field } => Some(Edit::Object {
                index: object as usize,
                change: ObjectChange::Material(field.with(value as f32)),
            }),
            _ => None,
        }
    }

    /// Values worth a first look, as the values syntax writes them.
    pub(crate) fn default_values(self, base: &RenderSettings) -> String {
        match self {
            Param::GridM => "0.25..8:x2".into(),
            Param::Spp => "1..6".into(),
            Param::Depth => "0..6".into(),
            Param::LightSize => [0.25, 0.5, 1.0, 2.0, 4.0]
                .map(|f| format!("{:.3}", f64::from(base.light_size) * f))
                .map(|v| values::format(v.parse().unwrap_or_default()))
                .join(","),
            Param::Aperture => "0..16:4".into(),
            Param::Resolution => "64..512:x2".into(),
            Param::Level => "1..4".into(),
            Param::NoiseThreshold => "0.0025..0.04:x2".into(),
            Param::Material { field, .. } => field.default_values().into(),
        }
    }

    /// The structures a study of this parameter measures unless told:
    /// the grid for its multiplier, all three for scaling, else `current`.
    pub(crate) fn default_structures(self, current: AccelKind) -> Vec<AccelKind> {
        match self {
            Param::GridM => vec![AccelKind::Grid],
            Param::Level => AccelKind::ALL.to_vec(),
            _ => vec![current],
        }
    }
}

impl fmt::Display for Param {
    /// The name `--param` takes: `grid-m`, `object:5:ior`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Param::Material { object, field } => write!(f, "object:{object}:{}", field.name()),
            _ => f.write_str(self.name()),
        }
    }
}

impl FromStr for Param {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if let Some(rest) = s.trim().strip_prefix("object:") {
            return material::parse(rest);
        }
        Param::ALL
            .into_iter()
            .find(|p| p.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| {
                let names: Vec<&str> = Param::ALL.iter().map(|p| p.name()).collect();
                format!(
                    "unknown parameter `{s}` (expected one of {}, or object:N:FIELD with FIELD \
                     one of {})",
                    names.join(", "),
                    Knob::NAMES.join(", ")
                )
            })
    }
}

/// What a study renders.
pub(crate) enum Subject {
    /// One scene, with the settings every point starts from.
    Scene {
        world: Arc<World>,
        base: RenderSettings,
    },
    /// One scene with its document, for studies that edit the scene (a
    /// material field) as well as those that change settings.
    Document {
        scene: Arc<Scene>,
        world: Arc<World>,
        base: RenderSettings,
    },
    /// The level study: a built-in generator's scene at each level, with
    /// the settings each generated scene gets.
    Generated {
        generator: GeneratorName,
        seed: u64,
        settings: Box<dyn Fn(&Scene) -> RenderSettings + Send>,
    },
}

/// A study: which parameter, which values, which structures, how measured.
#[derive(Debug, Clone)]
pub(crate) struct Study {
    pub(crate) param: Param,
    /// Ascending (see [`values::parse`]).
    pub(crate) values: Vec<f64>,
    pub(crate) structures: Vec<AccelKind>,
    pub(crate) options: RunOptions,
    pub(crate) encoding: Encoding,
    /// N of the reference of the `spp` and `noise-threshold` studies;
    /// `None`: twice the largest N (the adaptive maximum's strata).
    pub(crate) reference_samples: Option<u32>,
}

impl Study {
    /// How many points it measures.
    pub(crate) fn len(&self) -> usize {
        self.values.len() * self.structures.len()
    }

    /// The points in the order they are measured: structure by structure
    /// over one scene (each structure's built ones are kept), level by
    /// level for generated scenes (each level is generated once).
    pub(crate) fn plan(&self) -> Vec<(AccelKind, f64)> {
        let mut plan = Vec::new();
        if self.param == Param::Level {
            for &value in &self.values {
                plan.extend(self.structures.iter().map(|&a| (a, value)));
            }
        } else {
            for &accel in &self.structures {
                plan.extend(self.values.iter().map(|&v| (accel, v)));
            }
        }
        plan
    }

    /// N of the reference image of the `spp` and `noise-threshold`
    /// studies over `base`.
    pub(crate) fn reference_samples(&self, base: &RenderSettings) -> u32 {
        self.reference_samples.unwrap_or_else(|| {
            let largest = match self.param {
                Param::NoiseThreshold => point_settings(base, self.param, base.accel, 0.0).strata(),
                _ => self.values.iter().copied().fold(1.0, f64::max) as u32,
            };
            (2 * largest).min(MAX_SAMPLES)
        })
    }

    /// Refuses a study that cannot run, before anything is rendered.
    pub(crate) fn check(&self, subject: &Subject) -> Result<()> {
        if self.values.is_empty() {
            bail!("the study has no values");
        }
        if self.structures.is_empty() {
            bail!("the study has no structures");
        }
        for &value in &self.values {
            self.param.check(value).map_err(anyhow::Error::msg)?;
        }
        if let (Param::Material { .. }, Subject::Document { scene, .. }) = (self.param, subject) {
            return material::check(self, scene);
        }
        match subject {
            Subject::Scene { base, .. } | Subject::Document { base, .. } => {
                if matches!(self.param, Param::Material { .. }) {
                    bail!(
                        "{} edits the scene: the study needs its document",
                        self.param
                    );
                }
                if self.param == Param::Level {
                    bail!(
                        "the level study sweeps a generated scene: give a generator, not a scene"
                    );
                }
                for (accel, value) in self.plan() {
                    let settings = point_settings(base, self.param, accel, value);
                    settings
                        .validate()
                        .with_context(|| format!("{} = {}", self.param, values::format(value)))?;
                }
            }
            Subject::Generated { generator, .. } => {
                if self.param != Param::Level {
                    bail!(
                        "a generated scene is swept by level; for {} give a scene file",
                        self.param
                    );
                }
                let range = generate::level_range(*generator);
                if let Some(bad) = self.values.iter().find(|&&v| !range.contains(&(v as u32))) {
                    bail!(
                        "{generator} has levels {}..={}, not {}",
                        range.start(),
                        range.end(),
                        values::format(*bad)
                    );
                }
            }
        }
        Ok(())
    }
}

/// The settings of one point.
fn point_settings(
    base: &RenderSettings,
    param: Param,
    accel: AccelKind,
    value: f64,
) -> RenderSettings {
    let mut settings = RenderSettings {
        accel,
        ..base.clone()
    };
    param.apply(&mut settings, value);
    settings
}

fn point_case(study: &Study, base: &RenderSettings, accel: AccelKind, value: f64) -> Case {
    Case {
        label: format!(
            "{} {} = {}",
            accel.name(),
            study.param,
            values::format(value)
        ),
        settings: point_settings(base, study.param, accel, value),
        encoding: study.encoding,
    }
}

/// One measured point.
#[derive(Debug, Clone)]
pub struct Point {
    /// The parameter's value.
    pub value: f64,
    /// Where it goes on the x axis: the value, or the primitive count for
    /// the level study.
    pub(crate) x: f64,
    /// Primitives of the scene rendered.
    pub(crate) primitives: usize,
    pub(crate) measurement: Measurement,
    /// The image's error against the reference (the `spp` study).
    pub(crate) error: Option<Metrics>,
}

impl Point {
    pub fn accel(&self) -> AccelKind {
        self.measurement.case.settings.accel
    }

    /// The median frame time in milliseconds.
    pub(crate) fn frame_ms(&self) -> f64 {
        millis(self.measurement.median())
    }
}

/// The `spp` study's reference image.
#[derive(Debug, Clone)]
pub(crate) struct ReferenceRender {
    pub(crate) samples: u32,
    pub(crate) image: RgbImage,
}

/// What a study reports while it works.
#[derive(Debug)]
pub(crate) enum StudyEvent<'a> {
    /// Work before the points: generating a level's scene, rendering the
    /// reference; `fraction` (0..=1) of it done.
    Preparing { what: &'a str, fraction: f32 },
    /// Frame `run` of point `point` (in [`Study::plan`] order) is
    /// `fraction` done.
    Rendering {
        point: usize,
        run: usize,
        fraction: f32,
    },
    /// Point `point` is measured.
    Measured { point: usize, result: &'a Point },
}

/// The points measured, and whether the study stopped early.
#[derive(Debug, Clone, Default)]
pub(crate) struct StudyOutcome {
    pub(crate) points: Vec<Point>,
    pub(crate) cancelled: bool,
    pub(crate) reference: Option<ReferenceRender>,
}

/// Measures every point of `study` on `subject`, in [`Study::plan`] order,
/// reusing each built structure for all points that trace against it.
/// `stop` ends it early with the points measured so far. Blocks.
pub fn run(
    study: &Study,
    subject: &Subject,
    stop: Stop,
    on_event: &mut dyn FnMut(StudyEvent),
) -> Result<StudyOutcome> {
    study.check(subject)?;
    match subject {
        Subject::Document { scene, world, base } if study.param.edit(0.0).is_some() => {
            material::run(study, scene, world, base, stop, on_event)
        }
        Subject::Scene { world, base } | Subject::Document { world, base, .. } => {
            run_scene(study, world, base, None, stop, on_event)
        }
        Subject::Generated {
            generator,
            seed,
            settings,
        } => run_levels(study, *generator, *seed, settings, stop, on_event),
    }
}

/// [`run`] against a reference already rendered, another study's of the
/// same scene and N (a noise-threshold study beside the `spp` study it is
/// compared with): its points are measured against that image, which is
/// not rendered again.
pub(crate) fn run_with_reference(
    study: &Study,
    subject: &Subject,
    reference: ReferenceRender,
    stop: Stop,
    on_event: &mut dyn FnMut(StudyEvent),
) -> Result<StudyOutcome> {
    study.check(subject)?;
    let Subject::Scene { world, base } = subject else {
        bail!("a reference is reused on a scene's settings only");
    };
    let wanted = study.reference_samples(base);
    if !study.param.has_reference() || reference.samples != wanted {
        bail!(
            "the {} study takes a reference of N = {wanted}, not N = {}",
            study.param,
            reference.samples
        );
    }
    run_scene(study, world, base, Some(reference), stop, on_event)
}

/// Some of a study's points (`first..`), measured in one call of the
/// runner on `world`: its events forwarded as study events, each
/// measurement turned into a point (with its error against `reference`).
struct Batch<'a> {
    world: &'a Arc<World>,
    cases: &'a [Case],
    first: usize,
    /// Where the points stand on the chart's x axis, if not at their value.
    x: Option<f64>,
    /// Each case's value.
    values: Vec<f64>,
    reference: Option<&'a RgbImage>,
}

impl Batch<'_> {
    /// What every runner does in its loop: measures the cases with the
    /// structures built so far, adds their points to `outcome` and marks
    /// it cancelled when the study was stopped.
    fn measure(
        &self,
        options: RunOptions,
        structures: &mut Structures,
        stop: Stop,
        outcome: &mut StudyOutcome,
        on_event: &mut dyn FnMut(StudyEvent),
    ) -> Result<()> {
        let points = &mut outcome.points;
        let measured = benchmark::run_with(
            self.world,
            self.cases,
            options,
            structures,
            stop,
            &mut |event| self.event(event, points, on_event),
        )?;
        outcome.cancelled |= measured.cancelled;
        Ok(())
    }

    fn event(&self, event: Event, points: &mut Vec<Point>, on_event: &mut dyn FnMut(StudyEvent)) {
        match event {
            Event::Rendering {
                case,
                run,
                fraction,
            } => on_event(StudyEvent::Rendering {
                point: self.first + case,
                run,
                fraction,
            }),
            Event::Measured { case, measurement } => {
                let value = self.values[case];
                let error = self.reference.and_then(|reference| {
                    ab::measure(&measurement.image, reference, Heatmap::Flip)
                        .ok()
                        .map(|(metrics, _)| metrics)
                });
                let point = Point {
                    value,
                    x: self.x.unwrap_or(value),
                    primitives: self.world.counts.primitives,
                    measurement: measurement.clone(),
                    error,
                };
                on_event(StudyEvent::Measured {
                    point: self.first + case,
                    result: &point,
                });
                points.push(point);
            }
        }
    }
}

/// The points of `study` over `base` on `world`, against `reference`
/// or, when the study has one and none is given, a reference it renders.
fn run_scene(
    study: &Study,
    world: &Arc<World>,
    base: &RenderSettings,
    reference: Option<ReferenceRender>,
    stop: Stop,
    on_event: &mut dyn FnMut(StudyEvent),
) -> Result<StudyOutcome> {
    let mut structures = Structures::default();
    let mut outcome = StudyOutcome {
        reference,
        ..StudyOutcome::default()
    };
    let one_frame = RunOptions {
        runs: 1,
        ..study.options
    };
    if study.param.has_reference() && outcome.reference.is_none() {
        let samples = study.reference_samples(base);
        let what = format!("reference image, N = {samples}");
        // The image does not depend on the structure: use the first one,
        // so it is built once for the reference and the points.
        let case = Case {
            label: what.clone(),
            settings: RenderSettings {
                accel: study.structures[0],
                antialiasing: true,
                samples,
                sampling: Sampling::Uniform,
                ..base.clone()
            },
            encoding: study.encoding,
        };
        let rendered = benchmark::run_with(
            world,
            &[case],
            one_frame,
            &mut structures,
            stop,
            &mut |event| {
                if let Event::Rendering { fraction, .. } = event {
                    on_event(StudyEvent::Preparing {
                        what: &what,
                        fraction,
                    });
                }
            },
        )?;
        match rendered.measurements.into_iter().next() {
            Some(m) if !rendered.cancelled => {
                outcome.reference = Some(ReferenceRender {
                    samples,
                    image: m.image,
                })
            }
            _ => {
                outcome.cancelled = true;
                return Ok(outcome);
            }
        }
    }
    // Borrowed by the batches while they add to the outcome.
    let reference = outcome.reference.take();
    for (i, &accel) in study.structures.iter().enumerate() {
        let cases: Vec<Case> = study
            .values
            .iter()
            .map(|&v| point_case(study, base, accel, v))
            .collect();
        let batch = Batch {
            world,
            cases: &cases,
            first: i * study.values.len(),
            x: None,
            values: study.values.clone(),
            reference: reference.as_ref().map(|r| &r.image),
        };
        batch.measure(study.options, &mut structures, stop, &mut outcome, on_event)?;
        if outcome.cancelled {
            break;
        }
    }
    outcome.reference = reference;
    Ok(outcome)
}

fn run_levels(
    study: &Study,
    generator: GeneratorName,
    seed: u64,
    settings: &dyn Fn(&Scene) -> RenderSettings,
    stop: Stop,
    on_event: &mut dyn FnMut(StudyEvent),
) -> Result<StudyOutcome> {
    let mut outcome = StudyOutcome::default();
    for (i, &level) in study.values.iter().enumerate() {
        if stop.now.load(Ordering::Relaxed) || stop.after_frame.load(Ordering::Relaxed) {
            outcome.cancelled = true;
            break;
        }
        let what = format!("generating {generator} level {}", values::format(level));
        on_event(StudyEvent::Preparing {
            what: &what,
            fraction: 0.0,
        });
        let options = GenerateOptions {
            level: level as u32,
            seed,
        };
        let scene = generate::generate(generator, &options)?;
        let world = Arc::new(World::build(&scene));
        let base = settings(&scene);
        let cases: Vec<Case> = study
            .structures
            .iter()
            .map(|&accel| point_case(study, &base, accel, level))
            .collect();
        let batch = Batch {
            world: &world,
            cases: &cases,
            first: i * study.structures.len(),
            x: Some(world.counts.primitives as f64),
            values: vec![level; cases.len()],
            reference: None,
        };
        // A new world: its structures are built once each, here.
        batch
            .measure(
                study.options,
                &mut Structures::default(),
                stop,
                &mut outcome,
                on_event,
            )
            .with_context(|| format!("{generator} level {}", values::format(level)))?;
        if outcome.cancelled {
            break;
        }
    }
    Ok(outcome)
}

#[cfg(test)]
mod tests;
