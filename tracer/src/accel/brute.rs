//! No acceleration: every ray is tested against every bounded shape. The
//! course's baseline, and the reference the other structures must match.

use crate::geometry::{Ray, Shape};
use crate::stats::Counters;

use super::{Hit, Nearest, first_occluder, offer_each};

/// The list of bounded shapes, tested in order.
#[derive(Debug, Clone)]
pub struct BruteForce {
    shapes: Vec<u32>,
}

impl BruteForce {
    /// Tests every one of `shapes` (indices into the world's shapes) for each ray.
    pub fn new(shapes: Vec<u32>) -> Self {
        Self { shapes }
    }

    /// Bytes of the shape list.
    pub fn memory_bytes(&self) -> usize {
        self.shapes.len() * 4
    }

    #[inline]
    /// The nearest hit of `ray` among the shapes, testing them all.
    pub fn closest_hit(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> Option<Hit> {
        let mut nearest = Nearest::new(t_max);
        let tests = &mut counters.intersection_tests;
        offer_each(&self.shapes, shapes, ray, t_min, &mut nearest, tests);
        nearest.best
    }

    /// The first shape in list order on the ray in `(t_min, t_max)`.
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
        first_occluder(&self.shapes, shapes, ray, t_min, t_max, tests)
    }
}
