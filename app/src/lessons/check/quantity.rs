//! What a check can read from the workbench, by a name a teacher writes:
//! a setting (`spp`), a scene value in the words of `--set` (`object 3
//! ior`), the pinned pixel's recorded ray tree (`tree blocked-shadow-rays`),
//! the acceleration structure (`grid cells`, `eye tests`). Each is computed
//! from the state when the check runs, never written in the lesson.

use std::fmt::{self, Display, Formatter};
use std::sync::Arc;

use tracer::accel::{AccelKind, SceneIndex};
use tracer::geometry::Ray;
use tracer::render::{Film, Outcome, RayKind, RayTree, Sampling, View, render};
use tracer::scene::{Primitive, Scene};

use crate::reports::ray_tree;

use super::super::state::{LessonState, SideState, Which};
use super::expect::{Expect, Value};

/// A render setting, by its `workbench render` flag's name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Setting {
    Width,
    Height,
    Depth,
    Aa,
    Spp,
    SamplesPerPixel,
    SoftShadows,
    LightSize,
    Dof,
    Aperture,
    Focal,
    Ambient,
    Accel,
    GridM,
    Seed,
    /// `uniform` or `adaptive`.
    Sampling,
    /// Adaptive sampling's noise threshold; off with uniform sampling.
    NoiseThreshold,
}

pub(super) const SETTINGS: [(&str, Setting); 17] = [
    ("width", Setting::Width),
    ("height", Setting::Height),
    ("depth", Setting::Depth),
    ("aa", Setting::Aa),
    ("spp", Setting::Spp),
    ("samples-per-pixel", Setting::SamplesPerPixel),
    ("soft-shadows", Setting::SoftShadows),
    ("light-size", Setting::LightSize),
    ("dof", Setting::Dof),
    ("aperture", Setting::Aperture),
    ("focal", Setting::Focal),
    ("ambient", Setting::Ambient),
    ("accel", Setting::Accel),
    ("grid-m", Setting::GridM),
    ("seed", Setting::Seed),
    ("sampling", Setting::Sampling),
    ("noise-threshold", Setting::NoiseThreshold),
];

/// A field of an object or a material.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    Kd,
    Ks,
    Shine,
    Transmittance,
    Ior,
    /// A sphere's radius.
    Radius,
    /// What it is: sphere, plane, triangle, polygon, box, ...
    Kind,
}

const FIELDS: [(&str, Field); 7] = [
    ("kd", Field::Kd),
    ("ks", Field::Ks),
    ("shine", Field::Shine),
    ("t", Field::Transmittance),
    ("ior", Field::Ior),
    ("radius", Field::Radius),
    ("kind", Field::Kind),
];

/// A figure of the pinned pixel's ray tree (sample 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TreeFigure {
    /// Rays of every kind.
    Rays,
    ShadowRays,
    BlockedShadowRays,
    Reflections,
    Refractions,
    /// Rays that left the scene.
    Misses,
    /// The deepest bounce (0: the eye ray alone).
    Depth,
    /// Whether a refraction was lost to total internal reflection.
    Tir,
    /// The object the eye ray hit, by index (`none` on a miss).
    EyeObject,
    /// Its kind (`triangle` for a three-sided polygon).
    EyeKind,
    /// The eye ray's distance to its hit.
    EyeT,
    /// Whether the eye ray arrived from outside the surface it hit.
    EyeOutside,
}

pub(super) const TREE_FIGURES: [(&str, TreeFigure); 12] = [
    ("rays", TreeFigure::Rays),
    ("shadow-rays", TreeFigure::ShadowRays),
    ("blocked-shadow-rays", TreeFigure::BlockedShadowRays),
    ("reflections", TreeFigure::Reflections),
    ("refractions", TreeFigure::Refractions),
    ("misses", TreeFigure::Misses),
    ("depth", TreeFigure::Depth),
    ("tir", TreeFigure::Tir),
    ("eye-object", TreeFigure::EyeObject),
    ("eye-kind", TreeFigure::EyeKind),
    ("eye-t", TreeFigure::EyeT),
    ("eye-outside", TreeFigure::EyeOutside),
];

