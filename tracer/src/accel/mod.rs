//! Acceleration structures behind one interface: closest hit, and any hit
//! for shadow rays, each counting its own work. Unbounded primitives
//! (infinite planes) live outside the structure and are always tested.

mod brute;
mod bvh;
mod grid;
mod packed;
mod structure_view;
#[cfg(test)]
mod tests;
mod visits;

use std::ops::Range;
use std::time::Duration;

use web_time::Instant;

use crate::geometry::{Ray, Shape};
use crate::stats::Counters;
use visits::{NoLog, VisitLog};

pub use brute::BruteForce;
pub use bvh::{Bvh, BvhParams};
pub use grid::{Grid, GridStats};
pub use structure_view::StructureLayer;
pub use visits::{Tally, Traversal, Visit};

/// Which structure to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AccelKind {
    /// Test every primitive: the course's baseline.
    None,
    /// The course's uniform grid (Amanatides-Woo traversal, multiplier m).
    Grid,
    /// A bounding volume hierarchy.
    #[default]
    Bvh,
}

/// A structure's name that is none of `none`, `grid`, `bvh`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("no structure '{0}'; structures: none, grid, bvh")]
pub struct UnknownAccel(pub String);

impl std::str::FromStr for AccelKind {
    type Err = UnknownAccel;

    /// Reads the names [`AccelKind::name`] gives, as the command line and
    /// reports spell them.
    fn from_str(name: &str) -> Result<Self, Self::Err> {
        AccelKind::ALL
            .into_iter()
            .find(|kind| kind.name() == name)
            .ok_or_else(|| UnknownAccel(name.to_string()))
    }
}

impl AccelKind {
    /// Every structure, slowest first.
    pub const ALL: [AccelKind; 3] = [AccelKind::None, AccelKind::Grid, AccelKind::Bvh];

    /// The name the command line and reports use: `none`, `grid`, `bvh`.
    pub fn name(self) -> &'static str {
        match self {
            AccelKind::None => "none",
            AccelKind::Grid => "grid",
            AccelKind::Bvh => "bvh",
        }
    }

    /// What tells structures of this kind over the same shapes apart: the
    /// multiplier for a grid, nothing for the others (they ignore it).
    /// Settings with equal keys can share one structure.
    pub fn structure_key(self, grid_multiplier: f32) -> (AccelKind, Option<f32>) {
        (self, (self == AccelKind::Grid).then_some(grid_multiplier))
    }
}

/// The closest surface a ray meets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Distance along the ray to the hit.
    pub t: f32,
    /// Index into the world's shapes.
    pub shape: u32,
}

/// The nearest hit so far, with ties in `t` going to the lowest shape
/// index: the order brute force tests in, so every structure returns the
/// same hit whatever order it meets the primitives in (overlapping or
/// touching primitives do meet a ray at bit-identical distances).
#[derive(Debug, Clone, Copy)]
struct Nearest {
    best: Option<Hit>,
    /// The `t_max` to test the next primitive with: one step above the
    /// best `t` once there is one, so a tie is still reported.
    limit: f32,
}

impl Nearest {
    #[inline]
    fn new(t_max: f32) -> Self {
        Self {
            best: None,
            limit: t_max,
        }
    }

    /// Keeps `t` (from a test with `t_max = self.limit`) on `shape` if it is
    /// nearer, or as near and of a lower index.
    #[inline]
    fn offer(&mut self, t: f32, shape: u32) {
        if self
            .best
            .is_none_or(|b| t < b.t || (t == b.t && shape < b.shape))
        {
            self.best = Some(Hit { t, shape });
            self.limit = next_up(t);
        }
    }

    /// The best `t`, or the caller's `t_max` while nothing is hit: nodes and
    /// cells entered beyond it can be skipped.
    #[inline]
    fn t_max(&self, t_max: f32) -> f32 {
        self.best.map_or(t_max, |b| b.t)
    }
}

/// What a structure's leaves list: a world shape's index, or the BVH's
/// packed copy of it. Both intersect bit for bit like the world's shape.
trait LeafShape {
    /// The index of the shape in the world's shapes.
    fn id(&self) -> u32;
    /// `shapes[self.id()].intersect(ray, t_min, t_max)`.
    fn intersect(&self, shapes: &[Shape], ray: &Ray, t_min: f32, t_max: f32) -> Option<f32>;
}

impl LeafShape for u32 {
    #[inline(always)]
    fn id(&self) -> u32 {
        *self
    }

    #[inline(always)]
    fn intersect(&self, shapes: &[Shape], ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        shapes[*self as usize].intersect(ray, t_min, t_max)
    }
}

