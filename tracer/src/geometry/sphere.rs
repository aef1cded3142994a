//! Spheres.

use glam::Vec3A;

use super::lanes::{Lanes, Vector};
use super::{Aabb, Ray};

/// A sphere; hit from outside or from inside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// The centre.
    pub centre: Vec3A,
    /// The radius, > 0.
    pub radius: f32,
}

impl Sphere {
    /// A sphere around `centre`; a negative radius is treated as its
    /// absolute value by every routine (the parser notes NFF's inside-only
    /// flag separately).
    pub fn new(centre: Vec3A, radius: f32) -> Self {
        Self { centre, radius }
    }

    /// The nearest hit in `(t_min, t_max)`: the entry point from outside,
    /// the exit point from inside. The arithmetic (written once for one
    /// sphere and for four side by side) is `intersect_spheres`'s.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        let (hit, t) =
            intersect_spheres(self.centre, self.radius, ray.origin, ray.dir, t_min, t_max)?;
        hit.then_some(t)
    }

    /// The outward unit normal at a point on the surface.
    #[inline]
    pub(crate) fn normal_at(&self, point: Vec3A) -> Vec3A {
        (point - self.centre) * self.radius.abs().recip()
    }

    /// The tight axis-aligned bounding box.
    pub fn bounds(&self) -> Aabb {
        let r = Vec3A::splat(self.radius.abs());
        Aabb::new(self.centre - r, self.centre + r)
    }
}

/// [`Sphere::intersect`] for one sphere (`f32`) or four side by side
/// (`Vec4`, a sphere a lane), with the same operations in every lane: which
/// lanes are hit in `(t_min, t_max)` and at what distance, or `None` when
/// no lane's ray comes near enough to its sphere.
///
/// Solves `t^2 - 2 b t + c = 0` with `b = d.(centre - origin)` and
/// `c = |centre - origin|^2 - r^2`. The discriminant is taken as
/// `r^2 - |oc - b d|^2` (the squared distance from the centre to the
/// ray's line, measured directly) rather than `b^2 - c`, which cancels
/// catastrophically for distant origins; the two roots come from
/// `q = b + sign(b) sqrt(disc)` as `q` and `c / q`, so the small root
/// does not lose digits either (Ray Tracing Gems, ch. 7).
#[inline(always)]
pub(crate) fn intersect_spheres<L: Lanes>(
    centre: L::Vector,
    radius: L,
    origin: L::Vector,
    dir: L::Vector,
    t_min: L,
    t_max: L,
) -> Option<(L::Mask, L)> {
    let oc = centre.sub(origin);
    let b = dir.dot(oc);
    let r2 = radius * radius;
    let diff = oc.sub(dir.scale(b));
    let disc = r2 - diff.dot(diff);
    // A negative discriminant misses; a NaN one (non-finite input, or a
    // lane of padding) gives NaN roots, which the interval tests reject.
    if !L::any(L::splat(0.0).le(disc)) {
        return None;
    }
    let c = oc.dot(oc) - r2;
    let q = b + disc.sqrt().copysign(b);
    // `c / q` is NaN only when q = c = 0 (a ray tangent at its own
    // origin); the comparisons below reject NaN.
    let (t0, t1) = (c / q, q);
    let ordered = t0.le(t1);
    let (near, far) = (L::select(ordered, t0, t1), L::select(ordered, t1, t0));
    // The entry point from outside, the exit point from inside. A single
    // sphere hit from outside returns at once (see docs/PERFORMANCE.md);
    // four rarely all are, not worth a branch.
    let near_in = t_min.lt(near) & near.lt(t_max);
    if L::LANES == 1 && L::all(near_in) {
        return Some((near_in, near));
    }
    let far_in = t_min.lt(far) & far.lt(t_max);
    Some((near_in | far_in, L::select(near_in, near, far)))
}

#[cfg(test)]
mod tests {
    use super::super::ray::strategies::{config, point, unit_vector};
    use super::*;
    use proptest::prelude::*;

    const INF: f32 = f32::INFINITY;

    fn unit() -> Sphere {
        Sphere::new(Vec3A::ZERO, 1.0)
    }

    #[test]
    fn hit_from_outside_is_the_entry_point() {
        let r = Ray::new(Vec3A::new(0.0, 0.0, -5.0), Vec3A::Z);
        assert_eq!(unit().intersect(&r, 0.0, INF), Some(4.0));
    }

    #[test]
    fn miss() {
        let r = Ray::new(Vec3A::new(0.0, 1.5, -5.0), Vec3A::Z);
        assert_eq!(unit().intersect(&r, 0.0, INF), None);
    }

    #[test]
    fn behind_the_origin_is_ignored() {
        let r = Ray::new(Vec3A::new(0.0, 0.0, 5.0), Vec3A::Z);
        assert_eq!(unit().intersect(&r, 0.0, INF), None);
    }

