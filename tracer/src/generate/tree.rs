//! A recursive tree (after SPD `tree.c` and Aono and Kunii's botanical
//! trees): every branch is a tapering cone that forks into two shorter,
//! thinner branches at its tip, rotated by the golden divergence angle and
//! jittered by the seed; joints get a sphere to hide the seams, the last
//! generation ends in leaf spheres. It stands on a square of ground.

use std::ops::RangeInclusive;

use glam::{DQuat, DVec3, Vec3};

use super::common::{Rng, SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = generations of branches; 2^level - 1 cones (level 16: 65,535).
pub(super) const LEVELS: RangeInclusive<u32> = 1..=16;

const TRUNK_LENGTH: f64 = 1.2;
const TRUNK_RADIUS: f64 = 0.1;
/// Radius at a branch's tip over its base radius.
const TAPER: f64 = 0.7;
/// Golden angle between successive forks, so branches fill space evenly.
const DIVERGENCE: f64 = 137.5;
/// Pull towards +z, so branches reach up rather than droop.
const UPWARD: f64 = 0.15;
const GROUND: f32 = 6.0;

/// (cones, joint spheres, leaves).
pub(super) fn counts(level: u32) -> (u64, u64, u64) {
    let tips = 1u64 << (level - 1);
    (2 * tips - 1, tips - 1, tips)
}

pub(super) fn describe(level: u32) -> String {
    let (cones, joints, leaves) = counts(level);
    format!(
        "tree of {cones} branch cones, {joints} joint spheres and {leaves} leaf spheres on the ground, 2 lights"
    )
}

struct Branches<'a> {
    rng: &'a mut Rng,
    level: u32,
    bark: Vec<Primitive>,
    leaves: Vec<Primitive>,
}

impl Branches<'_> {
    fn grow(&mut self, generation: u32, base: DVec3, dir: DVec3, length: f64, radius: f64) {
        let apex = base + dir * length;
        let top = radius * TAPER;
        self.bark.push(Primitive::Cone {
            base: base.as_vec3(),
            base_radius: radius as f32,
            apex: apex.as_vec3(),
            apex_radius: top as f32,
        });
        if generation + 1 == self.level {
            self.leaves.push(Primitive::Sphere {
                centre: apex.as_vec3(),
                radius: (0.6 * length).max(top * 2.0) as f32,
                inside_only: false,
            });
            return;
        }
        self.bark.push(Primitive::Sphere {
            centre: apex.as_vec3(),
            radius: top as f32,
            inside_only: false,
        });
        let phase = (DIVERGENCE * generation as f64 + self.rng.range(-20.0, 20.0)).to_radians();
        let side = DQuat::from_axis_angle(dir, phase) * dir.any_orthonormal_vector();
        for (angle, shrink) in [(28.0, 0.78), (-38.0, 0.68)] {
            let bend = (angle + self.rng.range(-8.0, 8.0)).to_radians();
            let child = (DQuat::from_axis_angle(side, bend) * dir + DVec3::Z * UPWARD).normalize();
            let child_length = length * shrink * self.rng.range(0.9, 1.1);
            self.grow(generation + 1, apex, child, child_length, top);
        }
    }
}

pub(super) fn generate(level: u32, seed: u64) -> Scene {
    let view = spd_view(Vec3::new(5.5, -6.0, 2.6), Vec3::new(0.0, 0.0, 1.8));
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    b.light(Vec3::new(5.0, -5.0, 10.0));
    b.light(Vec3::new(-6.0, -2.0, 6.0));

    b.material(material(
        Vec3::new(0.45, 0.55, 0.25),
        0.9,
        0.0,
        100.0,
        0.0,
        1.0,
    ));
    b.add(Primitive::Polygon {
        vertices: [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
            .map(|(x, y)| Vec3::new(x * GROUND, y * GROUND, 0.0))
            .to_vec(),
    });

    let mut rng = Rng::new(seed);
    let (cones, joints, leaves) = counts(level);
    let mut branches = Branches {
        rng: &mut rng,
        level,
        bark: Vec::with_capacity((cones + joints) as usize),
        leaves: Vec::with_capacity(leaves as usize),
    };
    branches.grow(0, DVec3::ZERO, DVec3::Z, TRUNK_LENGTH, TRUNK_RADIUS);
    let Branches { bark, leaves, .. } = branches;

    b.material(material(
        Vec3::new(0.45, 0.3, 0.15),
        0.9,
        0.05,
        20.0,
        0.0,
        1.0,
    ));
    b.reserve(bark.len() + leaves.len());
    bark.into_iter().for_each(|p| b.add(p));
    b.material(material(
        Vec3::new(0.2, 0.7, 0.15),
        0.8,
        0.1,
        40.0,
        0.0,
        1.0,
    ));
    leaves.into_iter().for_each(|p| b.add(p));
    b.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util;

    #[test]
    fn counts_per_level() {
        for level in [1, 2, 5, 10] {
            let (cones, joints, leaves) = counts(level);
            let scene = generate(level, 3);
            let got = test_util::counts(&scene);
            assert_eq!(got, ((joints + leaves) as usize, cones as usize, 1, 0));
        }
        assert_eq!(counts(16).0, 65_535);
    }

    #[test]
    fn stands_on_the_ground_within_reach() {
        for seed in 0..6 {
            let scene = generate(12, seed);
            for o in &scene.objects {
                if let Primitive::Cone {
                    base,
                    apex,
                    base_radius,
                    apex_radius,
                } = o.primitive
                {
                    assert!(base.z >= 0.0 && apex.z > 0.0 && apex.length() < 6.0);
                    assert!(apex_radius < base_radius && apex_radius > 0.0);
                }
            }
        }
    }

    #[test]
    fn seed_changes_the_shape() {
        assert_eq!(generate(6, 1), generate(6, 1));
        assert_ne!(generate(6, 1), generate(6, 2));
    }
}
