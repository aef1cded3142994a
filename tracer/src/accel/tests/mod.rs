//! The three structures must find exactly the same hits: same shape, same
//! `t`, for random scenes and random rays. The scenes mix every bounded
//! primitive (spheres, triangles, boxes, cones, open cylinders) with
//! randomly oriented planes; the rays start outside the scene, inside a
//! grid cell, inside a primitive and on a primitive's bounding-box corner,
//! run along every axis in both directions or anywhere, and many start
//! their interval at a `t_min` inside the scene, so the grid begins its
//! walk mid-grid.

mod refit;

use glam::Vec3A;
use proptest::prelude::*;

use super::{AccelKind, SceneIndex};
use crate::geometry::{AaBox, Aabb, Cone, Plane, Ray, Shape, Sphere, Triangle};
use crate::stats::Counters;

/// A deterministic generator of scene parts (xorshift), so a failing case
/// is reproducible from its seed.
pub(super) struct Rand(pub(super) u64);

impl Rand {
    pub(super) fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    pub(super) fn point(&mut self, scale: f32) -> Vec3A {
        Vec3A::new(self.next(), self.next(), self.next()) * (2.0 * scale) - scale
    }

    /// One of `0..n`.
    pub(super) fn below(&mut self, n: usize) -> usize {
        ((self.next() * n as f32) as usize).min(n.saturating_sub(1))
    }

    /// A unit vector along one of the six axis directions.
    fn axis_direction(&mut self) -> Vec3A {
        let mut dir = Vec3A::ZERO;
        dir[self.below(3)] = if self.next() < 0.5 { -1.0 } else { 1.0 };
        dir
    }
}

