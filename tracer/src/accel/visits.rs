//! What one ray's traversal visited, told by the traversal itself: the
//! grid walk and the BVH descent call a [`VisitLog`] at the very lines that
//! count `nodes_visited`, so the visits drawn over the image are exactly
//! the work the render counts. The render passes [`NoLog`], which compiles
//! away; [`SceneIndex::closest_hit_visits`] passes a list.

use glam::IVec3;

use crate::geometry::{Aabb, Ray, Shape};
use crate::stats::Counters;

use super::{Hit, SceneIndex, Structure};

/// One step of a traversal, as cheap to tell as possible: indices only,
/// turned into boxes afterwards.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum TraversalStep {
    /// The grid walk entered this cell.
    Cell(IVec3),
    /// The BVH descent visited this 8-wide node (tested its children's boxes).
    Node(u32),
    /// The BVH descent tested this leaf's primitives `first..first + count`.
    Leaf(u32, u32),
}

/// Told every step of a traversal.
pub(super) trait VisitLog {
    /// `step` begins after `tests` primitive tests by this traversal: the
    /// difference to the next step's is what this one tested (the grid's
    /// mailbox makes that less than a cell lists).
    fn step(&mut self, step: TraversalStep, tests: u64);
}

/// The render's log: keeps nothing, costs nothing (the counts it is told
/// are values the traversal holds anyway).
pub(super) struct NoLog;

impl VisitLog for NoLog {
    #[inline(always)]
    fn step(&mut self, _: TraversalStep, _: u64) {}
}

impl VisitLog for Vec<(TraversalStep, u64)> {
    fn step(&mut self, step: TraversalStep, tests: u64) {
        self.push((step, tests));
    }
}

/// A cell or node one ray's traversal visited, with its box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Visit {
    /// A grid cell the 3D-DDA walked through: its (x, y, z), its box, and
    /// the objects tested in it: those it lists that the per-ray mailbox
    /// had not seen tested in an earlier cell.
    Cell {
        /// The cell's (x, y, z) in the grid.
        cell: [u32; 3],
        /// The cell's box.
        bounds: Aabb,
        /// Objects tested in it for the first time.
        tested: u32,
    },
    /// An 8-wide BVH node whose `boxes` (its children's, all at once) were
    /// tested against the ray. `depth` counts as the overlay's does: the
    /// root's box (the scene's) is 0, the root's children 1.
    Node {
        /// The node's box.
        bounds: Aabb,
        /// Levels below the root's box (0).
        depth: u32,
        /// Child boxes tested.
        boxes: u32,
    },
    /// A BVH leaf whose `primitives` were all tested.
    Leaf {
        /// The leaf's box.
        bounds: Aabb,
        /// Levels below the root's box (0).
        depth: u32,
        /// Primitives tested.
        primitives: u32,
    },
}

impl Visit {
    /// The box of the cell, node or leaf.
    pub fn bounds(&self) -> Aabb {
        match *self {
            Visit::Cell { bounds, .. }
            | Visit::Node { bounds, .. }
            | Visit::Leaf { bounds, .. } => bounds,
        }
    }

    /// What this visit itself tested.
    pub fn tally(&self) -> Tally {
        let (primitives, boxes) = match *self {
            Visit::Cell { tested, .. } => (tested, 0),
            Visit::Node { boxes, .. } => (0, boxes),
            Visit::Leaf { primitives, .. } => (primitives, 0),
        };
        Tally {
            primitives: primitives.into(),
            boxes: boxes.into(),
        }
    }
}

/// Tests a traversal made, for stepping through it: a prefix of its
/// visits sums to what it had tested by then, and all of them to the
/// query's own `intersection_tests` less its unbounded shapes'.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tally {
    /// Ray-primitive tests, one per primitive tested, as
    /// `Counters::intersection_tests` counts them.
    pub primitives: u64,
    /// Ray-box tests of BVH children (the grid tests none: its walk steps
    /// from cell to cell by arithmetic).
    pub boxes: u64,
}

