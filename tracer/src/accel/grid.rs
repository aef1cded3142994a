//! The course's uniform grid: the scene's bounding box cut into equal cells,
//! `n = trunc(m * dim * s) + 1` per axis with `s = cbrt(objects / volume)`,
//! each object listed in every cell its box overlaps, rays walked cell by
//! cell with Amanatides and Woo's 3D-DDA.

use glam::{IVec3, Vec3A};

use crate::geometry::{Aabb, Ray, Shape};
use crate::stats::Counters;

use super::visits::{NoLog, TraversalStep, VisitLog};
use super::{Hit, Nearest, first_occluder, offer_each};

/// Most cells a grid may have, whatever the multiplier: 16 Mi cells take
/// 64 MiB of offsets.
const MAX_CELLS: u64 = 1 << 24;

/// Most object references a grid may hold (512 MiB): many large, overlapping
/// objects would otherwise each be listed in nearly every cell (30 000
/// spheres at one spot asked for 7.5 G references). Above it the cells are
/// made coarser until it fits; real scenes stay far below.
const MAX_REFERENCES: u64 = 1 << 27;

/// What the grid looks like, for the statistics panel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridStats {
    /// Cells along x, y and z.
    pub cells: [u32; 3],
    /// Cells that list no shape.
    pub empty_cells: u64,
    /// Object references summed over all cells.
    pub references: u64,
    /// Mean objects per non-empty cell.
    pub mean_per_cell: f32,
}

/// A uniform grid over the bounded shapes.
#[derive(Debug, Clone)]
pub struct Grid {
    bounds: Aabb,
    cells: IVec3,
    cell_size: Vec3A,
    inv_cell_size: Vec3A,
    /// Cell `i` lists `refs[offsets[i]..offsets[i + 1]]`.
    offsets: Vec<u32>,
    refs: Vec<u32>,
}

/// Slots of the per-ray mailbox: an object spanning several cells is tested
/// once per ray unless another object evicted it in between.
const MAILBOX_SLOTS: usize = 16;

impl Grid {
    /// Builds the grid over shapes `ids` with cell multiplier `m`.
    pub fn build(shapes: &[Shape], ids: &[u32], m: f32) -> Grid {
        Self::build_within(shapes, ids, m, MAX_REFERENCES)
    }

