//! The teapot (after SPD `teapot.c`): Newell's 32 bicubic Bezier patches
//! (the rim, body, handle, spout, lid and Crow's bottom), each tessellated
//! on an n x n grid of its parameters into 2 n^2 triangles with the
//! surface's normals at their corners (`pp` patches, smooth shaded), on a
//! checkerboard of n x n squares, under two lights. Triangles crowd where
//! the patches pinch (the lid's knob, the spout's tip, the bottom's
//! centre) and stay large on the body: a mesh of very uneven density.

use std::ops::RangeInclusive;

use glam::{DVec3, Vec3};

use super::common::{SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = SPD's size factor n: the tessellation of each patch and the
/// checkerboard's squares per side (12: 9 120 triangles, 40: 102 080).
pub(super) const LEVELS: RangeInclusive<u32> = 2..=64;

/// Half the checkerboard's side.
const BOARD: f64 = 4.0;

/// A corner of a grid cell whose vertex lies on the z axis is a cusp (the
/// lid's knob, the bottom's centre): two such corners make a triangle of
/// no area, which SPD drops; one gets the axis as its normal.
const CUSP: f64 = 1e-4;

/// Triangles of the teapot at `level`: the four lid-top and four bottom
/// patches meet the axis along one edge, which loses one triangle per
/// grid column there.
pub(super) fn triangle_count(level: u32) -> u64 {
    let n = u64::from(level);
    64 * n * n - 8 * n
}

pub(super) fn describe(level: u32) -> String {
    format!(
        "teapot: Newell's 32 Bezier patches as {} smooth triangles on a checkerboard of {} squares, 2 lights",
        triangle_count(level),
        level * level
    )
}

pub(super) fn generate(level: u32) -> Scene {
    let view = spd_view(Vec3::new(4.86, 7.2, 5.4), Vec3::ZERO);
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    b.light(Vec3::new(-3.1, 9.8, 12.1));
    b.light(Vec3::new(11.3, 5.1, 8.8));
    checkerboard(&mut b, level);
    b.material(material(
        Vec3::new(1.0, 0.5, 0.1),
        0.75,
        0.25,
        37.0,
        0.0,
        1.0,
    ));
    b.reserve(triangle_count(level) as usize);
    for patch in &PATCHES {
        tessellate(&control_points(patch), level, &mut b);
    }
    b.finish()
}

/// The 4 x 4 control points of a patch, row by row.
fn control_points(patch: &[u16; 16]) -> [DVec3; 16] {
    patch.map(|i| DVec3::from_array(VERTICES[i as usize].map(f64::from)))
}

/// The n x n squares over [-4, 4]^2 at z = 0: the white ones (odd x + y
/// cell index) first, then the grey ones, as SPD writes them.
fn checkerboard(b: &mut SceneBuilder, level: u32) {
    let corner = |i: u32, j: u32| {
        let at = |k: u32| (BOARD * (2.0 * f64::from(k) / f64::from(level) - 1.0)) as f32;
        Vec3::new(at(i), at(j), 0.0)
    };
    for (colour, parity) in [(Vec3::ONE, 1), (Vec3::splat(0.5), 0)] {
        b.material(material(colour, 0.5, 0.5, 30.0, 0.0, 1.0));
        for s in 0..level {
            for t in (0..level).filter(|t| (s + t) % 2 == parity) {
                b.add(Primitive::Polygon {
                    vertices: vec![
                        corner(s, t),
                        corner(s + 1, t),
                        corner(s + 1, t + 1),
                        corner(s, t + 1),
                    ],
                });
            }
        }
    }
}

/// The cubic Bernstein weights at `u` and their derivatives.
fn bernstein(u: f64) -> ([f64; 4], [f64; 4]) {
    let v = 1.0 - u;
    (
        [v * v * v, 3.0 * u * v * v, 3.0 * u * u * v, u * u * u],
        [
            -3.0 * v * v,
            3.0 * v * (v - 2.0 * u),
            3.0 * u * (2.0 * v - u),
            3.0 * u * u,
        ],
    )
}

/// The point of the patch `control` (rows along s, columns along t) at
/// `(s, t)`, and its unit normal `dP/dt x dP/ds` (zero at a cusp).
fn point(control: &[DVec3; 16], s: f64, t: f64) -> (DVec3, DVec3) {
    let ((bs, ds), (bt, dt)) = (bernstein(s), bernstein(t));
    let (mut p, mut along_s, mut along_t) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    for r in 0..4 {
        for c in 0..4 {
            let g = control[4 * r + c];
            p += g * (bs[r] * bt[c]);
            along_s += g * (ds[r] * bt[c]);
            along_t += g * (bs[r] * dt[c]);
        }
    }
    (p, along_t.cross(along_s).normalize_or_zero())
}

/// Adds the patch's 2 n^2 triangles, cell by cell: corners (s, t),
/// (s, t + 1), (s + 1, t + 1), then (s + 1, t + 1), (s + 1, t), (s, t), so
/// each triangle winds with its normals; a triangle with two corners on
/// the axis is dropped.
fn tessellate(control: &[DVec3; 16], n: u32, b: &mut SceneBuilder) {
    let at = |k: u32| f64::from(k) / f64::from(n);
    let on_axis = |p: DVec3| p.x.abs() < CUSP && p.y.abs() < CUSP;
    for s in 0..n {
        for t in 0..n {
            let corners = [(s, t), (s, t + 1), (s + 1, t + 1), (s + 1, t)];
            for half in [[0, 1, 2], [2, 3, 0]] {
                let mut vertices = half.map(|k| point(control, at(corners[k].0), at(corners[k].1)));
                if vertices.iter().filter(|(p, _)| on_axis(*p)).count() > 1 {
                    continue;
                }
                for (p, normal) in &mut vertices {
                    if on_axis(*p) {
                        // The knob's top (above the body) faces up, the
                        // bottom's centre down.
                        *normal = DVec3::Z * if p.z > 1.5 { 1.0 } else { -1.0 };
                    }
                }
                b.add(Primitive::Patch {
                    vertices: vertices.iter().map(|(p, _)| p.as_vec3()).collect(),
                    normals: vertices.iter().map(|(_, n)| n.as_vec3()).collect(),
                });
            }
        }
    }
}

/// Each patch's 4 x 4 control points, as indices into [`VERTICES`]: Newell's
/// data with its duplicate and unused vertices removed, as SPD has it.
#[rustfmt::skip]
const PATCHES: [[u16; 16]; 32] = [
    // rim
    [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15],
    [3, 16, 17, 18, 7, 19, 20, 21, 11, 22, 23, 24, 15, 25, 26, 27],
    [18, 28, 29, 30, 21, 31, 32, 33, 24, 34, 35, 36, 27, 37, 38, 39],
    [30, 40, 41, 0, 33, 42, 43, 4, 36, 44, 45, 8, 39, 46, 47, 12],
    // body
    [12, 13, 14, 15, 48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59],
    [15, 25, 26, 27, 51, 60, 61, 62, 55, 63, 64, 65, 59, 66, 67, 68],
    [27, 37, 38, 39, 62, 69, 70, 71, 65, 72, 73, 74, 68, 75, 76, 77],
    [39, 46, 47, 12, 71, 78, 79, 48, 74, 80, 81, 52, 77, 82, 83, 56],
    [56, 57, 58, 59, 84, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95],
    [59, 66, 67, 68, 87, 96, 97, 98, 91, 99, 100, 101, 95, 102, 103, 104],
    [68, 75, 76, 77, 98, 105, 106, 107, 101, 108, 109, 110, 104, 111, 112, 113],
    [77, 82, 83, 56, 107, 114, 115, 84, 110, 116, 117, 88, 113, 118, 119, 92],
    // handle
    [120, 121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135],
    [123, 136, 137, 120, 127, 138, 139, 124, 131, 140, 141, 128, 135, 142, 143, 132],
    [132, 133, 134, 135, 144, 145, 146, 147, 148, 149, 150, 151, 68, 152, 153, 154],
    [135, 142, 143, 132, 147, 155, 156, 144, 151, 157, 158, 148, 154, 159, 160, 68],
    // spout
    [161, 162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176],
    [164, 177, 178, 161, 168, 179, 180, 165, 172, 181, 182, 169, 176, 183, 184, 173],
    [173, 174, 175, 176, 185, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196],
    [176, 183, 184, 173, 188, 197, 198, 185, 192, 199, 200, 189, 196, 201, 202, 193],
    // lid
    [203, 203, 203, 203, 204, 205, 206, 207, 208, 208, 208, 208, 209, 210, 211, 212],
    [203, 203, 203, 203, 207, 213, 214, 215, 208, 208, 208, 208, 212, 216, 217, 218],
    [203, 203, 203, 203, 215, 219, 220, 221, 208, 208, 208, 208, 218, 222, 223, 224],
    [203, 203, 203, 203, 221, 225, 226, 204, 208, 208, 208, 208, 224, 227, 228, 209],
    [209, 210, 211, 212, 229, 230, 231, 232, 233, 234, 235, 236, 237, 238, 239, 240],
    [212, 216, 217, 218, 232, 241, 242, 243, 236, 244, 245, 246, 240, 247, 248, 249],
    [218, 222, 223, 224, 243, 250, 251, 252, 246, 253, 254, 255, 249, 256, 257, 258],
    [224, 227, 228, 209, 252, 259, 260, 229, 255, 261, 262, 233, 258, 263, 264, 237],
    // bottom
    [265, 265, 265, 265, 266, 267, 268, 269, 270, 271, 272, 273, 92, 119, 118, 113],
    [265, 265, 265, 265, 269, 274, 275, 276, 273, 277, 278, 279, 113, 112, 111, 104],
    [265, 265, 265, 265, 276, 280, 281, 282, 279, 283, 284, 285, 104, 103, 102, 95],
    [265, 265, 265, 265, 282, 286, 287, 266, 285, 288, 289, 270, 95, 94, 93, 92],
];

/// The control points, z up, the bottom at z = 0.
#[rustfmt::skip]
const VERTICES: [[f32; 3]; 290] = [
    [1.4, 0.0, 2.4], [1.4, -0.784, 2.4], [0.784, -1.4, 2.4],
    [0.0, -1.4, 2.4], [1.3375, 0.0, 2.53125], [1.3375, -0.749, 2.53125],
    [0.749, -1.3375, 2.53125], [0.0, -1.3375, 2.53125], [1.4375, 0.0, 2.53125],
    [1.4375, -0.805, 2.53125], [0.805, -1.4375, 2.53125], [0.0, -1.4375, 2.53125],
    [1.5, 0.0, 2.4], [1.5, -0.84, 2.4], [0.84, -1.5, 2.4],
    [0.0, -1.5, 2.4], [-0.784, -1.4, 2.4], [-1.4, -0.784, 2.4],
    [-1.4, 0.0, 2.4], [-0.749, -1.3375, 2.53125], [-1.3375, -0.749, 2.53125],
    [-1.3375, 0.0, 2.53125], [-0.805, -1.4375, 2.53125], [-1.4375, -0.805, 2.53125],
    [-1.4375, 0.0, 2.53125], [-0.84, -1.5, 2.4], [-1.5, -0.84, 2.4],
    [-1.5, 0.0, 2.4], [-1.4, 0.784, 2.4], [-0.784, 1.4, 2.4],
    [0.0, 1.4, 2.4], [-1.3375, 0.749, 2.53125], [-0.749, 1.3375, 2.53125],
    [0.0, 1.3375, 2.53125], [-1.4375, 0.805, 2.53125], [-0.805, 1.4375, 2.53125],
    [0.0, 1.4375, 2.53125], [-1.5, 0.84, 2.4], [-0.84, 1.5, 2.4],
    [0.0, 1.5, 2.4], [0.784, 1.4, 2.4], [1.4, 0.784, 2.4],
    [0.749, 1.3375, 2.53125], [1.3375, 0.749, 2.53125], [0.805, 1.4375, 2.53125],
    [1.4375, 0.805, 2.53125], [0.84, 1.5, 2.4], [1.5, 0.84, 2.4],
    [1.75, 0.0, 1.875], [1.75, -0.98, 1.875], [0.98, -1.75, 1.875],
    [0.0, -1.75, 1.875], [2.0, 0.0, 1.35], [2.0, -1.12, 1.35],
    [1.12, -2.0, 1.35], [0.0, -2.0, 1.35], [2.0, 0.0, 0.9],
    [2.0, -1.12, 0.9], [1.12, -2.0, 0.9], [0.0, -2.0, 0.9],
    [-0.98, -1.75, 1.875], [-1.75, -0.98, 1.875], [-1.75, 0.0, 1.875],
    [-1.12, -2.0, 1.35], [-2.0, -1.12, 1.35], [-2.0, 0.0, 1.35],
    [-1.12, -2.0, 0.9], [-2.0, -1.12, 0.9], [-2.0, 0.0, 0.9],
    [-1.75, 0.98, 1.875], [-0.98, 1.75, 1.875], [0.0, 1.75, 1.875],
    [-2.0, 1.12, 1.35], [-1.12, 2.0, 1.35], [0.0, 2.0, 1.35],
    [-2.0, 1.12, 0.9], [-1.12, 2.0, 0.9], [0.0, 2.0, 0.9],
    [0.98, 1.75, 1.875], [1.75, 0.98, 1.875], [1.12, 2.0, 1.35],
    [2.0, 1.12, 1.35], [1.12, 2.0, 0.9], [2.0, 1.12, 0.9],
    [2.0, 0.0, 0.45], [2.0, -1.12, 0.45], [1.12, -2.0, 0.45],
    [0.0, -2.0, 0.45], [1.5, 0.0, 0.225], [1.5, -0.84, 0.225],
    [0.84, -1.5, 0.225], [0.0, -1.5, 0.225], [1.5, 0.0, 0.15],
    [1.5, -0.84, 0.15], [0.84, -1.5, 0.15], [0.0, -1.5, 0.15],
    [-1.12, -2.0, 0.45], [-2.0, -1.12, 0.45], [-2.0, 0.0, 0.45],
    [-0.84, -1.5, 0.225], [-1.5, -0.84, 0.225], [-1.5, 0.0, 0.225],
    [-0.84, -1.5, 0.15], [-1.5, -0.84, 0.15], [-1.5, 0.0, 0.15],
    [-2.0, 1.12, 0.45], [-1.12, 2.0, 0.45], [0.0, 2.0, 0.45],
    [-1.5, 0.84, 0.225], [-0.84, 1.5, 0.225], [0.0, 1.5, 0.225],
    [-1.5, 0.84, 0.15], [-0.84, 1.5, 0.15], [0.0, 1.5, 0.15],
    [1.12, 2.0, 0.45], [2.0, 1.12, 0.45], [0.84, 1.5, 0.225],
    [1.5, 0.84, 0.225], [0.84, 1.5, 0.15], [1.5, 0.84, 0.15],
    [-1.6, 0.0, 2.025], [-1.6, -0.3, 2.025], [-1.5, -0.3, 2.25],
    [-1.5, 0.0, 2.25], [-2.3, 0.0, 2.025], [-2.3, -0.3, 2.025],
    [-2.5, -0.3, 2.25], [-2.5, 0.0, 2.25], [-2.7, 0.0, 2.025],
    [-2.7, -0.3, 2.025], [-3.0, -0.3, 2.25], [-3.0, 0.0, 2.25],
    [-2.7, 0.0, 1.8], [-2.7, -0.3, 1.8], [-3.0, -0.3, 1.8],
    [-3.0, 0.0, 1.8], [-1.5, 0.3, 2.25], [-1.6, 0.3, 2.025],
    [-2.5, 0.3, 2.25], [-2.3, 0.3, 2.025], [-3.0, 0.3, 2.25],
    [-2.7, 0.3, 2.025], [-3.0, 0.3, 1.8], [-2.7, 0.3, 1.8],
    [-2.7, 0.0, 1.575], [-2.7, -0.3, 1.575], [-3.0, -0.3, 1.35],
    [-3.0, 0.0, 1.35], [-2.5, 0.0, 1.125], [-2.5, -0.3, 1.125],
    [-2.65, -0.3, 0.9375], [-2.65, 0.0, 0.9375], [-2.0, -0.3, 0.9],
    [-1.9, -0.3, 0.6], [-1.9, 0.0, 0.6], [-3.0, 0.3, 1.35],
    [-2.7, 0.3, 1.575], [-2.65, 0.3, 0.9375], [-2.5, 0.3, 1.125],
    [-1.9, 0.3, 0.6], [-2.0, 0.3, 0.9], [1.7, 0.0, 1.425],
    [1.7, -0.66, 1.425], [1.7, -0.66, 0.6], [1.7, 0.0, 0.6],
    [2.6, 0.0, 1.425], [2.6, -0.66, 1.425], [3.1, -0.66, 0.825],
    [3.1, 0.0, 0.825], [2.3, 0.0, 2.1], [2.3, -0.25, 2.1],
    [2.4, -0.25, 2.025], [2.4, 0.0, 2.025], [2.7, 0.0, 2.4],
    [2.7, -0.25, 2.4], [3.3, -0.25, 2.4], [3.3, 0.0, 2.4],
    [1.7, 0.66, 0.6], [1.7, 0.66, 1.425], [3.1, 0.66, 0.825],
    [2.6, 0.66, 1.425], [2.4, 0.25, 2.025], [2.3, 0.25, 2.1],
    [3.3, 0.25, 2.4], [2.7, 0.25, 2.4], [2.8, 0.0, 2.475],
    [2.8, -0.25, 2.475], [3.525, -0.25, 2.49375], [3.525, 0.0, 2.49375],
    [2.9, 0.0, 2.475], [2.9, -0.15, 2.475], [3.45, -0.15, 2.5125],
    [3.45, 0.0, 2.5125], [2.8, 0.0, 2.4], [2.8, -0.15, 2.4],
    [3.2, -0.15, 2.4], [3.2, 0.0, 2.4], [3.525, 0.25, 2.49375],
    [2.8, 0.25, 2.475], [3.45, 0.15, 2.5125], [2.9, 0.15, 2.475],
    [3.2, 0.15, 2.4], [2.8, 0.15, 2.4], [0.0, 0.0, 3.15],
    [0.8, 0.0, 3.15], [0.8, -0.45, 3.15], [0.45, -0.8, 3.15],
    [0.0, -0.8, 3.15], [0.0, 0.0, 2.85], [0.2, 0.0, 2.7],
    [0.2, -0.112, 2.7], [0.112, -0.2, 2.7], [0.0, -0.2, 2.7],
    [-0.45, -0.8, 3.15], [-0.8, -0.45, 3.15], [-0.8, 0.0, 3.15],
    [-0.112, -0.2, 2.7], [-0.2, -0.112, 2.7], [-0.2, 0.0, 2.7],
    [-0.8, 0.45, 3.15], [-0.45, 0.8, 3.15], [0.0, 0.8, 3.15],
    [-0.2, 0.112, 2.7], [-0.112, 0.2, 2.7], [0.0, 0.2, 2.7],
    [0.45, 0.8, 3.15], [0.8, 0.45, 3.15], [0.112, 0.2, 2.7],
    [0.2, 0.112, 2.7], [0.4, 0.0, 2.55], [0.4, -0.224, 2.55],
    [0.224, -0.4, 2.55], [0.0, -0.4, 2.55], [1.3, 0.0, 2.55],
    [1.3, -0.728, 2.55], [0.728, -1.3, 2.55], [0.0, -1.3, 2.55],
    [1.3, 0.0, 2.4], [1.3, -0.728, 2.4], [0.728, -1.3, 2.4],
    [0.0, -1.3, 2.4], [-0.224, -0.4, 2.55], [-0.4, -0.224, 2.55],
    [-0.4, 0.0, 2.55], [-0.728, -1.3, 2.55], [-1.3, -0.728, 2.55],
    [-1.3, 0.0, 2.55], [-0.728, -1.3, 2.4], [-1.3, -0.728, 2.4],
    [-1.3, 0.0, 2.4], [-0.4, 0.224, 2.55], [-0.224, 0.4, 2.55],
    [0.0, 0.4, 2.55], [-1.3, 0.728, 2.55], [-0.728, 1.3, 2.55],
    [0.0, 1.3, 2.55], [-1.3, 0.728, 2.4], [-0.728, 1.3, 2.4],
    [0.0, 1.3, 2.4], [0.224, 0.4, 2.55], [0.4, 0.224, 2.55],
    [0.728, 1.3, 2.55], [1.3, 0.728, 2.55], [0.728, 1.3, 2.4],
    [1.3, 0.728, 2.4], [0.0, 0.0, 0.0], [1.425, 0.0, 0.0],
    [1.425, 0.798, 0.0], [0.798, 1.425, 0.0], [0.0, 1.425, 0.0],
    [1.5, 0.0, 0.075], [1.5, 0.84, 0.075], [0.84, 1.5, 0.075],
    [0.0, 1.5, 0.075], [-0.798, 1.425, 0.0], [-1.425, 0.798, 0.0],
    [-1.425, 0.0, 0.0], [-0.84, 1.5, 0.075], [-1.5, 0.84, 0.075],
    [-1.5, 0.0, 0.075], [-1.425, -0.798, 0.0], [-0.798, -1.425, 0.0],
    [0.0, -1.425, 0.0], [-1.5, -0.84, 0.075], [-0.84, -1.5, 0.075],
    [0.0, -1.5, 0.075], [0.798, -1.425, 0.0], [1.425, -0.798, 0.0],
    [0.84, -1.5, 0.075], [1.5, -0.84, 0.075],
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::{assert_material_runs, counts};

    fn patches(scene: &Scene) -> Vec<(&[Vec3], &[Vec3])> {
        scene
            .objects
            .iter()
            .filter_map(|o| match &o.primitive {
                Primitive::Patch { vertices, normals } => Some((&vertices[..], &normals[..])),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn counts_per_level() {
        for level in [2, 3, 12] {
            let scene = generate(level);
            let n = level as usize;
            assert_eq!(counts(&scene), (0, 0, n * n, 0), "squares at {level}");
            assert_eq!(
                patches(&scene).len() as u64,
                triangle_count(level),
                "level {level}"
            );
            assert_material_runs(&scene);
        }
        // SPD's own table: 240 patches at 2, 552 at 3, 9120 at 12.
        assert_eq!([2, 3, 12].map(triangle_count), [240, 552, 9120]);
        assert_eq!(triangle_count(40), 102_080);
    }

    /// Every triangle winds the way its corner normals face (its edges'
    /// cross product is on their side), so smooth shading never flips to
    /// flat; the pot stands on the board, 3.15 high (the knob), from the
    /// handle's back (x = -3) to the spout's tip (x = 3.45 or so).
    #[test]
    fn triangles_wind_with_their_normals_and_the_pot_stands_on_the_board() {
        let scene = generate(6);
        let mut lo = Vec3::INFINITY;
        let mut hi = Vec3::NEG_INFINITY;
        for (v, n) in patches(&scene) {
            let face = (v[1] - v[0]).cross(v[2] - v[0]);
            let sum = n[0] + n[1] + n[2];
            assert!(face.dot(sum) > 0.0, "{v:?} {n:?}");
            for p in v {
                lo = lo.min(*p);
                hi = hi.max(*p);
            }
        }
        assert!(lo.z.abs() < 1e-6 && (hi.z - 3.15).abs() < 1e-5, "{lo} {hi}");
        assert!(
            (lo.x + 3.0).abs() < 0.05 && hi.x > 3.3 && hi.x < 3.5,
            "{lo} {hi}"
        );
    }

    #[test]
    fn a_patch_passes_through_its_corner_control_points() {
        let control = control_points(&PATCHES[0]);
        for (s, t, corner) in [(0.0, 0.0, 0), (0.0, 1.0, 3), (1.0, 0.0, 12), (1.0, 1.0, 15)] {
            assert!((point(&control, s, t).0 - control[corner]).length() < 1e-12);
        }
    }
}
