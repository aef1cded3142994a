//! Axis-aligned bounding boxes: the common currency of every acceleration
//! structure and of the box primitive.

use glam::Vec3A;

use super::Ray;

/// An axis-aligned box; `empty()` has `min > max` so that growing it by any
/// point or box gives that point or box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    pub min: Vec3A,
    pub max: Vec3A,
}

impl Aabb {
    /// The box that contains nothing; the identity of `union`.
    pub const fn empty() -> Self {
        Self {
            min: Vec3A::splat(f32::INFINITY),
            max: Vec3A::splat(f32::NEG_INFINITY),
        }
    }

    pub fn new(min: Vec3A, max: Vec3A) -> Self {
        Self { min, max }
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    pub fn grow(&self, p: Vec3A) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    pub fn extent(&self) -> Vec3A {
        self.max - self.min
    }

    pub fn centre(&self) -> Vec3A {
        (self.min + self.max) * 0.5
    }

    /// Half the surface area (the SAH only needs ratios).
    pub fn half_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// Kay-Kajiya slab test: the parametric interval `(t_enter, t_exit)`
    /// where the ray is inside the box, clipped to `[t_min, t_max]`, or
    /// `None` when it misses.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(f32, f32)> {
        let t0 = (self.min - ray.origin) * ray.inv_dir;
        let t1 = (self.max - ray.origin) * ray.inv_dir;
        // NaN (0 * inf when the origin lies on a slab plane of a parallel
        // ray) is dropped by min/max, which keep the other operand.
        let near = t0.min(t1).max_element().max(t_min);
        let far = t0.max(t1).min_element().min(t_max);
        (near <= far).then_some((near, far))
    }
}