impl Tally {
    /// What `visits` tested, added up.
    pub fn of(visits: &[Visit]) -> Tally {
        visits.iter().fold(Tally::default(), |sum, v| {
            let t = v.tally();
            Tally {
                primitives: sum.primitives + t.primitives,
                boxes: sum.boxes + t.boxes,
            }
        })
    }
}

/// One closest-hit query with everything its traversal visited.
#[derive(Debug, Clone, PartialEq)]
pub struct Traversal {
    /// The closest hit, if the ray met anything.
    pub hit: Option<Hit>,
    /// In visiting order. The grid's cells and the BVH's nodes (not its
    /// leaves) are what `counters.nodes_visited` counts, one for one.
    pub visits: Vec<Visit>,
    /// The work of this query alone: its `intersection_tests` are the
    /// visits' ([`Tally::of`]) plus one per unbounded shape (plane), each
    /// tested after the walk.
    pub counters: Counters,
}

impl SceneIndex {
    /// [`SceneIndex::closest_hit`] with the cells (grid) or nodes and leaves
    /// (BVH) its traversal visited, in order, and what each tested; brute
    /// force visits none. For inspecting one ray: it allocates.
    pub fn closest_hit_visits(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
    ) -> Traversal {
        let mut counters = Counters::default();
        let mut steps = Vec::new();
        let hit = self.closest_hit_logged(shapes, ray, t_min, t_max, &mut counters, &mut steps);
        let visits = match &self.structure {
            Structure::None(_) => Vec::new(),
            Structure::Grid(grid) => {
                // The structure's tests end where the unbounded shapes' begin.
                let walked = counters.intersection_tests - self.unbounded.len() as u64;
                let ends = steps.iter().skip(1).map(|&(_, t)| t).chain([walked]);
                steps
                    .iter()
                    .zip(ends)
                    .filter_map(|(&(step, before), after)| match step {
                        TraversalStep::Cell(c) => Some(Visit::Cell {
                            cell: c.as_uvec3().to_array(),
                            bounds: grid.cell_bounds(c),
                            tested: (after - before) as u32,
                        }),
                        _ => None,
                    })
                    .collect()
            }
            Structure::Bvh(bvh) => bvh.visits(steps.iter().map(|&(step, _)| step)),
        };
        Traversal {
            hit,
            visits,
            counters,
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3A;

    use super::*;
    use crate::accel::AccelKind;
    use crate::geometry::{Plane, Sphere};

    /// Unit spheres every 3 units along x, a row of them.
    fn row(n: usize) -> Vec<Shape> {
        (0..n)
            .map(|i| Shape::Sphere(Sphere::new(Vec3A::new(i as f32 * 3.0, 0.0, 0.0), 1.0)))
            .collect()
    }

    /// A 3D scatter of small spheres, for a deep BVH.
    fn cloud() -> Vec<Shape> {
        (0..200)
            .map(|i| {
                let f = i as f32;
                let p = Vec3A::new((f * 1.7) % 10.0, (f * 2.3) % 10.0, (f * 3.1) % 10.0);
                Shape::Sphere(Sphere::new(p, 0.3))
            })
            .collect()
    }

    fn rays() -> Vec<Ray> {
        let mut out = Vec::new();
        for i in 0..40 {
            let f = i as f32;
            let origin = Vec3A::new(-5.0, 5.0 + (f * 0.37) % 3.0, -5.0 + (f * 0.53) % 4.0);
            let target = Vec3A::new(10.0 - (f * 0.71) % 10.0, (f * 0.29) % 10.0, 10.0);
            out.push(Ray::new(origin, target - origin));
        }
        out
    }

    /// The cells of a grid traversal, in order.
    fn cells_of(traversal: &Traversal) -> Vec<[u32; 3]> {
        let cell = |v: &Visit| match v {
            Visit::Cell { cell, .. } => *cell,
            other => panic!("not a cell: {other:?}"),
        };
        traversal.visits.iter().map(cell).collect()
    }

    #[test]
    fn a_ray_along_the_x_axis_walks_the_grid_cells_in_order() {
        let shapes = row(8);
        let index = SceneIndex::build(&shapes, AccelKind::Grid, 2.0);
        let (bounds, cells) = match &index.structure {
            Structure::Grid(g) => g.lattice(),
            _ => unreachable!(),
        };
        // Through the middle of the row, from the left, missing nothing:
        // it stops in the first sphere's cell.
        let centre = bounds.centre();
        let ray = Ray::new(Vec3A::new(-10.0, centre.y, centre.z), Vec3A::X);
        let first = index.closest_hit_visits(&shapes, &ray, 0.0, f32::INFINITY);
        assert_eq!(first.hit.map(|h| h.shape), Some(0));
        // Just above the spheres: the ray crosses the whole row of cells.
        let above = Ray::new(Vec3A::new(-10.0, bounds.max.y - 1e-3, centre.z), Vec3A::X);
        let all = index.closest_hit_visits(&shapes, &above, 0.0, f32::INFINITY);
        assert_eq!(all.hit, None);
        let size = bounds.extent() / Vec3A::from(cells.map(|n| n as f32));
        let row_y = ((above.origin.y - bounds.min.y) / size.y) as u32;
        let row_z = ((centre.z - bounds.min.z) / size.z) as u32;
        let expected: Vec<[u32; 3]> = (0..cells[0]).map(|x| [x, row_y, row_z]).collect();
        assert_eq!(cells_of(&all), expected);
        assert_eq!(all.visits.len() as u64, all.counters.nodes_visited);
        // Through the centre the first sphere, at the grid's left face, is
        // hit in the first cell, before its exit: the walk ends there.
        let centre_row = ((centre - bounds.min) / size).as_uvec3();
        assert_eq!(cells_of(&first), vec![[0, centre_row.y, centre_row.z]]);
        // Each cell's box holds the ray where the walk says it is in it.
        for v in &all.visits {
            let b = v.bounds();
            assert!(b.intersect(&above, 0.0, f32::INFINITY).is_some(), "{b:?}");
        }
    }

    #[test]
    fn grid_visits_count_as_the_counter_does_and_the_hit_is_the_renders() {
        let shapes = cloud();
        let index = SceneIndex::build(&shapes, AccelKind::Grid, 2.0);
        for ray in rays() {
            let t = index.closest_hit_visits(&shapes, &ray, 0.0, f32::INFINITY);
            let mut counters = Counters::default();
            let hit = index.closest_hit(&shapes, &ray, 0.0, f32::INFINITY, &mut counters);
            assert_eq!(t.hit, hit);
            assert_eq!(t.counters, counters);
            assert_eq!(t.visits.len() as u64, counters.nodes_visited);
            for v in &t.visits {
                assert!(v.bounds().intersect(&ray, 0.0, f32::INFINITY).is_some());
            }
        }
    }

    #[test]
    fn bvh_visits_are_a_descent_from_the_root_through_boxes_the_ray_enters() {
        let shapes = cloud();
        let index = SceneIndex::build(&shapes, AccelKind::Bvh, 2.0);
        let Structure::Bvh(bvh) = &index.structure else {
            unreachable!()
        };
        let scene = bvh.boxes(Some(0))[0];
        let mut deep = 0;
        for ray in rays() {
            let t = index.closest_hit_visits(&shapes, &ray, 0.0, f32::INFINITY);
            let mut counters = Counters::default();
            let hit = index.closest_hit(&shapes, &ray, 0.0, f32::INFINITY, &mut counters);
            assert_eq!((t.hit, t.counters), (hit, counters));
            let nodes = t
                .visits
                .iter()
                .filter(|v| matches!(v, Visit::Node { .. }))
                .count();
            assert_eq!(
                nodes as u64, counters.nodes_visited,
                "exactly what is counted"
            );
            let tested: u32 = t
                .visits
                .iter()
                .map(|v| match v {
                    Visit::Leaf { primitives, .. } => *primitives,
                    _ => 0,
                })
                .sum();
            assert_eq!(tested as u64, counters.intersection_tests);
            // The root first, at depth 0, with the scene's box.
            assert_eq!(
                t.visits[0],
                Visit::Node {
                    bounds: scene,
                    depth: 0,
                    boxes: bvh.boxes(Some(1)).len() as u32,
                }
            );
            let mut seen_depths = vec![0u32];
            for v in &t.visits[1..] {
                let (bounds, depth) = match *v {
                    Visit::Node { bounds, depth, .. } | Visit::Leaf { bounds, depth, .. } => {
                        (bounds, depth)
                    }
                    Visit::Cell { .. } => panic!("a cell in a BVH"),
                };
                // Every node hangs below one visited before it.
                assert!(depth >= 1 && seen_depths.contains(&(depth - 1)), "{v:?}");
                assert!(
                    bounds.intersect(&ray, 0.0, f32::INFINITY).is_some(),
                    "{v:?}"
                );
                let inside = (bounds.min.cmpge(scene.min) & bounds.max.cmple(scene.max)).all();
                assert!(inside, "{v:?}");
                if matches!(v, Visit::Node { .. }) {
                    seen_depths.push(depth);
                }
                deep = deep.max(depth);
            }
        }
        assert!(deep >= 2, "the rays reach below the root's children");
    }

    #[test]
    fn running_tallies_end_at_the_querys_own_counts() {
        let mut shapes = cloud();
        // A floor: unbounded, tested after every walk, in no visit.
        let floor = Plane::from_points([Vec3A::ZERO, Vec3A::Z, Vec3A::X]).unwrap();
        shapes.push(Shape::Plane(floor));
        for kind in [AccelKind::Grid, AccelKind::Bvh] {
            let index = SceneIndex::build(&shapes, kind, 2.0);
            let mut tested = 0;
            for ray in rays() {
                let t = index.closest_hit_visits(&shapes, &ray, 0.0, f32::INFINITY);
                let all = Tally::of(&t.visits);
                assert_eq!(
                    all.primitives + 1,
                    t.counters.intersection_tests,
                    "{kind:?}"
                );
                // A running total never falls, and the last is the whole.
                let running: Vec<Tally> = (1..=t.visits.len())
                    .map(|k| Tally::of(&t.visits[..k]))
                    .collect();
                assert!(
                    running
                        .windows(2)
                        .all(|w| w[0].primitives <= w[1].primitives)
                );
                assert_eq!(running.last().copied().unwrap_or_default(), all);
                let nodes = t.visits.iter().filter(|v| matches!(v, Visit::Node { .. }));
                match kind {
                    AccelKind::Grid => assert_eq!(all.boxes, 0),
                    _ => {
                        assert!(nodes.clone().all(|v| (1..=8).contains(&v.tally().boxes)));
                        assert!(all.boxes >= nodes.count() as u64);
                    }
                }
                tested += all.primitives;
            }
            assert!(tested > 0, "{kind:?}: the rays test something");
        }
    }

    #[test]
    fn the_grid_counts_an_object_in_many_cells_once_per_ray() {
        // One big sphere listed in every cell of a 3 x 3 x 3 grid.
        let shapes = vec![Shape::Sphere(Sphere::new(Vec3A::ZERO, 5.0))];
        let index = SceneIndex::build(&shapes, AccelKind::Grid, 2.0);
        assert_eq!(index.info().grid.map(|g| g.cells), Some([3, 3, 3]));
        // Along an edge of its box, missing it: three cells, one test.
        let ray = Ray::new(Vec3A::new(-10.0, 4.5, 4.5), Vec3A::X);
        let t = index.closest_hit_visits(&shapes, &ray, 0.0, f32::INFINITY);
        assert_eq!(t.hit, None);
        let tested: Vec<u64> = t.visits.iter().map(|v| v.tally().primitives).collect();
        assert_eq!(tested, [1, 0, 0]);
        assert_eq!(t.counters.intersection_tests, 1);
    }

    #[test]
    fn brute_force_visits_nothing() {
        let shapes = row(3);
        let index = SceneIndex::build(&shapes, AccelKind::None, 2.0);
        let ray = Ray::new(Vec3A::new(-10.0, 0.0, 0.0), Vec3A::X);
        let t = index.closest_hit_visits(&shapes, &ray, 0.0, f32::INFINITY);
        assert_eq!(t.hit.map(|h| h.shape), Some(0));
        assert!(t.visits.is_empty());
        assert_eq!(t.counters.intersection_tests, 3);
    }
}