/// `count` bounded primitives of every kind in a cube of side 20, plus
/// `planes` randomly oriented planes through points of that cube.
pub(super) fn random_shapes(seed: u64, count: usize, planes: usize) -> Vec<Shape> {
    let mut r = Rand(seed.max(1));
    let mut shapes = Vec::new();
    for i in 0..count {
        let c = r.point(10.0);
        let size = 0.05 + r.next() * 1.5;
        let shape = match i % 5 {
            0 => Some(Shape::Sphere(Sphere::new(c, size))),
            1 => Triangle::new(c, c + r.point(size), c + r.point(size)).map(Shape::Triangle),
            2 => Some(Shape::Box(AaBox::new(c, c + Vec3A::splat(size)))),
            // A cone (to a tip, or truncated) along a random axis.
            3 => {
                let apex_radius = if r.next() < 0.5 { 0.0 } else { r.next() * size };
                Cone::new(c, size, c + r.point(2.0 * size), apex_radius).map(Shape::Cone)
            }
            // An open cylinder, sometimes along a coordinate axis.
            _ => {
                let axis = if r.next() < 0.3 {
                    r.axis_direction() * (2.0 * size)
                } else {
                    r.point(2.0 * size)
                };
                Cone::new(c, 0.5 * size, c + axis, 0.5 * size).map(Shape::Cone)
            }
        };
        shapes.extend(shape);
    }
    for _ in 0..planes {
        let p = r.point(9.0);
        shapes
            .extend(Plane::from_points([p, p + r.point(1.0), p + r.point(1.0)]).map(Shape::Plane));
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

/// The boxes of the bounded shapes, and the scene's box around them
/// (empty when there are none).
pub(super) fn boxes_and_bounds(shapes: &[Shape]) -> (Vec<Aabb>, Aabb) {
    let boxes: Vec<Aabb> = shapes.iter().filter_map(Shape::bounds).collect();
    let bounds = boxes.iter().fold(Aabb::empty(), |acc, b| acc.union(b));
    (boxes, bounds)
}

/// A ray and its `(t_min, t_max)` interval, as the renderer could ask, in
/// a scene of primitives with boxes `bounded` inside `bounds`.
pub(super) fn random_query(
    r: &mut Rand,
    bounded: &[Aabb],
    bounds: &Aabb,
) -> Option<(Ray, f32, f32)> {
    let origin = match (r.below(4), bounded.is_empty()) {
        // Inside a primitive: the centre of its box lies inside every
        // sphere, box, cylinder and cone generated above.
        (0, false) => bounded[r.below(bounded.len())].centre(),
        // On a corner of a primitive's box, where cells and slabs meet.
        (1, false) => {
            let b = bounded[r.below(bounded.len())];
            Vec3A::select(r.point(1.0).cmpge(Vec3A::ZERO), b.max, b.min)
        }
        // Inside a grid cell: anywhere in the scene's box.
        (2, false) => bounds.min + bounds.extent() * (r.point(0.5) + 0.5),
        // From inside or outside the scene.
        _ => r.point(14.0),
    };
    let dir = if r.next() < 0.35 {
        r.axis_direction()
    } else {
        r.point(1.0)
    };
    if dir.length_squared() < 1e-6 {
        return None;
    }
    let ray = Ray::new(origin, dir);
    // Half the rays start their interval somewhere inside the scene's box.
    let t_min = match bounds.intersect(&ray, 0.0, f32::INFINITY) {
        Some((near, far)) if r.next() < 0.5 => near + (far - near) * r.next(),
        _ => 0.0,
    };
    let t_max = if r.next() < 0.3 {
        t_min + 5.0
    } else {
        f32::INFINITY
    };
    Some((ray, t_min, t_max))
}

fn check_rays(shapes: &[Shape], seed: u64, rays: usize) {
    let indices = indices(shapes);
    let (boxes, bounds) = boxes_and_bounds(shapes);
    let mut r = Rand(seed ^ 0x5555);
    for _ in 0..rays {
        let Some((ray, t_min, t_max)) = random_query(&mut r, &boxes, &bounds) else {
            continue;
        };
        let mut counters = Counters::default();
        let reference = indices[0].closest_hit(shapes, &ray, t_min, t_max, &mut counters);
        let any_reference = indices[0].any_hit(shapes, &ray, t_min, t_max, &mut counters);
        assert_eq!(any_reference, reference.is_some());
        for index in &indices[1..] {
            let hit = index.closest_hit(shapes, &ray, t_min, t_max, &mut counters);
            assert_eq!(
                hit,
                reference,
                "{:?} on {ray:?} in ({t_min}, {t_max})",
                index.kind()
            );
            let occluder = index.occluder(shapes, &ray, t_min, t_max, &mut counters);
            assert_eq!(
                occluder.is_some(),
                any_reference,
                "{:?} on {ray:?} in ({t_min}, {t_max})",
                index.kind()
            );
            // The occluder reported is one the ray really meets.
            if let Some(id) = occluder {
                let t = shapes[id as usize].intersect(&ray, t_min, t_max);
                assert!(t.is_some(), "{:?}: {id} is no occluder", index.kind());
            }
        }
    }
}

#[test]
fn structures_agree_on_random_scenes() {
    for (seed, count, planes) in [(1, 1, 0), (2, 7, 1), (3, 60, 0), (4, 400, 2), (5, 2000, 1)] {
        check_rays(&random_shapes(seed, count, planes), seed, 3000);
    }
}

#[test]
fn structures_handle_an_empty_scene_and_planes_only() {
    check_rays(&[], 9, 100);
    check_rays(&random_shapes(9, 0, 3), 9, 300);
}

/// A ray whose interval starts mid-grid must walk from the cell at
/// `t_min`, not from where the ray enters the grid: the cells it visits
/// are those of the same ray started at `ray.at(t_min)` (give or take the
/// one cell a rounded start point can land in).
#[test]
fn the_grid_walk_starts_at_t_min() {
    let shapes = random_shapes(21, 600, 0);
    let (_, bounds) = boxes_and_bounds(&shapes);
    let grid = SceneIndex::build(&shapes, AccelKind::Grid, 2.0);
    let mut r = Rand(21);
    let mut checked = 0;
    for _ in 0..2000 {
        let ray = Ray::new(r.point(14.0), r.point(1.0));
        let Some((near, far)) = bounds.intersect(&ray, 0.0, f32::INFINITY) else {
            continue;
        };
        let t_min = near + (far - near) * r.next();
        let shifted = Ray::new(ray.at(t_min), ray.dir);
        let (mut from_t_min, mut from_start) = (Counters::default(), Counters::default());
        grid.any_hit(&shapes, &ray, t_min, f32::INFINITY, &mut from_t_min);
        grid.any_hit(&shapes, &shifted, 0.0, f32::INFINITY, &mut from_start);
        assert!(
            from_t_min.nodes_visited <= from_start.nodes_visited + 1,
            "{ray:?} from t = {t_min}: {} cells visited, {} from the start point",
            from_t_min.nodes_visited,
            from_start.nodes_visited
        );
        checked += 1;
    }
    assert!(checked > 500, "only {checked} rays met the scene");
}

#[test]
fn bvh_is_valid() {
    for (seed, count) in [(1, 1), (2, 2), (3, 100), (4, 5000)] {
        let shapes = random_shapes(seed, count, 0);
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
    let shapes = random_shapes(11, 300, 0);
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
    fn structures_agree(seed in 1u64..u64::MAX, count in 0usize..300, planes in 0usize..3) {
        check_rays(&random_shapes(seed, count, planes), seed, 200);
    }
}