/// The leaf loop of every closest-hit query: offers each of `prims` the
/// ray meets to `nearest`, adding one to `tests` per primitive. (The BVH
/// runs it on a leaf's records after its groups of four spheres or triangles.)
#[inline(always)]
fn offer_each<P: LeafShape>(
    prims: &[P],
    shapes: &[Shape],
    ray: &Ray,
    t_min: f32,
    nearest: &mut Nearest,
    tests: &mut u64,
) {
    *tests += prims.len() as u64;
    for prim in prims {
        if let Some(t) = prim.intersect(shapes, ray, t_min, nearest.limit) {
            nearest.offer(t, prim.id());
        }
    }
}

/// The leaf loop of every any-hit query: the first of `prims` the ray
/// meets in `(t_min, t_max)`, adding one to `tests` per primitive tested.
/// (The BVH runs it on a leaf's records after its groups of four.)
#[inline(always)]
fn first_occluder<P: LeafShape>(
    prims: &[P],
    shapes: &[Shape],
    ray: &Ray,
    t_min: f32,
    t_max: f32,
    tests: &mut u64,
) -> Option<u32> {
    for prim in prims {
        *tests += 1;
        if prim.intersect(shapes, ray, t_min, t_max).is_some() {
            return Some(prim.id());
        }
    }
    None
}

/// The next float above a finite `t`.
#[inline]
fn next_up(t: f32) -> f32 {
    let bits = t.to_bits();
    if t == 0.0 {
        f32::from_bits(1)
    } else if t > 0.0 {
        f32::from_bits(bits + 1)
    } else {
        f32::from_bits(bits - 1)
    }
}

/// The structure over the bounded shapes, as a closed enum so traversal
/// dispatches without a virtual call.
#[derive(Debug, Clone)]
enum Structure {
    None(BruteForce),
    Grid(Grid),
    Bvh(Bvh),
}

/// What was built, for statistics and for deciding whether a settings
/// change needs a rebuild.
#[derive(Debug, Clone, PartialEq)]
pub struct AccelInfo {
    /// Which structure: none, grid or BVH.
    pub kind: AccelKind,
    /// The grid multiplier the grid was built with (grid only).
    pub grid_multiplier: Option<f32>,
    /// How long the build took.
    pub build_time: Duration,
    /// Bytes of the structure itself (not the world's shapes).
    pub memory_bytes: usize,
    /// BVH nodes (BVH only).
    pub bvh_nodes: Option<usize>,
    /// Cell statistics (grid only).
    pub grid: Option<GridStats>,
    /// Unbounded shapes (planes) tested outside the structure.
    pub unbounded: usize,
}

/// An acceleration structure plus the unbounded shapes tested on the side.
#[derive(Debug, Clone)]
pub struct SceneIndex {
    /// How many shapes it was built over.
    shapes: usize,
    unbounded: Vec<u32>,
    structure: Structure,
    info: AccelInfo,
}

impl SceneIndex {
    /// Builds the structure `kind` over `shapes`; `grid_multiplier` is the
    /// course's m, used by the grid only.
    pub fn build(shapes: &[Shape], kind: AccelKind, grid_multiplier: f32) -> SceneIndex {
        let start = Instant::now();
        let (bounded, unbounded): (Vec<u32>, Vec<u32>) =
            (0..shapes.len() as u32).partition(|&i| shapes[i as usize].bounds().is_some());
        let structure = match kind {
            AccelKind::None => Structure::None(BruteForce::new(bounded)),
            AccelKind::Grid => Structure::Grid(Grid::build(shapes, &bounded, grid_multiplier)),
            AccelKind::Bvh => Structure::Bvh(Bvh::build(shapes, &bounded, &BvhParams::default())),
        };
        let (memory_bytes, bvh_nodes, grid) = match &structure {
            Structure::None(b) => (b.memory_bytes(), None, None),
            Structure::Grid(g) => (g.memory_bytes(), None, Some(g.stats())),
            Structure::Bvh(b) => (b.memory_bytes(), Some(b.node_count()), None),
        };
        SceneIndex {
            info: AccelInfo {
                kind,
                grid_multiplier: kind.structure_key(grid_multiplier).1,
                build_time: start.elapsed(),
                memory_bytes: memory_bytes + unbounded.len() * 4,
                bvh_nodes,
                grid,
                unbounded: unbounded.len(),
            },
            shapes: shapes.len(),
            unbounded,
            structure,
        }
    }

