//! The three structures must find exactly the same hits: same shape, same
//! `t`, for random scenes and random rays.

use glam::Vec3A;
use proptest::prelude::*;

use super::{AccelKind, SceneIndex};
use crate::geometry::{AaBox, Plane, Ray, Shape, Sphere, Triangle};
use crate::stats::Counters;

/// A deterministic generator of scene parts (xorshift), so a failing case
/// is reproducible from its seed.
struct Rand(u64);

impl Rand {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn point(&mut self, scale: f32) -> Vec3A {
        Vec3A::new(self.next(), self.next(), self.next()) * (2.0 * scale) - scale
    }
}

fn random_shapes(seed: u64, count: usize, with_plane: bool) -> Vec<Shape> {
    let mut r = Rand(seed.max(1));
    let mut shapes = Vec::new();
    for i in 0..count {
        let c = r.point(10.0);
        let size = 0.05 + r.next() * 1.5;
        let shape = match i % 3 {
            0 => Some(Shape::Sphere(Sphere::new(c, size))),
            1 => Triangle::new(c, c + r.point(size), c + r.point(size)).map(Shape::Triangle),
            _ => Some(Shape::Box(AaBox::new(c, c + Vec3A::splat(size)))),
        };
        shapes.extend(shape);
    }
    if with_plane {
        shapes.extend(
            Plane::from_points([
                Vec3A::new(0.0, -9.0, 0.0),
                Vec3A::new(1.0, -9.0, 0.0),
                Vec3A::new(0.0, -9.0, 1.0),
            ])
            .map(Shape::Plane),
        );
    }
    shapes
}

fn indices(shapes: &[Shape]) -> Vec<SceneIndex> {
    vec![
        SceneIndex::build(shapes, AccelKind::None, 2.0),
        SceneIndex::build(shapes, AccelKind::Grid, 2.0),
        SceneIndex::build(shapes, AccelKind::Grid, 0.3),
        SceneIndex::build(shapes, AccelKind::Grid, 7.0),
        SceneIndex::build(shapes, AccelKind::Bvh, 2.0),
    ]
}

fn check_rays(shapes: &[Shape], seed: u64, rays: usize) {
    let indices = indices(shapes);
    let mut r = Rand(seed ^ 0x5555);
    for _ in 0..rays {
        // Rays from inside and outside the scene, some axis-aligned.
        let origin = r.point(14.0);
        let mut dir = r.point(1.0);
        if r.next() < 0.1 {
            dir = Vec3A::new(dir.x, 0.0, 0.0);
        }
        if dir.length_squared() < 1e-6 {
            continue;
        }
        let ray = Ray::new(origin, dir);
        let t_max = if r.next() < 0.3 { 5.0 } else { f32::INFINITY };
        let mut counters = Counters::default();
        let reference = indices[0].closest_hit(shapes, &ray, 0.0, t_max, &mut counters);
        let any_reference = indices[0].any_hit(shapes, &ray, 0.0, t_max, &mut counters);
        assert_eq!(any_reference, reference.is_some());
        for index in &indices[1..] {
            let hit = index.closest_hit(shapes, &ray, 0.0, t_max, &mut counters);
            assert_eq!(hit, reference, "{:?} on {ray:?}", index.kind());
            let any = index.any_hit(shapes, &ray, 0.0, t_max, &mut counters);
            assert_eq!(any, any_reference, "{:?} on {ray:?}", index.kind());
        }
    }
}

#[test]
fn structures_agree_on_random_scenes() {
    for (seed, count) in [(1, 1), (2, 7), (3, 60), (4, 400), (5, 2000)] {
        check_rays(&random_shapes(seed, count, seed % 2 == 0), seed, 3000);
    }
}

#[test]
fn structures_handle_an_empty_scene_and_planes_only() {
    check_rays(&[], 9, 100);
    check_rays(&random_shapes(9, 0, true), 9, 100);
}

#[test]
fn bvh_is_valid() {
    for (seed, count) in [(1, 1), (2, 2), (3, 100), (4, 5000)] {
        let shapes = random_shapes(seed, count, false);
        let ids: Vec<u32> = (0..shapes.len() as u32).collect();
        let bvh = super::Bvh::build(&shapes, &ids, &super::BvhParams::default());
        bvh.validate().unwrap();
    }
    // Many identical primitives cannot be separated by any plane.
    let same: Vec<Shape> = (0..500)
        .map(|_| Shape::Sphere(Sphere::new(Vec3A::ONE, 1.0)))
        .collect();
    let ids: Vec<u32> = (0..500).collect();
    super::Bvh::build(&same, &ids, &super::BvhParams::default())
        .validate()
        .unwrap();
}

#[test]
fn grid_statistics_count_references() {
    let shapes = random_shapes(11, 300, false);
    let index = SceneIndex::build(&shapes, AccelKind::Grid, 2.0);
    let grid = index.info().grid.unwrap();
    let cells = grid.cells.iter().map(|&c| c as u64).product::<u64>();
    assert!(grid.references >= shapes.len() as u64);
    assert!(grid.empty_cells < cells);
    assert!(grid.mean_per_cell >= 1.0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn structures_agree(seed in 1u64..u64::MAX, count in 0usize..300, plane in any::<bool>()) {
        check_rays(&random_shapes(seed, count, plane), seed, 200);
    }
}
