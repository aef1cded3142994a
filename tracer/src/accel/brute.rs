//! No acceleration: every ray is tested against every bounded shape. The
//! seed's baseline, and the reference the other structures must match.

use crate::geometry::{Ray, Shape};
use crate::stats::Counters;

use super::Hit;

/// The list of bounded shapes, tested in order.
#[derive(Debug, Clone)]
pub struct BruteForce {
    shapes: Vec<u32>,
}

impl BruteForce {
    pub fn new(shapes: Vec<u32>) -> Self {
        Self { shapes }
    }

    /// Bytes of the shape list.
    pub fn memory_bytes(&self) -> usize {
        self.shapes.len() * 4
    }

    #[inline]
    pub fn closest_hit(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        mut t_max: f32,
        counters: &mut Counters,
    ) -> Option<Hit> {
        let mut best = None;
        counters.intersection_tests += self.shapes.len() as u64;
        for &i in &self.shapes {
            if let Some(t) = shapes[i as usize].intersect(ray, t_min, t_max) {
                t_max = t;
                best = Some(Hit { t, shape: i });
            }
        }
        best
    }

    #[inline]
    pub fn any_hit(
        &self,
        shapes: &[Shape],
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        counters: &mut Counters,
    ) -> bool {
        for &i in &self.shapes {
            counters.intersection_tests += 1;
            if shapes[i as usize].intersect(ray, t_min, t_max).is_some() {
                return true;
            }
        }
        false
    }
}