/// A numbered part of the scene that a quantity, or a check's reference,
/// names: validated against the scene when the lesson loads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Part {
    Object(usize),
    Material(usize),
    Light(usize),
}

/// Something a check reads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Quantity {
    Setting(Setting),
    /// `object N FIELD`.
    Object(usize, Field),
    /// `material M FIELD`.
    Material(usize, Field),
    /// `objects`: how many the scene has.
    Objects,
    /// `lights`.
    Lights,
    /// `camera distance`: from the eye to `at`, the view-plane distance.
    CameraDistance,
    /// `camera angle`: the vertical field of view in degrees.
    CameraAngle,
    /// `observer`: whether the observer view is open (the window's layout).
    Observer,
    /// `view`: the image view shown (`shaded`, `tests`, `shadow`, ...).
    View,
    /// `focus-error N`: how far the plane in focus is from object N's
    /// centre, as a fraction of the object's distance along the view.
    FocusError(usize),
    /// `tree FIGURE`.
    Tree(TreeFigure),
    /// `tree blocker L`: the object blocking the first shadow ray towards
    /// light L (`none` when all of them are lit).
    Blocker(usize),
    /// `grid cells`: nx * ny * nz of the grid side A's m builds.
    GridCells,
    /// `grid nx`, `grid ny`, `grid nz`.
    GridAxis(usize),
    /// `eye steps`: cells or nodes the pinned pixel's eye ray walked with
    /// the side's structure.
    EyeSteps,
    /// `eye tests`: its ray-primitive tests with the side's structure.
    EyeTests,
    /// `brute-force tests`: what one ray tests with no structure (every
    /// shape).
    BruteForceTests,
    /// `pixel samples`: the samples the pinned pixel took in the side's
    /// render, as its film counted them (adaptive sampling's decisions).
    PixelSamples,
    /// `samples mean`: the side's render's samples per pixel, on average.
    SamplesMean,
    /// `samples max`: the most samples one pixel of the render took.
    SamplesMax,
}

fn lookup<T: Copy>(table: &[(&str, T)], word: &str, what: &str) -> Result<T, String> {
    table
        .iter()
        .find(|(name, _)| *name == word)
        .map(|&(_, v)| v)
        .ok_or_else(|| {
            let names: Vec<&str> = table.iter().map(|(n, _)| *n).collect();
            format!("no {what} `{word}`; expected one of {}", names.join(", "))
        })
}

fn index(word: Option<&str>, what: &str) -> Result<usize, String> {
    word.and_then(|w| w.parse().ok())
        .ok_or_else(|| format!("expected {what} number (from 0)"))
}

impl Quantity {
    /// Reads a quantity's name; the error lists what exists.
    pub(crate) fn parse(text: &str) -> Result<Quantity, String> {
        let words: Vec<&str> = text.split_whitespace().collect();
        let quantity = match words.as_slice() {
            ["objects"] => Quantity::Objects,
            ["lights"] => Quantity::Lights,
            ["camera", "distance"] => Quantity::CameraDistance,
            ["camera", "angle"] => Quantity::CameraAngle,
            ["observer"] => Quantity::Observer,
            ["view"] => Quantity::View,
            ["focus-error", n] => Quantity::FocusError(index(Some(n), "an object")?),
            ["object", n, field] => {
                Quantity::Object(index(Some(n), "an object")?, lookup(&FIELDS, field, "field")?)
            }
            ["material", n, field] => {
                let field = lookup(&FIELDS, field, "field")?;
                if matches!(field, Field::Radius | Field::Kind) {
                    return Err(format!("a material has no `{text}`; objects have it"));
                }
                Quantity::Material(index(Some(n), "a material")?, field)
            }
            ["tree", "blocker", light] => Quantity::Blocker(index(Some(light), "a light")?),
            ["tree", figure] => Quantity::Tree(lookup(&TREE_FIGURES, figure, "tree figure")?),
            ["grid", "cells"] => Quantity::GridCells,
            ["grid", axis] => Quantity::GridAxis(lookup(
                &[("nx", 0), ("ny", 1), ("nz", 2)],
                axis,
                "grid figure (cells, nx, ny, nz)",
            )?),
            ["eye", "steps"] => Quantity::EyeSteps,
            ["eye", "tests"] => Quantity::EyeTests,
            ["brute-force", "tests"] => Quantity::BruteForceTests,
            ["pixel", "samples"] => Quantity::PixelSamples,
            ["samples", "mean"] => Quantity::SamplesMean,
            ["samples", "max"] => Quantity::SamplesMax,
            [setting] => Quantity::Setting(lookup(&SETTINGS, setting, "setting").map_err(|e| {
                format!(
                    "{e}; or objects, lights, camera distance, camera angle, observer, view, focus-error N, object N FIELD, \
                     material M FIELD, tree FIGURE, tree blocker L, grid cells, eye steps, \
                     eye tests, brute-force tests, pixel samples, samples mean, samples max"
                )
            })?),
            _ => {
                return Err(format!(
                    "`{text}` names nothing to read; expected a setting (spp, accel, ...), \
                     objects, lights, camera distance, camera angle, observer, view, focus-error N, object N FIELD, \
                     material M FIELD, tree FIGURE, tree blocker L, grid cells, eye steps, \
                     eye tests, brute-force tests, pixel samples, samples mean or samples max"
                ));
            }
        };
        Ok(quantity)
    }

