//! Refits: after random moves of random objects (runs of shapes), a
//! refitted BVH finds exactly the hits, and any-hit answers, of a BVH
//! built over the moved shapes and of brute force (a grid, which refuses
//! refits, is built again); the BVH stays valid (every primitive reached
//! once, every box around its children); a refit that would make the tree
//! much worse or change the shapes' count is refused. And the world says
//! which shapes an edit changed, which is what the refit follows.

use std::ops::Range;

use glam::Vec3A;
use proptest::prelude::*;

use super::{Rand, boxes_and_bounds, random_query, random_shapes};
use crate::accel::{AccelKind, SceneIndex, Structure};
use crate::geometry::{AaBox, Cone, Shape, Sphere, Triangle};
use crate::scene::edit::Edit;
use crate::scene::{Limits, parse_scene};
use crate::stats::Counters;
use crate::world::{ShapeChange, World};

/// `shape` moved by `by`, and for a sphere its radius scaled by `scale`;
/// unbounded shapes (planes) stay (nothing holds them but the list on the
/// side), as does a shape that would become degenerate.
fn moved(shape: &Shape, by: Vec3A, scale: f32) -> Shape {
    let moved = match shape {
        Shape::Sphere(s) => Some(Shape::Sphere(Sphere::new(s.centre + by, s.radius * scale))),
        Shape::Triangle(t) => {
            Triangle::new(t.v0 + by, t.v0 + t.e1 + by, t.v0 + t.e2 + by).map(Shape::Triangle)
        }
        Shape::Box(b) => Some(Shape::Box(AaBox::new(b.bounds.min + by, b.bounds.max + by))),
        Shape::Cone(c) => {
            Cone::new(c.base + by, c.base_radius, c.apex + by, c.apex_radius).map(Shape::Cone)
        }
        _ => None,
    };
    moved.unwrap_or_else(|| shape.clone())
}

/// The closest hits and any-hit answers of `index` are those of brute
/// force over `shapes` on `rays` random queries.
fn assert_same_hits(index: &SceneIndex, shapes: &[Shape], seed: u64, rays: usize) {
    let reference = SceneIndex::build(shapes, AccelKind::None, 2.0);
    let (boxes, bounds) = boxes_and_bounds(shapes);
    let mut r = Rand(seed | 1);
    let counters = &mut Counters::default();
    for _ in 0..rays {
        let Some((ray, t_min, t_max)) = random_query(&mut r, &boxes, &bounds) else {
            continue;
        };
        let expected = reference.closest_hit(shapes, &ray, t_min, t_max, counters);
        let hit = index.closest_hit(shapes, &ray, t_min, t_max, counters);
        assert_eq!(
            hit,
            expected,
            "{:?} on {ray:?} in ({t_min}, {t_max})",
            index.kind()
        );
        let occluder = index.occluder(shapes, &ray, t_min, t_max, counters);
        assert_eq!(
            occluder.is_some(),
            expected.is_some(),
            "{:?} on {ray:?}",
            index.kind()
        );
        if let Some(id) = occluder {
            let t = shapes[id as usize].intersect(&ray, t_min, t_max);
            assert!(t.is_some(), "{:?}: {id} is no occluder", index.kind());
        }
    }
}

/// The BVH's invariants, for a BVH index.
fn assert_valid(index: &SceneIndex) {
    if let Structure::Bvh(bvh) = &index.structure {
        bvh.validate().unwrap();
    }
}