    /// [`Grid::build`] holding at most `max_references` object references
    /// (unless one cell is all it has left): the tests give a small limit.
    fn build_within(shapes: &[Shape], ids: &[u32], m: f32, max_references: u64) -> Grid {
        let boxes: Vec<(u32, Aabb)> = ids
            .iter()
            .filter_map(|&id| Some((id, shapes[id as usize].bounds()?)))
            .collect();
        let raw = boxes.iter().fold(Aabb::empty(), |b, (_, o)| b.union(o));
        if boxes.is_empty() {
            return Grid {
                bounds: Aabb::new(Vec3A::ZERO, Vec3A::ZERO),
                cells: IVec3::ONE,
                cell_size: Vec3A::ONE,
                inv_cell_size: Vec3A::ONE,
                offsets: vec![0, 0],
                refs: Vec::new(),
            };
        }
        // A flat scene has zero volume; give every axis a sliver of the
        // largest so the cell formula stays finite, and pad the box so
        // objects on its faces fall inside.
        let largest = raw.extent().max_element().max(f32::MIN_POSITIVE);
        let pad = Vec3A::splat(largest * 1e-4);
        let bounds = Aabb::new(raw.min - pad, raw.max + pad);
        let mut cells = cell_counts(bounds.extent(), boxes.len(), m);
        // Count references before allocating them: coarser cells until they
        // fit. Each step takes a tenth or more off every axis, a cell at
        // least, and no axis has over 65 537 cells, so fewer than 100 steps
        // reach one cell: the bound makes a step that shrinks nothing a
        // grid over its limit, which the tests see, instead of a hang.
        for _ in 0..100 {
            let refs: u64 = boxes
                .iter()
                .map(|(_, b)| {
                    let (lo, hi) = cell_range(&bounds, cells, b);
                    (hi - lo + 1).as_i64vec3().element_product() as u64
                })
                .sum();
            if refs <= max_references || cells == IVec3::ONE {
                break;
            }
            let shrink = (max_references as f64 / refs as f64).cbrt().min(0.9);
            cells = (cells.as_dvec3() * shrink).as_ivec3().max(IVec3::ONE);
        }
        let cell_size = bounds.extent() / cells.as_vec3a();
        let cell_range = |b: &Aabb| cell_range(&bounds, cells, b);
        let index = |c: IVec3| (c.x + cells.x * (c.y + cells.y * c.z)) as usize;
        let cell_count = (cells.x * cells.y * cells.z) as usize;

        // Two passes: count each cell's objects, then fill the slices.
        let mut offsets = vec![0u32; cell_count + 1];
        let for_each_cell = |b: &Aabb, f: &mut dyn FnMut(usize)| {
            let (lo, hi) = cell_range(b);
            for z in lo.z..=hi.z {
                for y in lo.y..=hi.y {
                    for x in lo.x..=hi.x {
                        f(index(IVec3::new(x, y, z)));
                    }
                }
            }
        };
        for (_, b) in &boxes {
            for_each_cell(b, &mut |i| offsets[i + 1] += 1);
        }
        for i in 0..cell_count {
            offsets[i + 1] += offsets[i];
        }
        let mut cursor = offsets.clone();
        let mut refs = vec![0u32; offsets[cell_count] as usize];
        for (id, b) in &boxes {
            for_each_cell(b, &mut |i| {
                refs[cursor[i] as usize] = *id;
                cursor[i] += 1;
            });
        }
        Grid {
            bounds,
            cells,
            cell_size,
            inv_cell_size: cell_size.recip(),
            offsets,
            refs,
        }
    }

    /// Its resolution and occupancy.
    pub fn stats(&self) -> GridStats {
        let cells = self.offsets.len() - 1;
        let empty = self.offsets.windows(2).filter(|w| w[0] == w[1]).count();
        let refs = self.refs.len() as u64;
        GridStats {
            cells: self.cells.to_array().map(|c| c as u32),
            empty_cells: empty as u64,
            references: refs,
            mean_per_cell: refs as f32 / (cells - empty).max(1) as f32,
        }
    }

    /// Bytes used by the cell offsets and references.
    pub fn memory_bytes(&self) -> usize {
        (self.offsets.len() + self.refs.len()) * 4
    }

    /// The nearest hit in `(t_min, t_max)`, telling `log` each cell walked.
    #[inline]
    pub(in crate::accel) fn closest_hit(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
        log: &mut impl VisitLog,
    ) -> Option<Hit> {
        let mut nearest = Nearest::new(t_max);
        self.walk(ray, t_min, t_max, counters, log, |id, counters| {
            let tests = &mut counters.intersection_tests;
            offer_each(&[id], shapes, ray, t_min, &mut nearest, tests);
            // Stop once the nearest hit lies before the cell's exit.
            nearest.t_max(t_max)
        });
        nearest.best
    }

