//! Axis-aligned bounding boxes: the common currency of every acceleration
//! structure and of the box primitive.

use glam::Vec3A;

use super::Ray;

/// An axis-aligned box; `empty()` has `min > max` so that growing it by any
/// point or box gives that point or box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// The corner with the smallest coordinates.
    pub min: Vec3A,
    /// The corner with the largest coordinates.
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

    /// The box from `min` to `max`.
    pub fn new(min: Vec3A, max: Vec3A) -> Self {
        Self { min, max }
    }

    /// Contains no point (`min > max` on some axis), as the empty box does.
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The smallest box holding this one and `p`.
    pub fn grow(&self, p: Vec3A) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// Side lengths: `max - min`.
    pub fn extent(&self) -> Vec3A {
        self.max - self.min
    }

    /// The middle point.
    pub fn centre(&self) -> Vec3A {
        (self.min + self.max) * 0.5
    }

    /// Half the surface area (the SAH only needs ratios).
    pub(crate) fn half_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        e.x * e.y + e.y * e.z + e.z * e.x
    }

    /// Kay-Kajiya slab test: the parametric interval `(t_enter, t_exit)`
    /// where the ray is inside the box, clipped to `[t_min, t_max]`, or
    /// `None` when it misses. The box is closed: a ray along a face counts
    /// as a hit. Not meaningful for `empty()` (the slabs ignore which corner
    /// is which); callers skip empty boxes.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<(f32, f32)> {
        let t0 = (self.min - ray.origin) * ray.inv_dir;
        let t1 = (self.max - ray.origin) * ray.inv_dir;
        // A ray parallel to a slab whose origin lies on one of its planes
        // gives 0 * inf = NaN in that lane. Clamping each lane against the
        // interval ends *before* combining the two planes drops the NaN
        // (`max(NaN, t_min)` is `t_min` for SSE `maxps` and IEEE `maxNum`
        // alike), so such a ray counts as inside that slab (the box is
        // closed) and no NaN reaches the horizontal min/max, where its
        // effect would depend on the lane order.
        let lo = Vec3A::splat(t_min);
        let hi = Vec3A::splat(t_max);
        let near = t0.max(lo).min(t1.max(lo)).max_element();
        let far = t0.min(hi).max(t1.min(hi)).min_element();
        (near <= far).then_some((near, far))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Aabb {
        Aabb::new(Vec3A::ZERO, Vec3A::ONE)
    }

    #[test]
    fn hit_from_outside_gives_entry_and_exit() {
        let r = Ray::new(Vec3A::new(-1.0, 0.5, 0.5), Vec3A::X);
        let (near, far) = unit_box().intersect(&r, 0.0, f32::INFINITY).unwrap();
        assert!((near - 1.0).abs() < 1e-6 && (far - 2.0).abs() < 1e-6);
    }

    #[test]
    fn miss_behind_and_beside() {
        let b = unit_box();
        let behind = Ray::new(Vec3A::new(2.0, 0.5, 0.5), Vec3A::X);
        assert_eq!(b.intersect(&behind, 0.0, f32::INFINITY), None);
        let beside = Ray::new(Vec3A::new(-1.0, 2.0, 0.5), Vec3A::X);
        assert_eq!(b.intersect(&beside, 0.0, f32::INFINITY), None);
        let diagonal_miss = Ray::new(Vec3A::new(-1.0, 0.0, 0.5), Vec3A::new(1.0, 3.0, 0.0));
        assert_eq!(b.intersect(&diagonal_miss, 0.0, f32::INFINITY), None);
    }

    #[test]
    fn from_inside_interval_starts_at_t_min() {
        let r = Ray::new(Vec3A::splat(0.5), Vec3A::new(1.0, 1.0, 0.0));
        let (near, far) = unit_box().intersect(&r, 0.0, f32::INFINITY).unwrap();
        assert_eq!(near, 0.0);
        assert!((far - 0.5 * 2f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn interval_is_clipped_to_t_max() {
        let r = Ray::new(Vec3A::new(-1.0, 0.5, 0.5), Vec3A::X);
        assert_eq!(unit_box().intersect(&r, 0.0, 0.5), None);
        assert_eq!(unit_box().intersect(&r, 0.0, 1.5), Some((1.0, 1.5)));
    }

    #[test]
    fn ray_in_a_slab_plane_with_zero_component_is_nan_free() {
        let b = unit_box();
        // Lies in the plane y = 1 (max) and z = 0 (min), dir.y = dir.z = 0.
        for &(y, z) in &[(1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.0, 0.0)] {
            for dir in [Vec3A::X, -Vec3A::X] {
                let origin = Vec3A::new(0.5 - 2.0 * dir.x, y, z);
                let r = Ray::new(origin, dir);
                let (near, far) = b.intersect(&r, 0.0, f32::INFINITY).unwrap();
                assert!((near - 1.5).abs() < 1e-6 && (far - 2.5).abs() < 1e-6);
            }
        }
        // Negative zero direction components give -inf reciprocals.
        let r = Ray {
            origin: Vec3A::new(-1.0, 1.0, 0.0),
            dir: Vec3A::new(1.0, -0.0, -0.0),
            inv_dir: Vec3A::new(1.0, f32::NEG_INFINITY, f32::NEG_INFINITY),
        };
        assert_eq!(b.intersect(&r, 0.0, f32::INFINITY), Some((1.0, 2.0)));
        // In the plane z = 0 but outside in x: a miss, whatever the lane.
        let miss = Ray::new(Vec3A::new(2.0, 2.0, 0.0), Vec3A::Y);
        assert_eq!(b.intersect(&miss, 0.0, f32::INFINITY), None);
        let miss = Ray::new(Vec3A::new(0.5, 2.0, 1.0), Vec3A::X);
        assert_eq!(b.intersect(&miss, 0.0, f32::INFINITY), None);
    }

    #[test]
    fn parallel_outside_a_slab_misses() {
        let r = Ray::new(Vec3A::new(-1.0, 1.5, 0.5), Vec3A::X);
        assert_eq!(unit_box().intersect(&r, 0.0, f32::INFINITY), None);
    }

    #[test]
    fn flat_box_is_hit_head_on() {
        let flat = Aabb::new(Vec3A::new(0.0, 0.0, 0.0), Vec3A::new(1.0, 0.0, 1.0));
        let r = Ray::new(Vec3A::new(0.5, 1.0, 0.5), -Vec3A::Y);
        assert_eq!(flat.intersect(&r, 0.0, f32::INFINITY), Some((1.0, 1.0)));
    }

    #[test]
    fn empty_box_is_the_union_identity() {
        assert!(Aabb::empty().is_empty());
        assert_eq!(Aabb::empty().half_area(), 0.0);
        assert_eq!(
            Aabb::empty().grow(Vec3A::ONE),
            Aabb::new(Vec3A::ONE, Vec3A::ONE)
        );
    }
}
