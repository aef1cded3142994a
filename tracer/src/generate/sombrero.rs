//! A sombrero (after SPD `sombrero.c`): the height field of a damped
//! cosine ripple, `z = cos(k r) e^(-r / d)`, as one triangle mesh over a
//! square grid, under a coloured ring of lights. Many small triangles of
//! nearly equal size, tilted every which way: a well-behaved mesh case.

use std::f64::consts::TAU;
use std::ops::RangeInclusive;

use glam::Vec3;

use super::common::{SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = grid resolution: (2^level)^2 cells, 2 triangles each (level 7:
/// 32,768 triangles, level 10: 2,097,152).
pub(super) const LEVELS: RangeInclusive<u32> = 2..=10;

/// Half the side of the square grid.
const HALF_SIZE: f64 = 4.0;
/// Ripples out to the grid's edge.
const WAVES: f64 = 3.0;
/// Distance over which the ripple's height falls by e.
const DAMPING: f64 = 2.5;

/// Triangles at `level`.
pub(super) fn triangle_count(level: u32) -> u64 {
    2 << (2 * level)
}

pub(super) fn describe(level: u32) -> String {
    format!(
        "sombrero: a damped ripple height field of {} triangles in one mesh, 3 coloured lights",
        triangle_count(level)
    )
}

/// Height of the ripple at `(x, y)`.
fn height(x: f64, y: f64) -> f64 {
    let r = x.hypot(y);
    let k = TAU * WAVES / HALF_SIZE;
    (k * r).cos() * (-r / DAMPING).exp()
}

pub(super) fn generate(level: u32) -> Scene {
    let view = spd_view(Vec3::new(0.0, -9.0, 5.5), Vec3::new(0.0, 0.0, -0.3));
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    for i in 0..3 {
        let a = TAU * i as f64 / 3.0;
        b.light(Vec3::new(
            (6.0 * a.sin()) as f32,
            (-6.0 * a.cos()) as f32,
            6.0,
        ));
    }
    b.material(material(Vec3::new(0.9, 0.8, 0.5), 0.8, 0.2, 30.0, 0.0, 1.0));

    let cells = 1u32 << level;
    let side = cells + 1;
    let step = 2.0 * HALF_SIZE / cells as f64;
    let vertices = (0..side * side)
        .map(|i| {
            let x = -HALF_SIZE + (i % side) as f64 * step;
            let y = -HALF_SIZE + (i / side) as f64 * step;
            Vec3::new(x as f32, y as f32, height(x, y) as f32)
        })
        .collect();
    let mut triangles = Vec::with_capacity(triangle_count(level) as usize);
    for row in 0..cells {
        for col in 0..cells {
            let a = row * side + col;
            let (b, c, d) = (a + 1, a + side, a + side + 1);
            triangles.push([a, b, d]);
            triangles.push([a, d, c]);
        }
    }
    b.add(Primitive::Mesh {
        vertices,
        triangles,
    });
    b.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::counts;

    #[test]
    fn counts_per_level() {
        for level in [2, 4] {
            let n = triangle_count(level) as usize;
            assert_eq!(counts(&generate(level)), (0, 0, 0, n));
        }
        assert_eq!(triangle_count(7), 32768);
    }

    #[test]
    fn the_ripple_peaks_in_the_middle_and_dies_out() {
        assert_eq!(height(0.0, 0.0), 1.0);
        assert!(height(HALF_SIZE, 0.0).abs() < 0.3);
    }
}
