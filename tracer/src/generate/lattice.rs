//! A lattice (after SPD `lattice.c`): a cube of n x n x n balls joined to
//! their neighbours along each axis by thin cylinders. Long thin
//! primitives whose bounding boxes span whole cells, the case where
//! boxes fit their primitives worst.

use std::ops::RangeInclusive;

use glam::Vec3;

use super::common::{SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = balls along an edge of the cube, n = level + 1: n^3 balls and
/// 3 n^2 (n - 1) cylinders (level 11: 1728 balls, 4752 cylinders).
pub(super) const LEVELS: RangeInclusive<u32> = 1..=24;

/// Ball and rod radii as fractions of the spacing, so the rods show
/// between the balls at every level.
const BALL_RADIUS: f32 = 0.22;
const ROD_RADIUS: f32 = 0.06;

/// (balls, cylinders) at `level`.
pub(super) fn counts(level: u32) -> (u64, u64) {
    let n = level as u64 + 1;
    (n * n * n, 3 * n * n * (n - 1))
}

pub(super) fn describe(level: u32) -> String {
    let (balls, rods) = counts(level);
    format!("lattice of {balls} balls joined by {rods} cylinders in a cube, 3 lights")
}

pub(super) fn generate(level: u32) -> Scene {
    // The cube spans [-1, 1] on every axis whatever the level.
    let n = level + 1;
    let step = 2.0 / level as f32;
    let at = |i: u32, j: u32, k: u32| Vec3::new(i as f32, j as f32, k as f32) * step - 1.0;

    let view = spd_view(Vec3::new(2.1, -3.1, 1.7), Vec3::new(0.0, 0.0, -0.1));
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    b.light(Vec3::new(4.0, -6.0, 8.0));
    b.light(Vec3::new(-6.0, -4.0, 3.0));
    b.light(Vec3::new(1.0, 5.0, 6.0));
    let (balls, rods) = counts(level);
    b.reserve((balls + rods) as usize);

    b.material(material(
        Vec3::new(0.9, 0.2, 0.15),
        0.6,
        0.4,
        60.0,
        0.0,
        1.0,
    ));
    // Lattice points (i, j, k), i fastest.
    let points = || (0..n * n * n).map(|m| (m % n, m / n % n, m / (n * n)));
    for (i, j, k) in points() {
        b.add(Primitive::Sphere {
            centre: at(i, j, k),
            radius: BALL_RADIUS * step,
            inside_only: false,
        });
    }
    b.material(material(
        Vec3::new(0.8, 0.8, 0.85),
        0.5,
        0.5,
        80.0,
        0.0,
        1.0,
    ));
    for (i, j, k) in points() {
        let p = at(i, j, k);
        for (di, dj, dk) in [(1, 0, 0), (0, 1, 0), (0, 0, 1)] {
            if i + di < n && j + dj < n && k + dk < n {
                b.add(Primitive::Cone {
                    base: p,
                    base_radius: ROD_RADIUS * step,
                    apex: at(i + di, j + dj, k + dk),
                    apex_radius: ROD_RADIUS * step,
                });
            }
        }
    }
    b.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util;

    #[test]
    fn counts_per_level() {
        assert_eq!(counts(11), (1728, 4752));
        for level in [1, 3] {
            let (balls, rods) = counts(level);
            assert_eq!(
                test_util::counts(&generate(level)),
                (balls as usize, rods as usize, 0, 0)
            );
        }
    }
}