    /// This index over `shapes`, in which the shapes `moved` changed in
    /// place since it was built (an object moved or resized: the same
    /// number of shapes, each of its old kind), refitted around them
    /// rather than built again; `None` when it cannot be, and a build
    /// must follow: the shapes' count changed, a moved shape gained or
    /// lost its bounds, the structure is a grid (whose refit measured no
    /// faster than its build), or the BVH's
    /// boxes would grow so much that its rays would cost more than 1.1
    /// times what they did when it was built (its SAH cost).
    /// The result finds the hits a build over `shapes` finds; `build_time`
    /// is the refit's.
    pub fn refit(&self, shapes: &[Shape], moved: Range<u32>) -> Option<SceneIndex> {
        let start = Instant::now();
        if shapes.len() != self.shapes || moved.end as usize > shapes.len() {
            return None;
        }
        let unbounded_kept = moved.clone().all(|id| {
            let unbounded = self.unbounded.binary_search(&id).is_ok();
            shapes[id as usize].bounds().is_none() == unbounded
        });
        if !unbounded_kept {
            return None;
        }
        let structure = match &self.structure {
            Structure::None(b) => Structure::None(b.clone()),
            // Relisting the moved shapes' references is a pass over every
            // cell, no faster than a build (measured in docs/PERFORMANCE.md,
            // "Scene edits"). A grid is built anew.
            Structure::Grid(_) => return None,
            Structure::Bvh(b) => Structure::Bvh(b.refit(shapes, moved)?),
        };
        Some(SceneIndex {
            info: AccelInfo {
                build_time: start.elapsed(),
                ..self.info.clone()
            },
            shapes: self.shapes,
            unbounded: self.unbounded.clone(),
            structure,
        })
    }

    /// What was built and what it cost.
    pub fn info(&self) -> &AccelInfo {
        &self.info
    }

    /// The structure that was built.
    pub fn kind(&self) -> AccelKind {
        self.info.kind
    }

    /// How long the build took.
    pub fn build_time(&self) -> Duration {
        self.info.build_time
    }

    /// Whether this index is what `kind` with `grid_multiplier` would build,
    /// so a render with those settings can reuse it.
    pub fn matches(&self, kind: AccelKind, grid_multiplier: f32) -> bool {
        (self.info.kind, self.info.grid_multiplier) == kind.structure_key(grid_multiplier)
    }

    /// The nearest hit with `t` in `(t_min, t_max)`.
    #[inline]
    pub fn closest_hit(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> Option<Hit> {
        self.closest_hit_logged(shapes, ray, t_min, t_max, counters, &mut NoLog)
    }

    /// [`SceneIndex::closest_hit`], telling `log` every cell or node the
    /// traversal visits (a [`NoLog`] compiles the telling away).
    #[inline]
    fn closest_hit_logged(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
        log: &mut impl VisitLog,
    ) -> Option<Hit> {
        let mut best = match &self.structure {
            Structure::None(b) => b.closest_hit(shapes, ray, t_min, t_max, counters),
            Structure::Grid(g) => g.closest_hit(shapes, ray, t_min, t_max, counters, log),
            Structure::Bvh(b) => b.closest_hit(shapes, ray, t_min, t_max, counters, log),
        };
        let mut t_max = best.map_or(t_max, |h| h.t);
        for &i in &self.unbounded {
            counters.intersection_tests += 1;
            if let Some(t) = shapes[i as usize].intersect(ray, t_min, t_max) {
                t_max = t;
                best = Some(Hit { t, shape: i });
            }
        }
        if best.is_some() {
            counters.hits += 1;
        }
        best
    }

    /// Whether anything lies on the ray with `t` in `(t_min, t_max)`; stops
    /// at the first hit found.
    #[inline]
    pub fn any_hit(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> bool {
        self.occluder(shapes, ray, t_min, t_max, counters).is_some()
    }

    /// The first shape found on the ray with `t` in `(t_min, t_max)`, if
    /// any: which one depends on the structure, that there is one does not.
    /// Shadow rays remember it to test it first next time.
    #[inline]
    pub fn occluder(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> Option<u32> {
        let tests = &mut counters.intersection_tests;
        if let Some(id) = first_occluder(&self.unbounded, shapes, ray, t_min, t_max, tests) {
            return Some(id);
        }
        match &self.structure {
            Structure::None(b) => b.occluder(shapes, ray, t_min, t_max, counters),
            Structure::Grid(g) => g.occluder(shapes, ray, t_min, t_max, counters),
            Structure::Bvh(b) => b.occluder(shapes, ray, t_min, t_max, counters),
        }
    }
}
