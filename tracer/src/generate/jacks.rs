//! Jacks (after SPD `jacks.c`): the children's toy, three crossed
//! cylinders with a ball on each of their six ends, repeated
//! recursively: every ball of a jack carries a smaller jack, out to
//! `level` generations. Primitives of very different sizes clustered
//! around each other, over a floor.

use std::ops::RangeInclusive;

use glam::{DVec3, Vec3};

use super::common::{SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = generations of jacks: the first has 6 children, every later
/// one 5 (none back towards its parent), so 1 + 6 (5^(level-1) - 1) / 4
/// jacks of 3 cylinders and 6 balls (level 5: 937 jacks, 8433 primitives).
pub(super) const LEVELS: RangeInclusive<u32> = 1..=7;

/// Half the length of the first jack's arms.
const ARM: f64 = 1.0;
const ROD_RADIUS: f64 = 0.06;
const BALL_RADIUS: f64 = 0.16;
/// Size of a child jack relative to its parent.
const SHRINK: f64 = 0.42;
/// The six arm directions.
const ARMS: [DVec3; 6] = [
    DVec3::X,
    DVec3::NEG_X,
    DVec3::Y,
    DVec3::NEG_Y,
    DVec3::Z,
    DVec3::NEG_Z,
];

/// Jacks at `level`.
pub(super) fn jack_count(level: u32) -> u64 {
    1 + 6 * (5u64.pow(level - 1) - 1) / 4
}

pub(super) fn describe(level: u32) -> String {
    let jacks = jack_count(level);
    format!(
        "{jacks} jacks in {level} recursive generations ({} cylinders, {} balls) over a floor, 2 lights",
        3 * jacks,
        6 * jacks
    )
}

/// Appends the rods and balls of a jack at `centre` of size `scale`, then
/// its children on every ball except the one pointing back at `from`.
fn jack(
    centre: DVec3,
    scale: f64,
    from: Option<DVec3>,
    generations: u32,
    out: &mut (Vec<Primitive>, Vec<Primitive>),
) {
    for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
        out.0.push(Primitive::Cone {
            base: (centre - axis * ARM * scale).as_vec3(),
            base_radius: (ROD_RADIUS * scale) as f32,
            apex: (centre + axis * ARM * scale).as_vec3(),
            apex_radius: (ROD_RADIUS * scale) as f32,
        });
    }
    for dir in ARMS {
        let ball = centre + dir * ARM * scale;
        out.1.push(Primitive::Sphere {
            centre: ball.as_vec3(),
            radius: (BALL_RADIUS * scale) as f32,
            inside_only: false,
        });
        if generations > 1 && from != Some(-dir) {
            let child = ball + dir * ARM * scale * SHRINK;
            jack(child, scale * SHRINK, Some(dir), generations - 1, out);
        }
    }
}

pub(super) fn generate(level: u32) -> Scene {
    let view = spd_view(Vec3::new(3.2, -4.0, 2.6), Vec3::new(0.0, 0.0, -0.2));
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    b.light(Vec3::new(5.0, -6.0, 9.0));
    b.light(Vec3::new(-7.0, -2.0, 4.0));

    // Each generation reaches 2 SHRINK times further than the one before.
    let extent = ARM * (1.0 + 2.0 * SHRINK / (1.0 - SHRINK)) + BALL_RADIUS;
    let floor = -(extent as f32) - 0.05;
    b.material(material(Vec3::new(0.3, 0.5, 0.3), 0.8, 0.0, 10.0, 0.0, 1.0));
    b.add(Primitive::Polygon {
        vertices: [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
            .map(|(x, y)| Vec3::new(x * 8.0, y * 8.0, floor))
            .to_vec(),
    });

    let jacks = jack_count(level) as usize;
    let mut parts = (Vec::with_capacity(3 * jacks), Vec::with_capacity(6 * jacks));
    jack(DVec3::ZERO, 1.0, None, level, &mut parts);
    b.reserve(9 * jacks);
    b.material(material(
        Vec3::new(0.75, 0.75, 0.8),
        0.4,
        0.6,
        80.0,
        0.0,
        1.0,
    ));
    for rod in parts.0 {
        b.add(rod);
    }
    b.material(material(
        Vec3::new(0.9, 0.15, 0.1),
        0.7,
        0.3,
        40.0,
        0.0,
        1.0,
    ));
    for ball in parts.1 {
        b.add(ball);
    }
    b.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::counts;

    #[test]
    fn counts_per_level() {
        assert_eq!(jack_count(5), 937);
        assert_eq!(jack_count(1), 1);
        assert_eq!(jack_count(2), 7);
        for level in [1, 2, 3] {
            let jacks = jack_count(level) as usize;
            assert_eq!(counts(&generate(level)), (6 * jacks, 3 * jacks, 1, 0));
        }
    }
}
