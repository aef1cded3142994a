//! Meshing gears (SPD `gears.c`): layers of spur gears on a square grid,
//! neighbours turned half a tooth apart so their teeth interleave. Each
//! gear is two concave 144-vertex faces plus one quad per outline edge for
//! the tooth walls, which tests concave-polygon intersection. Colours and
//! each layer's turn come from the seed; about a quarter of the gears are
//! glass. A reflective floor lies below.

use std::f64::consts::TAU;
use std::ops::RangeInclusive;

use glam::{DVec2, Vec3};

use super::common::{Rng, SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = layers, each of level x level gears; level^3 gears in all.
pub(super) const LEVELS: RangeInclusive<u32> = 1..=8;

/// Teeth per gear; a multiple of 4 so both grid directions mesh.
const TEETH: usize = 36;
/// Tip and root radii as fractions of the pitch radius.
const TIP: f64 = 1.08;
const ROOT: f64 = 0.9;
/// Half-widths of a tooth at its root and tip, as fractions of a period.
const ROOT_HALF: f64 = 0.26;
const TIP_HALF: f64 = 0.12;
/// Thickness of a gear as a fraction of the layer spacing.
const THICKNESS: f64 = 0.4;
const FLOOR: f32 = 2.0;

pub(super) fn gear_count(level: u32) -> u64 {
    (level as u64).pow(3)
}

/// Polygons per gear: two faces and a wall quad per outline edge.
pub(super) const POLYGONS_PER_GEAR: u64 = 2 + 4 * TEETH as u64;

pub(super) fn describe(level: u32) -> String {
    let gears = gear_count(level);
    format!(
        "{gears} meshing gears in {level} layers ({} polygons, faces of {} vertices) over a floor, 4 lights",
        gears * POLYGONS_PER_GEAR,
        4 * TEETH
    )
}

/// The gear outline around the origin for pitch radius 1, counter-clockwise
/// seen from +z, starting at a root corner so the first three vertices make
/// a convex corner (the parser takes the face normal from them).
fn outline(phase: f64) -> Vec<DVec2> {
    let period = TAU / TEETH as f64;
    (0..TEETH)
        .flat_map(|m| {
            let centre = phase + m as f64 * period;
            [
                (ROOT, -ROOT_HALF),
                (TIP, -TIP_HALF),
                (TIP, TIP_HALF),
                (ROOT, ROOT_HALF),
            ]
            .map(|(r, half)| DVec2::from_angle(centre + half * period) * r)
        })
        .collect()
}

fn hsv(hue: f64, saturation: f64, value: f64) -> Vec3 {
    let h = hue.rem_euclid(1.0) * 6.0;
    let f = |n: f64| {
        let k = (n + h) % 6.0;
        value - value * saturation * (k.min(4.0 - k)).clamp(0.0, 1.0)
    };
    Vec3::new(f(5.0) as f32, f(3.0) as f32, f(1.0) as f32)
}

pub(super) fn generate(level: u32, seed: u64) -> Scene {
    let view = spd_view(Vec3::new(-1.9, -3.7, 4.3), Vec3::new(0.0, 0.0, 0.35));
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    for p in [
        (2.0, 4.0, 4.0),
        (-2.0, 4.0, 3.0),
        (2.0, -2.5, 2.5),
        (-1.0, -4.0, 2.0),
    ] {
        b.light(Vec3::from(p));
    }
    b.material(material(
        Vec3::new(1.0, 0.85, 0.7),
        0.3,
        0.6,
        30.0,
        0.0,
        1.0,
    ));
    b.add(Primitive::Polygon {
        vertices: [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
            .map(|(x, y)| Vec3::new(x * FLOOR, y * FLOOR, 0.0))
            .to_vec(),
    });

    let mut rng = Rng::new(seed);
    let n = level as usize;
    let pitch = 1.0 / n as f64;
    let spacing = 1.0 / n as f64;
    let period = TAU / TEETH as f64;
    b.reserve(n * n * n * POLYGONS_PER_GEAR as usize);
    for layer in 0..n {
        // Meshing gears turn opposite ways: +turn on one colour of the
        // checkerboard, -turn and half a tooth on the other.
        let turn = rng.range(0.0, period);
        let top = 1.0 - layer as f64 * spacing;
        let bottom = top - THICKNESS * spacing;
        let shapes = [outline(turn), outline(0.5 * period - turn)];
        for cell in 0..n * n {
            let (i, j) = (cell % n, cell / n);
            let centre = DVec2::new(
                -1.0 + (2 * i + 1) as f64 * pitch,
                -1.0 + (2 * j + 1) as f64 * pitch,
            );
            let glass = rng.unit() < 0.25;
            let colour = hsv(rng.unit(), 0.85, 1.0);
            b.material(if glass {
                material(colour, 0.2, 0.2, 100.0, 0.8, 1.1)
            } else {
                material(colour, 1.0, 0.0, 100.0, 0.0, 1.0)
            });
            let ring: Vec<DVec2> = shapes[(i + j) % 2]
                .iter()
                .map(|p| centre + *p * pitch)
                .collect();
            add_gear(&mut b, &ring, top, bottom);
        }
    }
    b.finish()
}

/// The two faces (top counter-clockwise from above, bottom reversed so it
/// faces down) and one outward-facing wall quad per outline edge.
fn add_gear(b: &mut SceneBuilder, ring: &[DVec2], top: f64, bottom: f64) {
    let at = |p: DVec2, z: f64| p.extend(z).as_vec3();
    b.add(Primitive::Polygon {
        vertices: ring.iter().map(|&p| at(p, top)).collect(),
    });
    b.add(Primitive::Polygon {
        vertices: ring.iter().rev().map(|&p| at(p, bottom)).collect(),
    });
    for (k, &p) in ring.iter().enumerate() {
        let q = ring[(k + 1) % ring.len()];
        b.add(Primitive::Polygon {
            vertices: vec![at(p, top), at(p, bottom), at(q, bottom), at(q, top)],
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::counts;

    fn normal(v: &[Vec3]) -> Vec3 {
        (v[1] - v[0]).cross(v[2] - v[1]).normalize()
    }

    #[test]
    fn counts_per_level() {
        for level in 1..=4 {
            let scene = generate(level, 0);
            let polygons = gear_count(level) * POLYGONS_PER_GEAR + 1;
            assert_eq!(counts(&scene), (0, 0, polygons as usize, 0));
            assert_eq!(scene.materials.len() as u64, gear_count(level) + 1);
        }
    }

    #[test]
    fn faces_point_out_of_the_gear() {
        let scene = generate(2, 4);
        let gear = &scene.objects[1..1 + POLYGONS_PER_GEAR as usize];
        let verts = |k: usize| match &gear[k].primitive {
            Primitive::Polygon { vertices } => vertices.clone(),
            other => panic!("{other:?}"),
        };
        assert_eq!(verts(0).len(), 4 * TEETH);
        assert!(normal(&verts(0)).z > 0.99 && normal(&verts(1)).z < -0.99);
        let centre = verts(0).iter().sum::<Vec3>() / (4 * TEETH) as f32;
        for k in 2..gear.len() {
            let v = verts(k);
            let n = normal(&v);
            assert!(n.z.abs() < 1e-4 && n.dot(v[0] - centre) > 0.0, "wall {k}");
        }
    }

    /// Crossing-number point-in-polygon test.
    fn inside(p: DVec2, poly: &[DVec2]) -> bool {
        let mut odd = false;
        for (k, &a) in poly.iter().enumerate() {
            let b = poly[(k + 1) % poly.len()];
            if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
                odd = !odd;
            }
        }
        odd
    }

    /// Whether two outlines' edges cross anywhere.
    fn edges_cross(a: &[DVec2], b: &[DVec2]) -> bool {
        let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
        let edges = |v: &[DVec2]| {
            let v = v.to_vec();
            (0..v.len()).map(move |k| (v[k], v[(k + 1) % v.len()]))
        };
        edges(a).any(|(p, q)| {
            edges(b).any(|(r, s)| {
                side(p, q, r) * side(p, q, s) < 0.0 && side(r, s, p) * side(r, s, q) < 0.0
            })
        })
    }

    #[test]
    fn neighbours_interleave_without_overlapping() {
        let period = TAU / TEETH as f64;
        for turn in (0..20).map(|k| k as f64 * period / 20.0) {
            for offset in [DVec2::new(2.0, 0.0), DVec2::new(0.0, 2.0)] {
                let a = outline(turn);
                let b: Vec<DVec2> = outline(0.5 * period - turn)
                    .into_iter()
                    .map(|p| p + offset)
                    .collect();
                assert!(a.iter().all(|&p| !inside(p, &b)) && b.iter().all(|&p| !inside(p, &a)));
                assert!(!edges_cross(&a, &b), "turn {turn}");
                // Some tooth reaches past the other gear's tip circle.
                assert!(a.iter().any(|p| p.distance(offset) < TIP));
            }
        }
    }
}
