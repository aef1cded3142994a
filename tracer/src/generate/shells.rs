//! A seashell of overlapping spheres (after SPD `shells.c`): spheres
//! strung along a conical logarithmic spiral, their radii growing a
//! thousandfold from the tip to the mouth, each overlapping hundreds of its
//! neighbours and the outer whorl enclosing part of the inner one. Many
//! overlapping primitives of very different sizes: the case where bounding
//! boxes overlap most and acceleration structures do worst.

use std::f64::consts::TAU;
use std::ops::RangeInclusive;

use glam::{DVec3, Vec3};

use super::common::{SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = density of the spheres along the same spiral: 45 * 2^level + 1
/// spheres (level 7: 5761, level 10: 46,081).
pub(super) const LEVELS: RangeInclusive<u32> = 1..=10;

/// Whorls from the tip to the mouth.
const TURNS: f64 = 3.0;
/// Sphere radius at the mouth over the radius at the tip.
const GROWTH: f64 = 1000.0;
/// Sphere radius over its centre's distance from the axis: above ~0.82
/// each whorl overlaps the next, so the shell looks closed.
const FATNESS: f64 = 0.9;
/// Drop along the axis per unit of distance from it: a conical shell.
const SLOPE: f64 = 0.8;
/// Distance of the mouth's centre from the axis.
const MOUTH: f64 = 2.0;

/// Spheres at `level`.
pub(super) fn sphere_count(level: u32) -> u64 {
    45 * (1u64 << level) + 1
}

pub(super) fn describe(level: u32) -> String {
    format!(
        "seashell of {} overlapping spheres on a spiral, radii over three decades, on a floor, 2 lights",
        sphere_count(level)
    )
}

/// The centre and radius of sphere `i` of `n`, from the tip (`i = 0`) to
/// the mouth (`i = n - 1`).
fn sphere(i: u64, n: u64) -> (DVec3, f64) {
    let s = i as f64 / (n - 1) as f64;
    let angle = s * TURNS * TAU;
    let distance = MOUTH * GROWTH.powf(s - 1.0);
    let centre = DVec3::new(
        distance * angle.cos(),
        distance * angle.sin(),
        MOUTH * SLOPE - distance * SLOPE,
    );
    (centre, FATNESS * distance)
}

pub(super) fn generate(level: u32) -> Scene {
    let view = spd_view(Vec3::new(5.0, -6.5, 6.0), Vec3::new(-0.3, 0.0, 0.6));
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    b.light(Vec3::new(6.0, -8.0, 12.0));
    b.light(Vec3::new(-8.0, -3.0, 7.0));

    // A floor just under the lowest point of the mouth sphere.
    let floor = -(MOUTH * FATNESS) as f32;
    b.material(material(
        Vec3::new(0.6, 0.6, 0.55),
        0.8,
        0.0,
        10.0,
        0.0,
        1.0,
    ));
    b.add(Primitive::Polygon {
        vertices: [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
            .map(|(x, y)| Vec3::new(x * 12.0, y * 12.0, floor))
            .to_vec(),
    });

    b.material(material(
        Vec3::new(1.0, 0.75, 0.55),
        0.7,
        0.3,
        40.0,
        0.0,
        1.0,
    ));
    let n = sphere_count(level);
    b.reserve(n as usize);
    for i in 0..n {
        let (centre, radius) = sphere(i, n);
        b.add(Primitive::Sphere {
            centre: centre.as_vec3(),
            radius: radius as f32,
            inside_only: false,
        });
    }
    b.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::counts;

    #[test]
    fn counts_per_level() {
        assert_eq!(sphere_count(7), 5761);
        for level in [1, 3] {
            let n = sphere_count(level) as usize;
            assert_eq!(counts(&generate(level)), (n, 0, 1, 0));
        }
    }

    #[test]
    fn radii_span_three_decades_and_neighbours_overlap() {
        let n = sphere_count(1);
        let (_, tip) = sphere(0, n);
        let (_, mouth) = sphere(n - 1, n);
        assert!((mouth / tip - GROWTH).abs() < 1e-6 * GROWTH);
        for i in 1..n {
            let (a, ra) = sphere(i - 1, n);
            let (b, rb) = sphere(i, n);
            assert!(
                a.distance(b) < ra + rb,
                "spheres {} and {i} are apart",
                i - 1
            );
        }
    }
}