/// Objects as runs of 1 to 6 consecutive shapes.
fn objects(count: usize, r: &mut Rand) -> Vec<Range<u32>> {
    let mut objects = Vec::new();
    let mut start = 0;
    while start < count {
        let end = (start + 1 + (r.next() * 6.0) as usize).min(count);
        objects.push(start as u32..end as u32);
        start = end;
    }
    objects
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Random objects moved in turn, each refit following the last (or a
    /// build where it is refused): the hits are those of brute force and
    /// of a structure built afresh over the moved shapes.
    #[test]
    fn refitted_structures_find_what_a_build_finds(
        seed in 1u64..u64::MAX,
        count in 1usize..400,
        planes in 0usize..3,
        moves in 1usize..5,
    ) {
        let mut shapes = random_shapes(seed, count, planes);
        let mut r = Rand(seed ^ 0xabcd);
        let objects = objects(shapes.len(), &mut r);
        let mut indices = [
            SceneIndex::build(&shapes, AccelKind::None, 2.0),
            SceneIndex::build(&shapes, AccelKind::Grid, 2.0),
            SceneIndex::build(&shapes, AccelKind::Bvh, 2.0),
        ];
        let mut refitted = [0; 3];
        for _ in 0..moves {
            let object = objects[r.below(objects.len())].clone();
            // Mostly small moves, which refit; some far ones, which may not.
            let reach = if r.next() < 0.8 { 1.0 } else { 15.0 };
            let by = r.point(reach);
            let scale = if r.next() < 0.3 { 0.5 + r.next() } else { 1.0 };
            for id in object.clone() {
                shapes[id as usize] = moved(&shapes[id as usize], by, scale);
            }
            for (index, refits) in indices.iter_mut().zip(&mut refitted) {
                *index = match index.refit(&shapes, object.clone()) {
                    Some(refit) => {
                        *refits += 1;
                        refit
                    }
                    None => SceneIndex::build(&shapes, index.kind(), 2.0),
                };
            }
        }
        prop_assert_eq!(refitted[0], moves, "brute force always refits");
        prop_assert_eq!(refitted[1], 0, "a grid is built again");
        let built = SceneIndex::build(&shapes, AccelKind::Bvh, 2.0);
        for index in indices.iter().chain([&built]) {
            assert_valid(index);
            assert_same_hits(index, &shapes, seed, 300);
            prop_assert_eq!(index.info().unbounded, built.info().unbounded);
        }
    }
}

/// Translating every shape at once keeps the tree's cost: the refit is
/// taken, keeps every node, and hits what brute force hits.
#[test]
fn a_translated_scene_refits_to_the_same_tree_moved() {
    let shapes = random_shapes(7, 1500, 1);
    let index = SceneIndex::build(&shapes, AccelKind::Bvh, 2.0);
    let by = Vec3A::new(3.0, -1.5, 0.25);
    let moved: Vec<Shape> = shapes.iter().map(|s| moved(s, by, 1.0)).collect();
    let refit = index
        .refit(&moved, 0..moved.len() as u32)
        .expect("a translation keeps the tree's cost");
    assert_eq!(refit.info().bvh_nodes, index.info().bvh_nodes);
    assert_valid(&refit);
    assert_same_hits(&refit, &moved, 7, 3000);
}

/// One sphere among many carried far across the scene stretches every box
/// from its old leaf to the root around it: refused, where a short move
/// of the same sphere is refitted. A grid refuses any.
#[test]
fn a_refit_that_would_degrade_the_tree_is_refused() {
    let spheres = |far: Option<Vec3A>| -> Vec<Shape> {
        let mut shapes: Vec<Shape> = (0..4096)
            .map(|i| {
                let c = Vec3A::new((i % 16) as f32, (i / 16 % 16) as f32, (i / 256) as f32);
                Shape::Sphere(Sphere::new(c, 0.3))
            })
            .collect();
        if let Some(centre) = far {
            shapes[0] = Shape::Sphere(Sphere::new(centre, 0.3));
        }
        shapes
    };
    let shapes = spheres(None);
    let index = SceneIndex::build(&shapes, AccelKind::Bvh, 2.0);
    let near = spheres(Some(Vec3A::new(0.2, 0.1, 0.0)));
    let refit = index.refit(&near, 0..1).expect("a short move refits");
    assert_valid(&refit);
    assert_same_hits(&refit, &near, 3, 2000);
    // From one corner of the cube of spheres to the other: the boxes on
    // the way up grow to the cube, the tree's cost by 1.2x.
    let across = spheres(Some(Vec3A::new(15.0, 15.0, 15.0)));
    assert!(index.refit(&across, 0..1).is_none());
    // Out of the cube along one edge: the boxes grow along that edge
    // alone, a little dearer, which is taken.
    let out = spheres(Some(Vec3A::new(40.0, 0.0, 0.0)));
    let refit = index.refit(&out, 0..1).expect("a cheaper stretch");
    assert_valid(&refit);
    assert_same_hits(&refit, &out, 4, 2000);
    let grid = SceneIndex::build(&shapes, AccelKind::Grid, 2.0);
    assert!(grid.refit(&near, 0..1).is_none());
}

/// A refit needs the shapes it was built over, in number and boundedness.
#[test]
fn a_refit_over_other_shapes_is_refused() {
    let shapes = random_shapes(5, 50, 2);
    for kind in AccelKind::ALL {
        let index = SceneIndex::build(&shapes, kind, 2.0);
        assert!(index.refit(&shapes[1..], 0..1).is_none(), "{kind:?}");
        assert!(
            index.refit(&shapes, 0..60).is_none(),
            "{kind:?}: past the end"
        );
        // A plane (the last shapes) where a sphere was.
        let mut swapped = shapes.clone();
        swapped.swap(0, 51);
        assert!(index.refit(&swapped, 0..1).is_none(), "{kind:?}");
        let nothing = index.refit(&shapes, 0..0);
        let refits = kind != AccelKind::Grid;
        assert_eq!(nothing.is_some(), refits, "{kind:?}: nothing moved");
    }
}

/// Every kind of object, one per line (object i is line i + 5).
const SCENE: &str = "\
v from 0 -12 3 at 0 0 0 up 0 0 1 angle 40 resolution 32 24
l 4 -4 6
f 1 0 0 0.7 1 1 1 0.3 30 0 1
s -2 0 0 1
s 2 0 0 -0.5
pl 0 0 -1 1 0 -1 0 1 -1
p 4 -1 -1 2 1 -1 2 1 1 2 -1 1 2
pp 3 0 0 3 0 0 1 1 0 3 0 0 1 0 1 3 0 0 1
c 3 3 0 1 3 3 2 0.5
box -4 -4 -1 -3 -3 0
mesh 4 2 0 2 0 1 2 0 1 3 0 0 3 1 1 2 3 1 3 4
";

/// The world says which shapes a move changed: the object's, in place;
/// a material edit none; a shape replaced by one of another kind makes
/// the shapes renumbered. Refitting the scene's structures by what it
/// says finds the hits of a build over the edited scene.
#[test]
fn the_world_says_which_shapes_an_edit_moved() {
    let mut scene = parse_scene(SCENE, None, &Limits::default()).unwrap();
    let mut world = World::build(&scene);
    let mut indices =
        [AccelKind::Grid, AccelKind::Bvh].map(|kind| SceneIndex::build(&world.shapes, kind, 2.0));
    let edits = [
        "object 0 centre -1 0.5 0",
        "object 1 radius 0.75",
        "object 2 translate 0 0 0.5",
        "object 3 translate 0.5 0 0.25",
        "object 4 translate 0 1 0",
        "object 5 translate 0 0 1",
        "object 6 translate -1 0 0",
        "object 7 translate 0.5 0.5 0",
    ];
    for (object, text) in edits.into_iter().enumerate() {
        let owned = |o: &u32| *o as usize == object;
        let start = world.shape_object.iter().position(owned).unwrap() as u32;
        let end = world.shape_object.iter().rposition(owned).unwrap() as u32 + 1;
        let edit = Edit::parse_in(text, &scene).unwrap();
        edit.apply(&mut scene).unwrap();
        let change = world.update_shapes(&scene, &edit);
        assert_eq!(change, ShapeChange::InPlace(start..end), "{text}");
        for index in &mut indices {
            *index = index
                .refit(&world.shapes, start..end)
                .unwrap_or_else(|| SceneIndex::build(&world.shapes, index.kind(), 2.0));
        }
        let built = World::build(&scene);
        for index in &indices {
            assert_valid(index);
            assert_same_hits(index, &built.shapes, 11, 500);
        }
    }
    let edit = Edit::parse_in("object 0 kd 0.5", &scene).unwrap();
    edit.apply(&mut scene).unwrap();
    assert_eq!(world.update_shapes(&scene, &edit), ShapeChange::None);
    // The sphere becomes a box: one shape still, of another kind.
    let edit = Edit::parse_in("object 0 shape box 0 0 0 1 1 1", &scene).unwrap();
    edit.apply(&mut scene).unwrap();
    assert_eq!(world.update_shapes(&scene, &edit), ShapeChange::Renumbered);
    // The quad (two triangles) becomes a triangle.
    let edit = Edit::parse_in("object 3 shape p 3 -1 -1 2 1 -1 2 1 1 2", &scene).unwrap();
    edit.apply(&mut scene).unwrap();
    assert_eq!(world.update_shapes(&scene, &edit), ShapeChange::Renumbered);
}

/// A move undone refits to the very tree that was built: the same nodes
/// and packed records to the bit, and the same counts.
#[test]
fn a_move_undone_refits_to_the_tree_built() {
    let shapes = random_shapes(13, 800, 1);
    let objects = objects(shapes.len(), &mut Rand(13));
    let index = SceneIndex::build(&shapes, AccelKind::Bvh, 2.0);
    let Structure::Bvh(built) = &index.structure else {
        unreachable!()
    };
    let mut refits = 0;
    for (i, object) in objects.iter().enumerate().step_by(7) {
        let by = Vec3A::new(0.3, -0.2, 0.1) * (i % 3) as f32;
        let mut moved_shapes = shapes.clone();
        for id in object.clone() {
            moved_shapes[id as usize] = moved(&shapes[id as usize], by, 1.25);
        }
        let Some(there) = index.refit(&moved_shapes, object.clone()) else {
            continue;
        };
        let back = there
            .refit(&shapes, object.clone())
            .expect("back where it was");
        let Structure::Bvh(bvh) = &back.structure else {
            unreachable!()
        };
        assert!(bvh.same_as(built), "{object:?}");
        assert_eq!(back.info().bvh_nodes, index.info().bvh_nodes);
        refits += 1;
    }
    assert!(refits > 10, "{refits} refits");
}
