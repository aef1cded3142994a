//! The fractal mountain (SPD `mount.c`): Carpenter's midpoint displacement.
//! A square made of two triangles is subdivided `level` times, each
//! triangle into four through its edge midpoints; every new midpoint is the
//! average of its edge's ends plus a Gaussian offset that shrinks with the
//! edge length as `length^H` (H = 3 - fractal dimension 2.2); the first
//! centre point is lifted so the noise rises into a peak. A pyramid of
//! four glass spheres rests on the slope.

use std::ops::RangeInclusive;

use glam::Vec3;

use super::common::{Rng, SPD_BACKGROUND, SceneBuilder, material, spd_view};
use crate::scene::{Primitive, Scene};

/// Level = subdivision steps; 2 * 4^level triangles (level 9: 524,288).
pub(super) const LEVELS: RangeInclusive<u32> = 0..=9;

/// Hurst exponent, 3 - the SPD's fractal dimension 2.2.
const HURST: f64 = 0.8;
/// Standard deviation of the offset on an edge of length 1.
const ROUGHNESS: f64 = 0.15;
/// Extra height of the first centre point, so the noise makes a mountain.
const PEAK: f64 = 0.45;
const SPHERE_RADIUS: f32 = 0.12;
/// Where the sphere pyramid stands: on the slope facing the camera.
const PYRAMID_AT: (f32, f32) = (-0.45, 0.45);

pub(super) fn triangle_count(level: u32) -> u64 {
    2 * 4u64.pow(level)
}

pub(super) fn describe(level: u32) -> String {
    format!(
        "fractal mountain of {} triangles in one mesh with 4 glass spheres, 1 light",
        triangle_count(level)
    )
}

/// Heights on a (2^level + 1)^2 grid over [-1, 1]^2, row-major by y.
/// Triangles split each cell along its (+1, +1) diagonal, which is exactly
/// what repeated four-way splitting of the two base triangles produces, so
/// every shared edge gets its midpoint once.
struct Terrain {
    n: usize,
    heights: Vec<f32>,
}

impl Terrain {
    fn new(level: u32, rng: &mut Rng) -> Self {
        let n = 1usize << level;
        let w = n + 1;
        let mut h = vec![0f32; w * w];
        let mut step = n;
        while step > 1 {
            let half = step / 2;
            let length = 2.0 * step as f64 / n as f64;
            let sigma = ROUGHNESS * length.powf(HURST);
            let lift = if step == n { PEAK } else { 0.0 };
            let mut displace = |h: &mut [f32], (x, y): (usize, usize), a: usize, b: usize| {
                let mid = 0.5 * (h[a] as f64 + h[b] as f64) + sigma * rng.gaussian();
                h[y * w + x] = mid as f32;
            };
            for y in (0..=n).step_by(step) {
                for x in (0..n).step_by(step) {
                    let (a, b) = (y * w + x, y * w + x + step);
                    displace(&mut h, (x + half, y), a, b);
                }
            }
            for y in (0..n).step_by(step) {
                for x in (0..=n).step_by(step) {
                    let (a, b) = (y * w + x, (y + step) * w + x);
                    displace(&mut h, (x, y + half), a, b);
                }
            }
            for y in (0..n).step_by(step) {
                for x in (0..n).step_by(step) {
                    let (a, b) = (y * w + x, (y + step) * w + x + step);
                    displace(&mut h, (x + half, y + half), a, b);
                    h[(y + half) * w + x + half] += lift as f32;
                }
            }
            step = half;
        }
        Self { n, heights: h }
    }

    fn coord(&self, i: usize) -> f32 {
        -1.0 + 2.0 * i as f32 / self.n as f32
    }

    /// Highest vertex within `radius` (plus one cell) of (x, y): triangles
    /// interpolate their vertices, so nothing there is higher.
    fn max_height_near(&self, x: f32, y: f32, radius: f32) -> f32 {
        let reach = radius + 2.0 / self.n as f32;
        let w = self.n + 1;
        let mut best = f32::NEG_INFINITY;
        for j in 0..w {
            for i in 0..w {
                let (dx, dy) = (self.coord(i) - x, self.coord(j) - y);
                if dx * dx + dy * dy <= reach * reach {
                    best = best.max(self.heights[j * w + i]);
                }
            }
        }
        best
    }

