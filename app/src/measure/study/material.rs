//! The material study (`--param object:N:FIELD`): one object's material
//! field swept over values. Each point is the scene with that edit, its
//! world updated from the unedited one ([`World::update`]: only the
//! surfaces change), so every point traces the structure built for the
//! first.

use std::sync::Arc;

use anyhow::{Context, Result, bail};
use tracer::render::RenderSettings;
use tracer::scene::Scene;
use tracer::scene::edit::{Edit, MaterialField};
use tracer::world::World;

use super::{Batch, Param, Study, StudyEvent, StudyOutcome, point_case, values};
use crate::measure::benchmark::{Stop, Structures};

/// A numeric field of the P3F material line that a study can sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(crate) enum Knob {
    Kd,
    Ks,
    Shine,
    Transmittance,
    Ior,
}

impl Knob {
    pub(crate) const ALL: [Knob; 5] = [
        Knob::Kd,
        Knob::Ks,
        Knob::Shine,
        Knob::Transmittance,
        Knob::Ior,
    ];
    /// The names, as `--set` spells the fields.
    pub(crate) const NAMES: [&str; 5] = ["kd", "ks", "shine", "t", "ior"];

    pub(crate) fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The x axis of its chart.
    pub(crate) fn axis(self) -> &'static str {
        match self {
            Knob::Kd => "Kd (diffuse weight)",
            Knob::Ks => "Ks (highlight and mirror weight)",
            Knob::Shine => "shine (Blinn-Phong exponent)",
            Knob::Transmittance => "T (transmittance)",
            Knob::Ior => "index of refraction",
        }
    }

    /// The field at `value`.
    pub(crate) fn with(self, value: f32) -> MaterialField {
        match self {
            Knob::Kd => MaterialField::Kd(value),
            Knob::Ks => MaterialField::Ks(value),
            Knob::Shine => MaterialField::Shine(value),
            Knob::Transmittance => MaterialField::Transmittance(value),
            Knob::Ior => MaterialField::Ior(value),
        }
    }

    /// Values worth a first look.
    pub(crate) fn default_values(self) -> &'static str {
        match self {
            Knob::Kd | Knob::Ks | Knob::Transmittance => "0..1:0.1",
            Knob::Shine => "1..1024:x2",
            Knob::Ior => "1..2:0.05",
        }
    }
}

/// `N:FIELD` after `object:`.
pub(super) fn parse(text: &str) -> Result<Param, String> {
    let syntax = || {
        format!(
            "`object:{text}` is not object:N:FIELD with FIELD one of {}",
            Knob::NAMES.join(", ")
        )
    };
    let (object, field) = text.split_once(':').ok_or_else(syntax)?;
    let object = object.trim().parse().map_err(|_| syntax())?;
    let field = Knob::ALL
        .into_iter()
        .find(|k| k.name() == field.trim())
        .ok_or_else(syntax)?;
    Ok(Param::Material { object, field })
}

/// Every point's edit must apply to `scene`: the object exists and the
/// value is one the parser would take (T in 0..1, ior > 0 for glass).
pub(super) fn check(study: &Study, scene: &Scene) -> Result<()> {
    for &value in &study.values {
        edited(study.param, scene, value)?;
    }
    Ok(())
}

/// The scene with `param` at `value`, and the edit that made it.
fn edited(param: Param, scene: &Scene, value: f64) -> Result<(Scene, Edit)> {
    let Some(edit) = param.edit(value) else {
        bail!("{param} is not a material parameter");
    };
    let mut scene = scene.clone();
    edit.apply(&mut scene)
        .with_context(|| format!("{param} = {}", values::format(value)))?;
    Ok((scene, edit))
}

/// Measures every point in [`Study::plan`] order, each over the scene with
/// its edit; the structures are built over the first point's shapes and
/// kept, since a material edit moves none.
pub(super) fn run(
    study: &Study,
    scene: &Scene,
    world: &Arc<World>,
    base: &RenderSettings,
    stop: Stop,
    on_event: &mut dyn FnMut(StudyEvent),
) -> Result<StudyOutcome> {
    let mut structures = Structures::default();
    let mut outcome = StudyOutcome::default();
    for (point, (accel, value)) in study.plan().into_iter().enumerate() {
        let (scene, edit) = edited(study.param, scene, value)?;
        let mut edited = (**world).clone();
        edited.update(&scene, &edit);
        let world = Arc::new(edited);
        let batch = Batch {
            world: &world,
            cases: &[point_case(study, base, accel, value)],
            first: point,
            x: None,
            values: vec![value],
            reference: None,
        };
        batch.measure(study.options, &mut structures, stop, &mut outcome, on_event)?;
        if outcome.cancelled {
            break;
        }
    }
    Ok(outcome)
}
