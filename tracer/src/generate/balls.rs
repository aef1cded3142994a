//! The sphereflake (SPD `balls.c`): a sphere with nine children of a third
//! its radius touching it, six around its equator and three above, each
//! oriented along the direction from its parent, recursively; over a floor.

use std::ops::RangeInclusive;

use glam::{DMat3, DQuat, DVec3, Vec3};

use super::common::{SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = recursion depth; level 5 already has 66,430 spheres.
pub(super) const LEVELS: RangeInclusive<u32> = 0..=5;

/// Child radius over parent radius.
const SCALE: f64 = 1.0 / 3.0;
const RADIUS: f64 = 0.5;
/// Half the floor's edge: the course files' two triangles, so timings compare.
const FLOOR: f32 = 3.0;

/// 1 + 9 + ... + 9^level.
pub(super) fn sphere_count(level: u32) -> u64 {
    (0..=level).map(|k| 9u64.pow(k)).sum()
}

pub(super) fn describe(level: u32) -> String {
    format!(
        "sphereflake of {} spheres over a floor, 3 lights",
        sphere_count(level)
    )
}

pub(super) fn generate(level: u32) -> Scene {
    let view = spd_view(Vec3::new(2.1, 1.3, 1.7), Vec3::ZERO);
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    for p in [(4.0, 3.0, 2.0), (1.0, -4.0, 4.0), (-3.0, 1.0, 5.0)] {
        b.light(Vec3::from(p));
    }
    b.material(material(
        Vec3::new(1.0, 0.75, 0.33),
        0.8,
        0.0,
        100.0,
        0.0,
        1.0,
    ));
    let z = -RADIUS as f32;
    let corners = [
        (FLOOR, FLOOR),
        (-FLOOR, FLOOR),
        (-FLOOR, -FLOOR),
        (FLOOR, -FLOOR),
    ]
    .map(|(x, y)| Vec3::new(x, y, z));
    for [i, j, k] in [[0, 1, 2], [2, 3, 0]] {
        b.add(Primitive::Polygon {
            vertices: vec![corners[i], corners[j], corners[k]],
        });
    }
    b.material(material(
        Vec3::new(1.0, 0.9, 0.7),
        0.5,
        0.5,
        30.0827,
        0.0,
        1.0,
    ));
    b.reserve(sphere_count(level) as usize);
    flake(&mut b, level, DVec3::ZERO, DVec3::Z, RADIUS, &child_set());
    b.finish()
}

/// The nine child directions for a parent whose axis is +z: three trios
/// 120 degrees apart about z, each trio tilted up by asin(2 / sqrt 6).
fn child_set() -> [DVec3; 9] {
    let d = std::f64::consts::FRAC_1_SQRT_2;
    let trio = [
        DVec3::new(d, d, 0.0),
        DVec3::new(d, 0.0, -d),
        DVec3::new(0.0, d, -d),
    ];
    let tilt = DMat3::from_axis_angle(
        DVec3::new(1.0, -1.0, 0.0).normalize(),
        (2.0 / 6f64.sqrt()).asin(),
    );
    std::array::from_fn(|i| {
        let spin = DMat3::from_rotation_z((i / 3) as f64 * std::f64::consts::TAU / 3.0);
        spin * (tilt * trio[i % 3])
    })
}

/// Emits the sphere, then (depth > 0) its nine children, the set rotated so
/// that +z maps onto `axis`, each at distance r + r/3 from the centre.
fn flake(
    b: &mut SceneBuilder,
    depth: u32,
    centre: DVec3,
    axis: DVec3,
    radius: f64,
    set: &[DVec3; 9],
) {
    b.add(Primitive::Sphere {
        centre: centre.as_vec3(),
        radius: radius as f32,
        inside_only: false,
    });
    if depth == 0 {
        return;
    }
    let orient = if axis.z <= -1.0 + 1e-12 {
        DQuat::from_rotation_y(std::f64::consts::PI)
    } else {
        DQuat::from_rotation_arc(DVec3::Z, axis)
    };
    let distance = radius * (1.0 + SCALE);
    for dir in set {
        let dir = (orient * *dir).normalize();
        flake(
            b,
            depth - 1,
            centre + dir * distance,
            dir,
            radius * SCALE,
            set,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::counts;

    fn spheres(scene: &Scene) -> Vec<(DVec3, f64)> {
        scene
            .objects
            .iter()
            .filter_map(|o| match o.primitive {
                Primitive::Sphere { centre, radius, .. } => {
                    Some((centre.as_dvec3(), radius as f64))
                }
                _ => None,
            })
            .collect()
    }

    #[test]
    fn sphere_counts_per_level() {
        for (level, n) in [(0, 1), (1, 10), (2, 91), (3, 820), (4, 7381)] {
            assert_eq!(sphere_count(level), n);
            assert_eq!(
                counts(&generate(level)),
                (n as usize, 0, 2, 0),
                "level {level}"
            );
        }
    }

    #[test]
    fn children_touch_their_parent() {
        let s = spheres(&generate(3));
        // Depth-first order: a child's parent is the nearest earlier sphere
        // three times its size.
        for (i, &(c, r)) in s.iter().enumerate().skip(1) {
            let (pc, pr) = s[..i]
                .iter()
                .rev()
                .find(|(_, pr)| (pr / r - 3.0).abs() < 1e-4)
                .copied()
                .expect("parent");
            assert!((pc.distance(c) - (pr + r)).abs() < 1e-5, "sphere {i}");
        }
    }

    #[test]
    fn fits_in_the_unit_cube_above_the_floor() {
        for (c, r) in spheres(&generate(4)) {
            let lo = c - DVec3::splat(r);
            let hi = c + DVec3::splat(r);
            assert!(lo.cmpge(DVec3::splat(-1.0)).all() && hi.cmple(DVec3::ONE).all());
            assert!(lo.z >= -0.5 - 1e-6, "below the floor: {c} {r}");
        }
    }

    #[test]
    fn first_child_is_the_classic_one() {
        // balls.c's first child of the root sits at (1, 1, 2) / sqrt 6 * 2/3.
        let (c, r) = spheres(&generate(1))[1];
        let want = DVec3::new(1.0, 1.0, 2.0) / 6f64.sqrt() * (2.0 / 3.0);
        assert!(c.distance(want) < 1e-6 && (r - 0.5 / 3.0).abs() < 1e-7);
    }
}