    #[test]
    fn from_inside_gives_the_exit_point() {
        let r = Ray::new(Vec3A::new(0.0, 0.5, 0.0), Vec3A::Y);
        assert_eq!(unit().intersect(&r, 0.0, INF), Some(0.5));
        let r = Ray::new(Vec3A::new(0.0, 0.5, 0.0), -Vec3A::Y);
        assert_eq!(unit().intersect(&r, 0.0, INF), Some(1.5));
    }

    #[test]
    fn t_range_is_open() {
        let r = Ray::new(Vec3A::new(0.0, 0.0, -5.0), Vec3A::Z);
        assert_eq!(unit().intersect(&r, 4.0, INF), Some(6.0));
        assert_eq!(unit().intersect(&r, 0.0, 4.0), None);
        assert_eq!(unit().intersect(&r, 6.0, INF), None);
    }

    #[test]
    fn grazing_ray_touches_once_or_misses_without_nan() {
        let r = Ray::new(Vec3A::new(0.0, 1.0, -5.0), Vec3A::Z);
        let t = unit().intersect(&r, 0.0, INF).expect("tangent ray");
        assert!((t - 5.0).abs() < 1e-3);
        let r = Ray::new(Vec3A::new(0.0, 1.0 + 1e-6, -5.0), Vec3A::Z);
        if let Some(t) = unit().intersect(&r, 0.0, INF) {
            assert!(t.is_finite());
        }
        // Tangent at its own origin: q = c = 0 must not leak a NaN.
        let r = Ray::new(Vec3A::new(0.0, 1.0, 0.0), Vec3A::X);
        assert_eq!(unit().intersect(&r, 0.0, INF), None);
    }

    #[test]
    fn distant_origin_keeps_precision() {
        let s = Sphere::new(Vec3A::new(0.0, 0.0, 1e5), 0.5);
        let r = Ray::new(Vec3A::ZERO, Vec3A::Z);
        let t = s.intersect(&r, 0.0, INF).unwrap();
        assert!((t - (1e5 - 0.5)).abs() < 1e-2, "{t}");
    }

    #[test]
    fn small_sphere_close_to_the_origin() {
        let s = Sphere::new(Vec3A::new(1e-3, 0.0, 0.0), 1e-4);
        let r = Ray::new(Vec3A::ZERO, Vec3A::X);
        let t = s.intersect(&r, 0.0, INF).unwrap();
        assert!((t - 9e-4).abs() < 1e-9, "{t}");
    }

    #[test]
    fn normal_is_unit_and_outward() {
        let s = Sphere::new(Vec3A::new(1.0, 2.0, 3.0), 2.0);
        let p = Vec3A::new(1.0, 4.0, 3.0);
        assert_eq!(s.normal_at(p), Vec3A::Y);
        let neg = Sphere::new(Vec3A::new(1.0, 2.0, 3.0), -2.0);
        assert_eq!(neg.normal_at(p), Vec3A::Y);
    }

    #[test]
    fn bounds_are_tight() {
        let s = Sphere::new(Vec3A::new(1.0, 2.0, 3.0), -2.0);
        assert_eq!(
            s.bounds(),
            Aabb::new(Vec3A::new(-1.0, 0.0, 1.0), Vec3A::new(3.0, 4.0, 5.0))
        );
    }

    proptest! {
        #![proptest_config(config())]

        #[test]
        fn rays_aimed_at_the_surface_hit_it(
            centre in point(), radius in 0.01f32..10.0, on in unit_vector(), origin in point(),
        ) {
            let s = Sphere::new(centre, radius);
            let target = centre + on * radius;
            let to = target - origin;
            prop_assume!(to.length() > 1e-2 * radius);
            let r = Ray::new(origin, to);
            let scale = radius + (origin - centre).length();
            let tol = 1e-5 * scale;
            let t = s.intersect(&r, 0.0, INF);
            prop_assert!(t.is_some());
            let t = t.unwrap();
            prop_assert!(t <= to.length() + tol);
            let hit = r.at(t);
            prop_assert!(((hit - centre).length() - radius).abs() <= tol);
            let n = s.normal_at(hit);
            prop_assert!((n.length() - 1.0).abs() < 1e-3);
            // From outside and not grazing, the first hit is the target.
            let cos = r.dir.dot(on);
            let outside = (origin - centre).length() > radius * 1.001;
            if outside && cos < -0.05 {
                prop_assert!((hit - target).length() <= 2.0 * tol);
                // Just past the hit, only the exit point remains, a chord
                // of length 2 r |cos| away, not the same point again.
                let off = 1e-4 * scale;
                let again = s.intersect(&r, t + off, INF);
                prop_assert!(again.is_some());
                let chord = again.unwrap() - t;
                prop_assert!((chord - 2.0 * radius * -cos).abs() <= 4.0 * tol + off, "{chord}");
            }
        }
    }
}
