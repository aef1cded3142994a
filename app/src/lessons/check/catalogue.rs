//! Every quantity a check can read on a scene, in the order of the
//! format's table: what `workbench lesson explain` lists with its value,
//! so a teacher sees the names and their current values side by side.

use tracer::scene::{Primitive, Scene};

use super::quantity::{Field, Quantity, SETTINGS, TREE_FIGURES};

/// How many objects and materials are listed one by one; past that the
/// list says how many more there are (a mesh scene has thousands).
pub(crate) const LISTED_PARTS: usize = 16;

/// The quantities readable on `scene` without a pinned pixel: settings,
/// counts, the camera, the layout, the first [`LISTED_PARTS`] objects and
/// materials, the grid, the structure's brute-force cost and the samples a
/// render takes.
pub(crate) fn without_pixel(scene: &Scene) -> Vec<Quantity> {
    let mut list: Vec<Quantity> = SETTINGS
        .iter()
        .map(|&(_, s)| Quantity::Setting(s))
        .collect();
    list.extend([
        Quantity::Objects,
        Quantity::Lights,
        Quantity::CameraAngle,
        Quantity::CameraDistance,
        Quantity::Observer,
        Quantity::View,
    ]);
    for (n, object) in scene.objects.iter().enumerate().take(LISTED_PARTS) {
        list.push(Quantity::Object(n, Field::Kind));
        match object.primitive {
            Primitive::Sphere { .. } => {
                list.push(Quantity::Object(n, Field::Radius));
                list.push(Quantity::FocusError(n));
            }
            Primitive::Box { .. } => list.push(Quantity::FocusError(n)),
            _ => {}
        }
    }
    for m in 0..scene.materials.len().min(LISTED_PARTS) {
        list.extend(MATERIAL_FIELDS.map(|field| Quantity::Material(m, field)));
    }
    list.extend([
        Quantity::GridCells,
        Quantity::GridAxis(0),
        Quantity::GridAxis(1),
        Quantity::GridAxis(2),
        Quantity::BruteForceTests,
        Quantity::SamplesMean,
        Quantity::SamplesMax,
    ]);
    list
}

/// The quantities that read the pinned pixel: its ray tree's figures, the
/// blocker of each light, its eye ray's walk, its samples.
pub(crate) fn at_pixel(scene: &Scene) -> Vec<Quantity> {
    let mut list: Vec<Quantity> = TREE_FIGURES
        .iter()
        .map(|&(_, f)| Quantity::Tree(f))
        .collect();
    list.extend((0..scene.lights.len()).map(Quantity::Blocker));
    list.extend([
        Quantity::EyeSteps,
        Quantity::EyeTests,
        Quantity::PixelSamples,
    ]);
    list
}

/// A material's fields, as `material M FIELD` reads them.
const MATERIAL_FIELDS: [Field; 5] = [
    Field::Kd,
    Field::Ks,
    Field::Shine,
    Field::Transmittance,
    Field::Ior,
];

#[cfg(test)]
mod tests {
    use super::*;
    use tracer::scene::{Limits, parse_scene};

    #[test]
    fn every_listed_quantity_reads_back_by_its_name() {
        let scene = parse_scene(
            "v from 0 0 5 at 0 0 0\nl 0 5 5 1 1 1\nf 1 0 0 1 0 0 0 0 1 0 1\ns 0 0 0 1\nbox 0 0 0 1 1 1\n",
            None,
            &Limits::default(),
        )
        .unwrap();
        let all: Vec<Quantity> = without_pixel(&scene)
            .into_iter()
            .chain(at_pixel(&scene))
            .collect();
        for quantity in &all {
            assert_eq!(
                Quantity::parse(&quantity.to_string()).as_ref(),
                Ok(quantity)
            );
        }
        assert!(all.contains(&Quantity::FocusError(1)), "{all:?}");
        assert!(all.contains(&Quantity::Blocker(0)), "{all:?}");
        assert_eq!(all.len(), 17 + 6 + 3 + 2 + 5 + 7 + 12 + 1 + 3);
    }
}