    /// What kind of value it reads, for checking a lesson's `is` and
    /// choices when it loads and for saying its values in the format's
    /// words.
    pub(crate) fn reads(&self) -> Reads {
        match self {
            Quantity::Setting(Setting::Aa | Setting::SoftShadows | Setting::Dof) => Reads::OnOff,
            Quantity::Setting(Setting::Accel) => Reads::Word(vec!["none", "grid", "bvh"]),
            Quantity::Setting(Setting::Sampling) => Reads::Word(vec!["uniform", "adaptive"]),
            Quantity::Setting(Setting::NoiseThreshold) => Reads::NumberOrOff,
            Quantity::Object(_, Field::Kind) => Reads::Word(OBJECT_KINDS.to_vec()),
            Quantity::Tree(TreeFigure::EyeKind) => {
                Reads::Word(OBJECT_KINDS.iter().copied().chain(["none"]).collect())
            }
            Quantity::View => Reads::Word(View::ALL.iter().map(|v| v.name()).collect()),
            Quantity::Observer | Quantity::Tree(TreeFigure::Tir | TreeFigure::EyeOutside) => {
                Reads::YesNo
            }
            Quantity::Tree(TreeFigure::EyeObject) | Quantity::Blocker(_) => Reads::ObjectOrNone,
            _ => Reads::Number,
        }
    }

    /// The part of the scene it names and which of its words is the
    /// number: `object 3 kd` names object 3 in word 1.
    pub(crate) fn part(&self) -> Option<(Part, usize)> {
        match *self {
            Quantity::Object(n, _) | Quantity::FocusError(n) => Some((Part::Object(n), 1)),
            Quantity::Material(n, _) => Some((Part::Material(n), 1)),
            Quantity::Blocker(light) => Some((Part::Light(light), 2)),
            _ => None,
        }
    }

