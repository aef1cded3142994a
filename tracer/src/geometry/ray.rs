//! Rays with their reciprocal direction precomputed, because every slab test
//! (boxes, BVH nodes, grid traversal) divides by the direction.

use glam::Vec3A;

/// A half-line `origin + t * dir`; `dir` is unit length for every ray the
/// renderer spawns, so `t` is a distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    pub origin: Vec3A,
    pub dir: Vec3A,
    /// `1 / dir` per component (infinite where a component is zero).
    pub inv_dir: Vec3A,
}

impl Ray {
    /// A ray from `origin` along `dir` (normalised here).
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        let dir = dir.normalize();
        Self {
            origin,
            dir,
            inv_dir: dir.recip(),
        }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3A {
        self.origin + self.dir * t
    }
}
