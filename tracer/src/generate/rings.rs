//! Interlocking rings (SPD `rings.c`): groups of six pentagonal rings of
//! cylinders with spheres at the joints, one ring per icosahedral axis so
//! they weave through each other, stacked in a pyramid of layers that
//! recede from the camera (layer k holds k x k groups), in front of a wall.

use std::f64::consts::TAU;
use std::ops::RangeInclusive;

use glam::{DVec3, Vec3};

use super::common::{SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = layers of the pyramid; level 12 is 650 groups, 39,000 objects.
pub(super) const LEVELS: RangeInclusive<u32> = 1..=12;

/// Circumradius of a ring's pentagon.
const RING_RADIUS: f64 = 0.93;
/// Radius of the cylinders and joint spheres.
const TUBE_RADIUS: f32 = 0.074;
/// Distance between layers along the view direction.
const LAYER_DEPTH: f64 = 2.6;
/// Spacing of groups within a layer: groups of radius ~1 just touch.
const GROUP_SPACING: f64 = 2.0;
/// One colour per ring of a group: red, green, blue, cyan, magenta, yellow.
const COLOURS: [[f32; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [1.0, 0.0, 1.0],
    [1.0, 1.0, 0.0],
];

/// 1 + 4 + ... + level^2 groups.
pub(super) fn group_count(level: u32) -> u64 {
    let n = level as u64;
    n * (n + 1) * (2 * n + 1) / 6
}

pub(super) fn describe(level: u32) -> String {
    let groups = group_count(level);
    format!(
        "{groups} groups of 6 interlocking rings ({} cylinders, {} spheres) before a wall, 3 lights",
        30 * groups,
        30 * groups
    )
}

pub(super) fn generate(level: u32) -> Scene {
    let eye_y = -LAYER_DEPTH as f32;
    let view = spd_view(
        Vec3::new(-1.0, eye_y, 0.5),
        Vec3::new(-1.0, eye_y + 1.0, 0.5),
    );
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    for (x, z) in [(3.0, 3.0), (-4.0, 1.0), (2.0, -4.0)] {
        b.light(Vec3::new(x, eye_y, z));
    }

    // The wall: far enough behind the last layer, wide enough for the view.
    let wall_y = (LAYER_DEPTH * (level as f64 + 1.0) + 2.0) as f32;
    let half = 0.5 * (wall_y - eye_y);
    b.material(material(Vec3::ONE, 1.0, 0.0, 100.0, 0.0, 1.0));
    b.add(Primitive::Polygon {
        vertices: [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
            .map(|(x, z)| Vec3::new(-1.0 + x * half, wall_y, 0.5 + z * half))
            .to_vec(),
    });

    let centres: Vec<DVec3> = (1..=level)
        .flat_map(|k| {
            let offset = (k as f64 - 1.0) * 0.5 * GROUP_SPACING;
            (0..k * k).map(move |i| {
                DVec3::new(
                    (i % k) as f64 * GROUP_SPACING - offset,
                    k as f64 * LAYER_DEPTH,
                    (i / k) as f64 * GROUP_SPACING - offset,
                )
            })
        })
        .collect();
    b.reserve(60 * centres.len());
    // Rings grouped by colour, so each material is one contiguous run.
    for (ring, colour) in COLOURS.iter().enumerate() {
        b.material(material(Vec3::from(*colour), 0.5, 0.2, 30.0, 0.0, 1.0));
        let corners = pentagon(ring);
        for &centre in &centres {
            for i in 0..5 {
                let p = (centre + corners[i]).as_vec3();
                let q = (centre + corners[(i + 1) % 5]).as_vec3();
                b.add(Primitive::Cone {
                    base: p,
                    base_radius: TUBE_RADIUS,
                    apex: q,
                    apex_radius: TUBE_RADIUS,
                });
                b.add(Primitive::Sphere {
                    centre: p,
                    radius: TUBE_RADIUS,
                    inside_only: false,
                });
            }
        }
    }
    b.finish()
}

/// The corners of ring `ring` (0..6) around the origin: ring 0 lies in the
/// z = 0 plane, rings 1..=5 in planes whose normals make 63.4 degrees
/// (atan 2, the angle between icosahedron axes) with z, 72 degrees apart.
/// The first corner lies on the horizontal line of the ring's plane.
fn pentagon(ring: usize) -> [DVec3; 5] {
    let (normal, u) = if ring == 0 {
        (DVec3::Z, DVec3::X)
    } else {
        let azimuth = (-54.0 + 72.0 * (ring - 1) as f64).to_radians();
        let polar = 2f64.atan();
        let n = DVec3::new(
            polar.sin() * azimuth.cos(),
            polar.sin() * azimuth.sin(),
            polar.cos(),
        );
        (n, DVec3::Z.cross(n).normalize())
    };
    let v = normal.cross(u);
    std::array::from_fn(|i| {
        let a = i as f64 * TAU / 5.0;
        (u * a.cos() + v * a.sin()) * RING_RADIUS
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::counts;

    #[test]
    fn counts_per_level() {
        for (level, groups) in [(1, 1), (2, 5), (3, 14), (7, 140)] {
            assert_eq!(group_count(level), groups);
            let n = 30 * groups as usize;
            assert_eq!(counts(&generate(level)), (n, n, 1, 0));
        }
    }

    #[test]
    fn rings_are_regular_pentagons_on_distinct_planes() {
        let normals: Vec<DVec3> = (0..6)
            .map(|r| {
                let c = pentagon(r);
                for i in 0..5 {
                    let side = c[i].distance(c[(i + 1) % 5]);
                    assert!((side - 2.0 * RING_RADIUS * (TAU / 10.0).sin()).abs() < 1e-9);
                }
                c[0].cross(c[1]).normalize()
            })
            .collect();
        for i in 0..6 {
            for j in 0..i {
                // Icosahedron axes: every pair at atan 2, |cos| = 1 / sqrt 5.
                let cos = normals[i].dot(normals[j]).abs();
                assert!((cos - 5f64.sqrt().recip()).abs() < 1e-9, "{i} {j}: {cos}");
            }
        }
    }
}