    /// Its value in `state`, on side `which`; why it cannot be read
    /// otherwise (no side B, no pixel pinned, no such object).
    pub(crate) fn read(&self, state: &LessonState, which: Which) -> Result<Value, String> {
        let side = state.side(which)?;
        let pixel = || state.pixel.ok_or_else(|| "no pixel is pinned".to_string());
        match *self {
            Quantity::Observer => Ok(Value::Bool(state.layout.observer)),
            Quantity::View => Ok(Value::Word(
                state.layout.view.unwrap_or(View::Shaded).name().to_string(),
            )),
            Quantity::CameraAngle => Ok(Value::Number(f64::from(side.scene.view.angle))),
            Quantity::Setting(setting) => Ok(read_setting(side, setting)),
            Quantity::Object(n, field) => read_object(&side.scene, n, field),
            Quantity::Material(n, field) => {
                let material = side.scene.materials.get(n).ok_or_else(|| {
                    format!(
                        "the scene has {} materials, no material {n}",
                        side.scene.materials.len()
                    )
                })?;
                material_field(material, field)
            }
            Quantity::Objects => Ok(count(side.scene.objects.len())),
            Quantity::Lights => Ok(count(side.scene.lights.len())),
            Quantity::CameraDistance => {
                let view = &side.scene.view;
                Ok(Value::Number(f64::from((view.at - view.from).length())))
            }
            Quantity::FocusError(n) => focus_error(side, n),
            Quantity::Tree(_) | Quantity::Blocker(_) => {
                let tree = record_tree(side, pixel()?)?;
                (self.read_tree(&side.scene, &tree))
                    .ok_or_else(|| format!("{self} is not a tree figure"))
            }
            Quantity::GridCells | Quantity::GridAxis(_) => {
                let grid = SceneIndex::build(
                    &side.world.shapes,
                    AccelKind::Grid,
                    side.settings.grid_multiplier,
                );
                let cells = grid.info().grid.map_or([0; 3], |g| g.cells);
                Ok(match *self {
                    Quantity::GridAxis(axis) => count(cells[axis] as usize),
                    _ => Value::Number(cells.iter().map(|&c| f64::from(c)).product()),
                })
            }
            Quantity::EyeSteps | Quantity::EyeTests => {
                let tree = record_tree(side, pixel()?)?;
                let eye = tree
                    .nodes
                    .first()
                    .filter(|n| n.kind == RayKind::Eye)
                    .ok_or("the pinned pixel has no eye ray")?;
                let index = SceneIndex::build(
                    &side.world.shapes,
                    side.settings.accel,
                    side.settings.grid_multiplier,
                );
                let hither = side
                    .settings
                    .render_camera(&side.world.view)
                    .map_err(|e| e.to_string())?
                    .hither();
                let ray = Ray::new(eye.origin, eye.dir);
                let walk =
                    index.closest_hit_visits(&side.world.shapes, &ray, hither, f32::INFINITY);
                Ok(match self {
                    Quantity::EyeSteps => count(walk.visits.len()),
                    _ => Value::Number(walk.counters.intersection_tests as f64),
                })
            }
            Quantity::BruteForceTests => Ok(count(side.world.shapes.len())),
            Quantity::PixelSamples => {
                let (x, y) = pixel()?;
                let film = rendered_film(side)?;
                if x >= film.width() || y >= film.height() {
                    return Err(format!(
                        "the pinned pixel ({x}, {y}) is outside the {}x{} image",
                        film.width(),
                        film.height()
                    ));
                }
                Ok(count(film.samples(x, y) as usize))
            }
            Quantity::SamplesMean | Quantity::SamplesMax => {
                let film = rendered_film(side)?;
                let counts = (0..film.height())
                    .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
                    .map(|(x, y)| f64::from(film.samples(x, y)));
                Ok(Value::Number(match self {
                    Quantity::SamplesMax => counts.fold(0.0, f64::max),
                    _ => counts.sum::<f64>() / f64::from(film.width() * film.height()).max(1.0),
                }))
            }
        }
    }
}

impl Quantity {
    /// A tree figure (`tree ...`, `tree blocker L`) read from a tree
    /// already recorded on `scene`, so that `lesson explain --find` records
    /// each pixel's tree once; `None` for any other quantity.
    pub(crate) fn read_tree(&self, scene: &Scene, tree: &RayTree) -> Option<Value> {
        match *self {
            Quantity::Tree(figure) => Some(tree_figure(scene, tree, figure)),
            Quantity::Blocker(light) => Some(blocker(tree, light)),
            _ => None,
        }
    }
}