    fn mesh(self) -> Primitive {
        let (n, w) = (self.n, self.n + 1);
        let vertices = (0..w * w)
            .map(|k| Vec3::new(self.coord(k % w), self.coord(k / w), self.heights[k]))
            .collect();
        let mut triangles = Vec::with_capacity(2 * n * n);
        for y in 0..n {
            for x in 0..n {
                let a = (y * w + x) as u32;
                let (b, c, d) = (a + 1, a + 1 + w as u32, a + w as u32);
                triangles.push([a, b, c]);
                triangles.push([a, c, d]);
            }
        }
        Primitive::Mesh {
            vertices,
            triangles,
        }
    }
}

pub(super) fn generate(level: u32, seed: u64) -> Scene {
    let mut view = spd_view(Vec3::new(-1.6, 1.6, 1.7), Vec3::ZERO);
    view.focal = 0.7;
    let mut b = SceneBuilder::new(view, SPD_BACKGROUND);
    b.light(Vec3::new(-100.0, -100.0, 100.0));
    let terrain = Terrain::new(level, &mut Rng::new(seed));

    // Three spheres touching each other, a fourth resting on them.
    let (px, py) = PYRAMID_AT;
    let r = SPHERE_RADIUS;
    let spread = 2.0 * r / 3f32.sqrt();
    let feet: Vec<(f32, f32)> = (0..3)
        .map(|k| {
            let a = k as f32 * std::f32::consts::TAU / 3.0;
            (px + spread * a.cos(), py + spread * a.sin())
        })
        .collect();
    let ground = feet
        .iter()
        .map(|&(x, y)| terrain.max_height_near(x, y, r))
        .fold(f32::NEG_INFINITY, f32::max);
    let base_z = ground + r + 0.01;
    b.material(material(Vec3::ONE, 0.1, 0.1, 100.0, 0.9, 1.5));
    b.add(sphere(Vec3::new(
        px,
        py,
        base_z + r * (8.0f32 / 3.0).sqrt(),
    )));
    for (x, y) in feet {
        b.add(sphere(Vec3::new(x, y, base_z)));
    }

    b.material(material(
        Vec3::new(0.5, 0.45, 0.35),
        1.0,
        0.0,
        1000.0,
        0.0,
        1.0,
    ));
    b.add(terrain.mesh());
    b.finish()
}

fn sphere(centre: Vec3) -> Primitive {
    Primitive::Sphere {
        centre,
        radius: SPHERE_RADIUS,
        inside_only: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::common::test_util::counts;

    fn mesh(scene: &Scene) -> (&[Vec3], &[[u32; 3]]) {
        scene
            .objects
            .iter()
            .find_map(|o| match &o.primitive {
                Primitive::Mesh {
                    vertices,
                    triangles,
                } => Some((vertices.as_slice(), triangles.as_slice())),
                _ => None,
            })
            .expect("a mesh")
    }

    #[test]
    fn triangle_counts_per_level() {
        for level in 0..=6 {
            let scene = generate(level, 1);
            assert_eq!(counts(&scene), (4, 0, 0, triangle_count(level) as usize));
            let (v, _) = mesh(&scene);
            assert_eq!(v.len(), ((1 << level) + 1usize).pow(2));
        }
        assert_eq!(triangle_count(8), 131_072);
    }

    #[test]
    fn top_level_exceeds_100k_triangles_with_valid_indices() {
        let scene = generate(8, 0);
        let (v, t) = mesh(&scene);
        assert!(t.len() > 100_000);
        assert!(t.iter().flatten().all(|&i| (i as usize) < v.len()));
        assert!(v.iter().all(|p| p.is_finite() && p.z.abs() < 3.0));
    }

    #[test]
    fn seed_changes_the_terrain() {
        assert_eq!(generate(4, 5), generate(4, 5));
        assert_ne!(mesh(&generate(4, 5)).0, mesh(&generate(4, 6)).0);
    }

    #[test]
    fn spheres_rest_above_the_terrain() {
        for seed in 0..8 {
            let scene = generate(5, seed);
            let (v, _) = mesh(&scene);
            for o in &scene.objects {
                if let Primitive::Sphere { centre, radius, .. } = o.primitive {
                    let below = v.iter().filter(|p| {
                        (p.truncate() - centre.truncate()).length() <= radius + 2.0 / 32.0
                    });
                    assert!(below.into_iter().all(|p| p.z < centre.z - radius));
                }
            }
        }
    }
}