    /// The first shape the walk meets on the ray in `(t_min, t_max)`.
    #[inline]
    pub fn occluder(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> Option<u32> {
        let mut found = None;
        self.walk(ray, t_min, t_max, counters, &mut NoLog, |id, counters| {
            let tests = &mut counters.intersection_tests;
            found = first_occluder(&[id], shapes, ray, t_min, t_max, tests);
            if found.is_some() {
                f32::NEG_INFINITY
            } else {
                f32::INFINITY
            }
        });
        found
    }

    /// Walks the cells the ray crosses in order (3D-DDA), calling `test`
    /// once per object (mailboxed). `test` returns the distance of the
    /// nearest hit so far; the walk stops when that lies within the
    /// current cell, or beyond `t_max`.
    #[inline]
    fn walk(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
        log: &mut impl VisitLog,
        mut test: impl FnMut(u32, &mut Counters) -> f32,
    ) {
        let Some((t_enter, _)) = self.bounds.intersect(ray, t_min, t_max) else {
            return;
        };
        let start = ray.at(t_enter);
        let mut cell = ((start - self.bounds.min) * self.inv_cell_size)
            .floor()
            .as_ivec3()
            .clamp(IVec3::ZERO, self.cells - 1);
        let positive = glam::BVec3::new(ray.dir.x > 0.0, ray.dir.y > 0.0, ray.dir.z > 0.0);
        let step = IVec3::select(positive, IVec3::ONE, IVec3::NEG_ONE);
        let stop = IVec3::select(positive, self.cells, IVec3::NEG_ONE);
        let next_boundary = self.bounds.min
            + (cell + IVec3::select(positive, IVec3::ONE, IVec3::ZERO)).as_vec3a() * self.cell_size;
        // Axes the ray does not move along never cross a boundary.
        let moving = ray.dir.cmpne(Vec3A::ZERO);
        let mut t_next = Vec3A::select(
            moving,
            (next_boundary - ray.origin) * ray.inv_dir,
            Vec3A::INFINITY,
        );
        let delta = Vec3A::select(
            moving,
            (self.cell_size * ray.inv_dir).abs(),
            Vec3A::INFINITY,
        );
        let mut mailbox = [u32::MAX; MAILBOX_SLOTS];
        let mut nearest = f32::INFINITY;
        // Each step moves one axis one cell towards its `stop`, so a walk
        // visits at most x + y + z - 2 cells and the bound never binds. It
        // is there so a broken step (one that never reaches `stop`) shows
        // as wrong hits in the tests instead of a render that hangs.
        let most_cells = self.cells.element_sum();
        for _ in 0..most_cells {
            counters.nodes_visited += 1;
            log.step(TraversalStep::Cell(cell), counters.intersection_tests);
            let i = (cell.x + self.cells.x * (cell.y + self.cells.y * cell.z)) as usize;
            let (from, to) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
            for &id in &self.refs[from..to] {
                let slot = id as usize % MAILBOX_SLOTS;
                if mailbox[slot] == id {
                    continue;
                }
                mailbox[slot] = id;
                nearest = test(id, counters);
                if nearest == f32::NEG_INFINITY {
                    return;
                }
            }
            let axis = if t_next.x < t_next.y {
                if t_next.x < t_next.z { 0 } else { 2 }
            } else if t_next.y < t_next.z {
                1
            } else {
                2
            };
            let exit = t_next[axis];
            if nearest <= exit || exit >= t_max {
                return;
            }
            cell[axis] += step[axis];
            if cell[axis] == stop[axis] {
                return;
            }
            t_next[axis] += delta[axis];
        }
    }
}

/// The first and last cell (inclusive) that box `b` overlaps.
fn cell_range(bounds: &Aabb, cells: IVec3, b: &Aabb) -> (IVec3, IVec3) {
    let cell_size = bounds.extent() / cells.as_vec3a();
    let to_cell = |p: Vec3A| {
        (((p - bounds.min) / cell_size).floor().as_ivec3()).clamp(IVec3::ZERO, cells - 1)
    };
    (to_cell(b.min), to_cell(b.max))
}

/// Cells per axis by the course's formula, shrunk uniformly if the total would
/// exceed [`MAX_CELLS`].
fn cell_counts(dim: Vec3A, objects: usize, m: f32) -> IVec3 {
    let volume = dim.x * dim.y * dim.z;
    let s = (objects as f32 / volume).cbrt();
    let mut scale = m;
    // Bounded: absurd scenes (infinite extents, NaN from inf * 0) once made
    // this loop spin forever, as NaN never shrinks.
    for _ in 0..1000 {
        let wanted = dim * (scale * s);
        // NaN counts as no cells (`cmpge` is false for it).
        let wanted = Vec3A::select(wanted.cmpge(Vec3A::ZERO), wanted, Vec3A::ZERO);
        let n = wanted.min(Vec3A::splat(65_536.0)).as_ivec3() + 1;
        let total = n.x as u64 * n.y as u64 * n.z as u64;
        if total <= MAX_CELLS {
            return n;
        }
        scale *= 0.9;
    }
    IVec3::ONE
}

impl Grid {
    /// The grid's box and its cells per axis, read only, for drawing its
    /// lattice over the image.
    pub fn lattice(&self) -> (Aabb, [u32; 3]) {
        (self.bounds, self.cells.as_uvec3().to_array())
    }