impl Display for Quantity {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match *self {
            Quantity::Setting(s) => f.write_str(name(&SETTINGS, s)),
            Quantity::Object(n, field) => write!(f, "object {n} {}", name(&FIELDS, field)),
            Quantity::Material(n, field) => write!(f, "material {n} {}", name(&FIELDS, field)),
            Quantity::Objects => f.write_str("objects"),
            Quantity::Lights => f.write_str("lights"),
            Quantity::CameraDistance => f.write_str("camera distance"),
            Quantity::CameraAngle => f.write_str("camera angle"),
            Quantity::Observer => f.write_str("observer"),
            Quantity::View => f.write_str("view"),
            Quantity::FocusError(n) => write!(f, "focus-error {n}"),
            Quantity::Tree(figure) => write!(f, "tree {}", name(&TREE_FIGURES, figure)),
            Quantity::Blocker(light) => write!(f, "tree blocker {light}"),
            Quantity::GridCells => f.write_str("grid cells"),
            Quantity::GridAxis(axis) => write!(f, "grid n{}", ["x", "y", "z"][axis]),
            Quantity::EyeSteps => f.write_str("eye steps"),
            Quantity::EyeTests => f.write_str("eye tests"),
            Quantity::BruteForceTests => f.write_str("brute-force tests"),
            Quantity::PixelSamples => f.write_str("pixel samples"),
            Quantity::SamplesMean => f.write_str("samples mean"),
            Quantity::SamplesMax => f.write_str("samples max"),
        }
    }
}

/// What `object N kind` and `tree eye-kind` read: a three-sided polygon
/// is a triangle.
const OBJECT_KINDS: [&str; 8] = [
    "sphere", "plane", "triangle", "polygon", "patch", "box", "cone", "mesh",
];

/// What kind of value a quantity reads.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Reads {
    Number,
    /// A switch: on or off.
    OnOff,
    /// A fact: yes or no.
    YesNo,
    /// One of these words.
    Word(Vec<&'static str>),
    /// An object's number, or `none`.
    ObjectOrNone,
    /// A number, or `off` (the noise threshold under uniform sampling).
    NumberOrOff,
}

impl Reads {
    /// Whether a tolerance means something for it.
    pub(crate) fn is_numeric(&self) -> bool {
        matches!(self, Reads::Number | Reads::NumberOrOff)
    }

    /// Its values in the lesson format's words.
    pub(crate) fn words(&self) -> String {
        match self {
            Reads::Number => "a number".into(),
            Reads::OnOff => "on or off".into(),
            Reads::YesNo => "yes or no".into(),
            Reads::Word(words) => format!("one of {}", words.join(", ")),
            Reads::ObjectOrNone => "an object's number or none".into(),
            Reads::NumberOrOff => "a number or off".into(),
        }
    }

    /// Whether `expect` can hold for one of its values; the error says
    /// what it is and what to write.
    pub(crate) fn accepts(&self, expect: &Expect) -> Result<(), String> {
        let comparison = !matches!(expect, Expect::Is(_));
        let fits = match (self, expect) {
            (Reads::Number | Reads::NumberOrOff, _) if comparison => true,
            (Reads::Number, Expect::Is(Value::Number(_))) => true,
            (Reads::NumberOrOff, Expect::Is(Value::Number(_) | Value::Bool(false))) => true,
            (Reads::OnOff | Reads::YesNo, Expect::Is(Value::Bool(_))) => true,
            (Reads::Word(words), Expect::Is(Value::Word(w))) => words.contains(&w.as_str()),
            (Reads::ObjectOrNone, Expect::Is(Value::Number(n))) => n.fract() == 0.0 && *n >= 0.0,
            (Reads::ObjectOrNone, Expect::Is(Value::Word(w))) => w == "none",
            _ => false,
        };
        if fits {
            return Ok(());
        }
        let hint = match self {
            Reads::Number | Reads::NumberOrOff => {
                "; write a number, or a comparison such as `>= 5` or `1.5 +- 2%`"
            }
            _ => "",
        };
        Err(format!(
            "is {}: `{}` can never match it{hint}",
            self.words(),
            self.show_expect(expect)
        ))
    }

    /// A value as the format says it: yes/no for facts, on/off for
    /// switches.
    pub(crate) fn show(&self, value: &Value) -> String {
        match (self, value) {
            (Reads::YesNo, Value::Bool(true)) => "yes".into(),
            (Reads::YesNo, Value::Bool(false)) => "no".into(),
            _ => value.to_string(),
        }
    }

