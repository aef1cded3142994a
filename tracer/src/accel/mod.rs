//! Acceleration structures behind one interface: closest hit, and any hit
//! for shadow rays, each counting its own work. Unbounded primitives
//! (infinite planes) live outside the structure and are always tested.

mod brute;

use std::time::{Duration, Instant};

use crate::geometry::{Ray, Shape};
use crate::stats::Counters;

pub use brute::BruteForce;

/// Which structure to build.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AccelKind {
    /// Test every primitive: the seed's baseline.
    None,
    /// The seed's uniform grid.
    Grid,
    /// A bounding volume hierarchy.
    #[default]
    Bvh,
}

/// The closest surface a ray meets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    pub t: f32,
    /// Index into the world's shapes.
    pub shape: u32,
}

/// The structure over the bounded shapes, as a closed enum so traversal
/// dispatches without a virtual call.
#[derive(Debug, Clone)]
enum Structure {
    None(BruteForce),
}

/// An acceleration structure plus the unbounded shapes tested on the side.
#[derive(Debug, Clone)]
pub struct SceneIndex {
    kind: AccelKind,
    unbounded: Vec<u32>,
    structure: Structure,
    build_time: Duration,
}

impl SceneIndex {
    /// Builds the structure `kind` over `shapes`.
    pub fn build(shapes: &[Shape], kind: AccelKind) -> SceneIndex {
        let start = Instant::now();
        let (bounded, unbounded): (Vec<u32>, Vec<u32>) =
            (0..shapes.len() as u32).partition(|&i| shapes[i as usize].bounds().is_some());
        let structure = match kind {
            AccelKind::None | AccelKind::Grid | AccelKind::Bvh => {
                Structure::None(BruteForce::new(bounded))
            }
        };
        SceneIndex {
            kind,
            unbounded,
            structure,
            build_time: start.elapsed(),
        }
    }

    /// The structure that was built.
    pub fn kind(&self) -> AccelKind {
        self.kind
    }

    pub fn build_time(&self) -> Duration {
        self.build_time
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
        let mut best = match &self.structure {
            Structure::None(b) => b.closest_hit(shapes, ray, t_min, t_max, counters),
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
        for &i in &self.unbounded {
            counters.intersection_tests += 1;
            if shapes[i as usize].intersect(ray, t_min, t_max).is_some() {
                return true;
            }
        }
        match &self.structure {
            Structure::None(b) => b.any_hit(shapes, ray, t_min, t_max, counters),
        }
    }
}