    /// The box of cell `c`, its faces where the walk places them.
    pub(in crate::accel) fn cell_bounds(&self, c: IVec3) -> Aabb {
        Aabb::new(
            self.bounds.min + c.as_vec3a() * self.cell_size,
            self.bounds.min + (c + 1).as_vec3a() * self.cell_size,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cell_counts_follow_the_seed_formula() {
        // 1000 objects in a 10 x 5 x 2 box: s = cbrt(1000 / 100) = 2.154.
        let n = cell_counts(Vec3A::new(10.0, 5.0, 2.0), 1000, 2.0);
        let s = 10f32.cbrt();
        assert_eq!(
            n,
            IVec3::new(
                (2.0 * 10.0 * s) as i32 + 1,
                (2.0 * 5.0 * s) as i32 + 1,
                (2.0 * 2.0 * s) as i32 + 1
            )
        );
        assert_eq!(n, IVec3::new(44, 22, 9));
        // m = 1 on a unit cube with 8 objects: 2 per axis plus one.
        assert_eq!(cell_counts(Vec3A::ONE, 8, 1.0), IVec3::splat(3));
        // A tiny multiplier still gives at least one cell per axis.
        assert_eq!(cell_counts(Vec3A::ONE, 8, 0.01), IVec3::ONE);
    }

    #[test]
    fn cell_counts_of_absurd_extents_are_finite() {
        for dim in [
            Vec3A::INFINITY,
            Vec3A::NAN,
            Vec3A::new(f32::INFINITY, 1.0, 1.0),
            Vec3A::splat(3e38),
        ] {
            let n = cell_counts(dim, 10, 2.0);
            assert!(n.cmpge(IVec3::ONE).all(), "{dim}: {n}");
            assert!(
                n.x as u64 * n.y as u64 * n.z as u64 <= MAX_CELLS,
                "{dim}: {n}"
            );
        }
    }

    #[test]
    fn cell_counts_are_capped() {
        let n = cell_counts(Vec3A::ONE, 10_000_000, 32.0);
        let total = n.x as u64 * n.y as u64 * n.z as u64;
        assert!(total <= MAX_CELLS);
        // Each step takes a tenth off every axis: the first count that
        // fits is more than half the cap, not one cell.
        assert!(total > MAX_CELLS / 2, "{n}");
    }

    fn spheres(spheres: &[(Vec3A, f32)]) -> (Vec<Shape>, Vec<u32>) {
        use crate::geometry::Sphere;
        let shapes: Vec<Shape> = spheres
            .iter()
            .map(|&(c, r)| Shape::Sphere(Sphere::new(c, r)))
            .collect();
        let ids = (0..shapes.len() as u32).collect();
        (shapes, ids)
    }

    /// Three spheres in a box 4 wide: 2 cells a side (s = cbrt(3 / 4^3)
    /// = 0.36, m = 1), the faces at 1.5. One sphere per far corner cell,
    /// one across the face between cells (0, 0, 0) and (1, 0, 0).
    fn two_by_two_by_two() -> (Vec<Shape>, Grid) {
        let (shapes, ids) = spheres(&[
            (Vec3A::ZERO, 0.5),
            (Vec3A::splat(3.0), 0.5),
            (Vec3A::new(1.5, 0.0, 0.0), 0.2),
        ]);
        let grid = Grid::build(&shapes, &ids, 1.0);
        (shapes, grid)
    }

    #[test]
    fn stats_and_memory_count_the_cells_by_hand() {
        let (_, grid) = two_by_two_by_two();
        let stats = grid.stats();
        assert_eq!(stats.cells, [2, 2, 2]);
        assert_eq!((stats.references, stats.empty_cells), (4, 5));
        assert_eq!(stats.mean_per_cell, 4.0 / 3.0);
        // 9 offsets and 4 references of 4 bytes.
        assert_eq!(grid.memory_bytes(), (9 + 4) * 4);
        // Padded by a ten-thousandth of the width: -0.5004 to 3.5004.
        let cell = grid.cell_bounds(IVec3::new(1, 0, 1));
        let (lo, hi) = (-0.5004, 3.5004);
        let want = Aabb::new(Vec3A::new(1.5, lo, 1.5), Vec3A::new(hi, 1.5, hi));
        assert!(
            (cell.min - want.min).abs().max_element() < 1e-5
                && (cell.max - want.max).abs().max_element() < 1e-5,
            "{cell:?}"
        );
    }

    /// The walk counts each cell it enters and stops in the cell that
    /// holds the nearest hit, or where the ray ends: in the 2 x 2 x 2 grid, a
    /// ray along x meets the sphere at the origin inside its first cell and
    /// the one at (3, 3, 3) inside its second; cut at x = 0, it ends in
    /// its first.
    #[test]
    fn the_walk_counts_its_cells_and_stops_at_the_nearest_hit() {
        let (shapes, grid) = two_by_two_by_two();
        let cases = [
            ((-1.0, 0.0), f32::INFINITY, Some(0), [[0, 0, 0]].as_slice()),
            ((-1.0, 3.0), f32::INFINITY, Some(1), &[[0, 1, 1], [1, 1, 1]]),
            ((-1.0, 3.0), 1.0, None, &[[0, 1, 1]]),
        ];
        for ((x, yz), t_max, want, cells) in cases {
            let ray = Ray::new(Vec3A::new(x, yz, yz), Vec3A::X);
            let (mut counters, mut log) = (Counters::default(), Vec::new());
            let hit = grid.closest_hit(&shapes, &ray, 0.0, t_max, &mut counters, &mut log);
            assert_eq!(hit.map(|h| h.shape), want, "{ray:?} to {t_max}");
            let logged: Vec<TraversalStep> = log.iter().map(|&(step, _)| step).collect();
            let walked: Vec<TraversalStep> = cells
                .iter()
                .map(|&c| TraversalStep::Cell(IVec3::from_array(c)))
                .collect();
            assert_eq!(logged, walked, "{ray:?} to {t_max}");
            assert_eq!(counters.nodes_visited, cells.len() as u64);
        }
    }

    /// A ray that starts on the grid's far corner lies, by its cell
    /// coordinates, one past the last cell on every axis: the walk starts
    /// in the last cell, (1, 1, 1), where it meets the sphere at (3, 3, 3).
    #[test]
    fn a_walk_from_the_far_corner_starts_in_the_last_cell() {
        let (shapes, grid) = two_by_two_by_two();
        let corner = grid.bounds.max;
        let past = ((corner - grid.bounds.min) * grid.inv_cell_size).floor();
        assert_eq!(past, Vec3A::splat(2.0), "the corner, in cells");
        let ray = Ray::new(corner, -Vec3A::ONE.normalize());
        let (mut counters, mut log) = (Counters::default(), Vec::new());
        let hit = grid.closest_hit(&shapes, &ray, 0.0, f32::INFINITY, &mut counters, &mut log);
        assert_eq!(hit.map(|h| h.shape), Some(1));
        let logged: Vec<TraversalStep> = log.iter().map(|&(step, _)| step).collect();
        assert_eq!(logged, [TraversalStep::Cell(IVec3::ONE)]);
    }

    /// Each sphere's references counted apart: the cells whose boxes
    /// (from the lattice) its box overlaps.
    fn references_by_hand(grid: &Grid, shapes: &[Shape]) -> u64 {
        let (bounds, cells) = grid.lattice();
        let size = bounds.extent() / Vec3A::from(cells.map(|c| c as f32));
        let cells_over = |lo: f32, hi: f32, axis: usize| {
            (0..cells[axis])
                .filter(|&i| {
                    let start = bounds.min[axis] + i as f32 * size[axis];
                    lo < start + size[axis] && hi >= start
                })
                .count() as u64
        };
        shapes
            .iter()
            .map(|s| {
                let b = s.bounds().unwrap();
                (0..3)
                    .map(|a| cells_over(b.min[a], b.max[a], a))
                    .product::<u64>()
            })
            .sum()
    }

    /// A 20 x 20 x 20 lattice of spheres of radius `r`, 1 apart.
    fn lattice_of_spheres(r: f32) -> (Vec<Shape>, Vec<u32>) {
        let centres: Vec<(Vec3A, f32)> = (0..8000)
            .map(|i| {
                let c = Vec3A::new((i % 20) as f32, (i / 20 % 20) as f32, (i / 400) as f32);
                (c, r)
            })
            .collect();
        spheres(&centres)
    }

    #[test]
    fn references_within_the_limit_keep_the_formulas_cells() {
        // Small spheres, one or two cells each (about 12 000 references),
        // far below the limit: the cells are the formula's, however far
        // from the grid's corner a sphere lies.
        let (shapes, ids) = lattice_of_spheres(0.1);
        let grid = Grid::build(&shapes, &ids, 2.0);
        let (bounds, cells) = grid.lattice();
        assert_eq!(
            IVec3::from_array(cells.map(|c| c as i32)),
            cell_counts(bounds.extent(), 8000, 2.0)
        );
        assert_eq!(grid.stats().references, references_by_hand(&grid, &shapes));
    }

    #[test]
    fn references_above_the_limit_make_the_cells_coarser() {
        // Spheres of radius 0.3 cover about 2 x 2 x 2 of the formula's
        // cells: some 60 000 references against a limit of 20 000.
        let (shapes, ids) = lattice_of_spheres(0.3);
        let unlimited = Grid::build(&shapes, &ids, 2.0).stats().references;
        assert!(unlimited > 50_000, "{unlimited}");
        let grid = Grid::build_within(&shapes, &ids, 2.0, 20_000);
        let references = grid.stats().references;
        assert!(references <= 20_000, "{references}");
        assert_eq!(references, references_by_hand(&grid, &shapes));
        // One step of cbrt(limit / references), not tenths until one cell.
        assert!(references > 8000, "{:?}", grid.stats());
    }

    #[test]
    fn overlapping_objects_shrink_in_one_step_where_tenths_would_pass_by() {
        // 500 identical spheres fill all 16 x 16 x 16 cells (2 048 000
        // references). A limit of 800 000 shrinks them by cbrt(800 000 /
        // 2 048 000) to 11 a side in one step (665 500; 12 would be
        // 864 000), where steps of a tenth would go 16, 14, 12, then 10.
        // Not built without the limit: a broken cell formula would fill
        // millions of cells, minutes at opt-level 0, before this failed.
        let (shapes, ids) = spheres(&[(Vec3A::ZERO, 1.0); 500]);
        let grid = Grid::build_within(&shapes, &ids, 2.0, 800_000);
        let (bounds, _) = grid.lattice();
        assert_eq!(cell_counts(bounds.extent(), 500, 2.0), IVec3::splat(16));
        let stats = grid.stats();
        assert_eq!(stats.cells, [11; 3]);
        assert_eq!(stats.references, 500 * 11 * 11 * 11);
    }

    #[test]
    fn many_overlapping_objects_shrink_in_one_step_to_the_limit() {
        // 30 000 identical spheres fill every cell: 63 a side (7.5 G
        // references) shrunk by cbrt(2^27 / 7.5 G) to 16 (123 M; 17 would
        // be 147 M, 15 is a second, needless step).
        let (shapes, ids) = spheres(&[(Vec3A::ZERO, 1.0); 30_000]);
        let stats = Grid::build(&shapes, &ids, 2.0).stats();
        assert_eq!(stats.cells, [16; 3]);
        assert_eq!(stats.references, 30_000 * 16 * 16 * 16);
    }
}