    /// An expectation in the same words.
    pub(crate) fn show_expect(&self, expect: &Expect) -> String {
        match expect {
            Expect::Is(value) => self.show(value),
            other => other.to_string(),
        }
    }
}

/// The name `v` has in `table`.
fn name<T: PartialEq>(table: &[(&'static str, T)], v: T) -> &'static str {
    table.iter().find(|(_, x)| *x == v).map_or("?", |(n, _)| *n)
}

fn count(n: usize) -> Value {
    Value::Number(n as f64)
}

fn read_setting(side: &SideState, setting: Setting) -> Value {
    let s = &side.settings;
    let number = |v: f32| Value::Number(f64::from(v));
    match setting {
        Setting::Width => count(s.width as usize),
        Setting::Height => count(s.height as usize),
        Setting::Depth => count(s.max_depth as usize),
        Setting::Aa => Value::Bool(s.antialiasing),
        Setting::Spp => count(s.samples as usize),
        Setting::SamplesPerPixel => count(s.samples_per_pixel() as usize),
        Setting::SoftShadows => Value::Bool(s.soft_shadows),
        Setting::LightSize => number(s.light_size),
        Setting::Dof => Value::Bool(s.depth_of_field),
        Setting::Aperture => number(s.chosen_lens(&side.scene.view).aperture),
        Setting::Focal => number(s.chosen_lens(&side.scene.view).focal),
        Setting::Ambient => number(s.ambient),
        Setting::Accel => Value::Word(s.accel.name().to_string()),
        Setting::GridM => number(s.grid_multiplier),
        Setting::Seed => Value::Number(s.seed as f64),
        Setting::Sampling => Value::Word(
            match s.sampling {
                Sampling::Uniform => "uniform",
                Sampling::Adaptive(_) => "adaptive",
            }
            .to_string(),
        ),
        Setting::NoiseThreshold => match s.sampling {
            Sampling::Uniform => Value::Bool(false),
            Sampling::Adaptive(a) => number(a.noise_threshold),
        },
    }
}

/// An object's kind as a student names it: a three-sided polygon is a
/// triangle.
fn kind_of(primitive: &Primitive) -> &'static str {
    match primitive {
        Primitive::Polygon { vertices } | Primitive::Patch { vertices, .. }
            if vertices.len() == 3 =>
        {
            "triangle"
        }
        other => other.kind(),
    }
}

fn read_object(scene: &Scene, n: usize, field: Field) -> Result<Value, String> {
    let object = scene.objects.get(n).ok_or_else(|| {
        format!(
            "the scene has {} objects, no object {n}",
            scene.objects.len()
        )
    })?;
    match (field, &object.primitive) {
        (Field::Kind, primitive) => Ok(Value::Word(kind_of(primitive).to_string())),
        (Field::Radius, Primitive::Sphere { radius, .. }) => Ok(Value::Number(f64::from(*radius))),
        (Field::Radius, other) => Err(format!(
            "object {n} is a {}: it has no radius",
            other.kind()
        )),
        (field, _) => {
            let material = scene
                .materials
                .get(object.material as usize)
                .ok_or_else(|| format!("object {n} has no material"))?;
            material_field(material, field)
        }
    }
}

fn material_field(material: &tracer::scene::Material, field: Field) -> Result<Value, String> {
    let v = match field {
        Field::Kd => material.kd,
        Field::Ks => material.ks,
        Field::Shine => material.shine,
        Field::Transmittance => material.transmittance,
        Field::Ior => material.ior,
        Field::Radius | Field::Kind => return Err("not a material field".into()),
    };
    Ok(Value::Number(f64::from(v)))
}

/// |plane in focus - object's depth| / object's depth, depths measured
/// along the view direction from the eye: the plane in focus lies at
/// `focal` times the view-plane distance `|at - from|`.
fn focus_error(side: &SideState, n: usize) -> Result<Value, String> {
    let scene = &side.scene;
    let object = scene.objects.get(n).ok_or_else(|| {
        format!(
            "the scene has {} objects, no object {n}",
            scene.objects.len()
        )
    })?;
    let centre = match &object.primitive {
        Primitive::Sphere { centre, .. } => *centre,
        Primitive::Box { min, max } => (*min + *max) * 0.5,
        other => {
            return Err(format!(
                "object {n} is a {}: focus on a sphere or box",
                other.kind()
            ));
        }
    };
    let view = &scene.view;
    let axis = (view.at - view.from).normalize_or_zero();
    let depth = (centre - view.from).dot(axis);
    if depth <= 0.0 {
        return Err(format!("object {n} is behind the camera"));
    }
    let in_focus = side.settings.chosen_lens(view).focal * (view.at - view.from).length();
    Ok(Value::Number(f64::from((in_focus - depth).abs() / depth)))
}

/// The side rendered to the end, as `workbench render` renders it: its
/// film counts every pixel's samples.
fn rendered_film(side: &SideState) -> Result<Film, String> {
    let index = Arc::new(SceneIndex::build(
        &side.world.shapes,
        side.settings.accel,
        side.settings.grid_multiplier,
    ));
    render(side.world.clone(), index, side.settings.clone(), None)
        .map(|(film, _)| film)
        .map_err(|e| e.to_string())
}

/// The pinned pixel's tree, sample 0, under the side's settings.
fn record_tree(side: &SideState, (x, y): (u32, u32)) -> Result<RayTree, String> {
    ray_tree::inspect(
        &side.world,
        None::<Arc<SceneIndex>>,
        &side.settings,
        (x, y),
        0,
    )
    .map_err(|e| format!("{e:#}"))
}

fn tree_figure(scene: &Scene, tree: &RayTree, figure: TreeFigure) -> Value {
    let nodes = &tree.nodes;
    let of_kind = |kind: RayKind| count(nodes.iter().filter(|n| n.kind == kind).count());
    let eye_hit = nodes
        .first()
        .filter(|n| n.kind == RayKind::Eye)
        .and_then(|n| match &n.outcome {
            Outcome::Surface(s) => Some(s),
            _ => None,
        });
    let none = || Value::Word("none".into());
    match figure {
        TreeFigure::Rays => count(nodes.len()),
        TreeFigure::ShadowRays => of_kind(RayKind::Shadow),
        TreeFigure::BlockedShadowRays => count(
            nodes
                .iter()
                .filter(|n| {
                    matches!(
                        n.outcome,
                        Outcome::Light {
                            occluder: Some(_),
                            ..
                        }
                    )
                })
                .count(),
        ),
        TreeFigure::Reflections => of_kind(RayKind::Reflection),
        TreeFigure::Refractions => of_kind(RayKind::Refraction),
        TreeFigure::Misses => count(
            nodes
                .iter()
                .filter(|n| n.outcome == Outcome::Background)
                .count(),
        ),
        TreeFigure::Depth => count(nodes.iter().map(|n| n.depth).max().unwrap_or(0) as usize),
        TreeFigure::Tir => Value::Bool(nodes.iter().any(
            |n| matches!(&n.outcome, Outcome::Surface(s) if s.fresnel.is_some_and(|(_, tir)| tir)),
        )),
        TreeFigure::EyeObject => eye_hit.map_or_else(none, |s| count(s.object as usize)),
        TreeFigure::EyeKind => eye_hit.map_or_else(none, |s| {
            let kind = scene
                .objects
                .get(s.object as usize)
                .map_or(s.object_kind, |o| kind_of(&o.primitive));
            Value::Word(kind.to_string())
        }),
        TreeFigure::EyeT => eye_hit.map_or_else(none, |s| Value::Number(f64::from(s.t))),
        TreeFigure::EyeOutside => eye_hit.map_or_else(none, |s| Value::Bool(s.outside)),
    }
}

/// The object blocking the first blocked shadow ray towards `light` from
/// the eye ray's hit, `none` when all of them are lit (or there are none).
fn blocker(tree: &RayTree, light: usize) -> Value {
    tree.children(Some(0))
        .find_map(|i| match &tree.nodes[i].outcome {
            Outcome::Light {
                light: l,
                occluder: Some(o),
                ..
            } if *l == light => Some(count(o.object as usize)),
            _ => None,
        })
        .unwrap_or_else(|| Value::Word("none".into()))
}
