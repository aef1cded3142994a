//! Open cones and cylinders (no end caps).

use glam::Vec3A;

use super::{Aabb, Ray};

/// A truncated cone between `base` and `apex`, radii `base_radius` and
/// `apex_radius` (equal radii: a cylinder). Open at both ends.
///
/// The private fields are the local frame the intersection needs, computed
/// once in [`Cone::new`]: build cones with it, not with a struct literal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    /// Centre of the base circle.
    pub base: Vec3A,
    /// Radius at the base.
    pub base_radius: f32,
    /// Centre of the apex circle.
    pub apex: Vec3A,
    /// Radius at the apex; equal radii make a cylinder.
    pub apex_radius: f32,
    /// Unit vector from base to apex.
    axis: Vec3A,
    /// Distance from base to apex.
    height: f32,
    /// Radius change per unit of axial distance, `(apex_r - base_r) / h`.
    slope: f32,
    /// `1 / sqrt(1 + slope^2)`, the length of `radial - slope * axis`.
    normal_scale: f32,
}

impl Cone {
    /// `None` when base and apex coincide or both radii are zero (or any
    /// input is not finite). Negative radii (NFF's inside-only flag) are
    /// taken by absolute value.
    pub fn new(base: Vec3A, base_radius: f32, apex: Vec3A, apex_radius: f32) -> Option<Self> {
        let (base_radius, apex_radius) = (base_radius.abs(), apex_radius.abs());
        let (axis, height) = (apex - base).normalize_and_length();
        let finite = base.is_finite() && apex.is_finite() && height.is_finite();
        let radii_ok = base_radius.is_finite()
            && apex_radius.is_finite()
            && (base_radius > 0.0 || apex_radius > 0.0);
        // `height > 0.0` is false for NaN as well.
        let valid = finite && radii_ok && height > 0.0;
        if !valid {
            return None;
        }
        let slope = (apex_radius - base_radius) / height;
        if !slope.is_finite() {
            return None;
        }
        Some(Self {
            base,
            base_radius,
            apex,
            apex_radius,
            axis,
            height,
            slope,
            normal_scale: (1.0 + slope * slope).sqrt().recip(),
        })
    }

    /// The nearest hit in `(t_min, t_max)` on the lateral surface.
    ///
    /// With `w = origin - base` split into its axial part `ws` and the
    /// perpendicular rest `wp` (likewise `ds`, `dp` for the direction), a
    /// point at `t` lies on the infinite cone when
    /// `|wp + t dp|^2 = (r(ws) + t slope ds)^2`, a quadratic solved with the
    /// cancellation-free `q` form. Working with the perpendicular parts
    /// directly (not `|w|^2 - ws^2`) keeps digits for distant origins. Each
    /// root in turn, nearest first, is kept when its axial coordinate lies
    /// in `[0, height]`, so a ray through an open end sees the inner wall.
    /// A ray parallel to a generator (`a = 0`) gets its single root from
    /// `c / q`; one on the surface gets none. NaN roots fail the tests.
    ///
    /// The quadratic is solved from the point of the ray nearest the
    /// cone's middle, not from the ray's origin: seen from far away, a thin
    /// cone's `c` and discriminant are differences of nearly equal large
    /// squares, which lost every digit of the radius (jacks' rods, 2 mm
    /// thick seen from 5 m, were hit up to a tenth of their radius off
    /// their surface, outside their bounding box). From nearby, the terms
    /// are of the cone's own size.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        let middle = (self.base + self.apex) * 0.5;
        let shift = (middle - ray.origin).dot(ray.dir);
        let w = ray.origin + ray.dir * shift - self.base;
        let ws = w.dot(self.axis);
        let ds = ray.dir.dot(self.axis);
        let wp = w - self.axis * ws;
        let dp = ray.dir - self.axis * ds;
        let rw = self.base_radius + self.slope * ws;
        let ks = self.slope * ds;
        let a = dp.length_squared() - ks * ks;
        let b = wp.dot(dp) - rw * ks;
        let c = wp.length_squared() - rw * rw;
        let disc = b * b - a * c;
        // A NaN discriminant passes on to NaN roots, which the tests reject.
        if disc < 0.0 {
            return None;
        }
        let q = -(b + disc.sqrt().copysign(b));
        let (t0, t1) = (q / a, c / q);
        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        for local in [near, far] {
            let t = shift + local;
            if t > t_min && t < t_max {
                let s = ws + local * ds;
                if (0.0..=self.height).contains(&s) {
                    return Some(t);
                }
            }
        }
        None
    }

    /// The outward unit normal of the lateral surface at `point`: the
    /// radial direction tilted back along the axis by the slope. At the tip
    /// of a true cone, where the radial direction is undefined, some
    /// perpendicular of the axis stands in.
    pub(crate) fn normal_at(&self, point: Vec3A) -> Vec3A {
        let q = point - self.base;
        let radial = q - self.axis * q.dot(self.axis);
        let u = radial.normalize_or(self.axis.any_orthonormal_vector());
        (u - self.axis * self.slope) * self.normal_scale
    }

    /// The union of the two end discs' boxes: a disc of radius `r` around
    /// axis `a` reaches `r sqrt(1 - a_i^2)` along axis `i`.
    pub fn bounds(&self) -> Aabb {
        let reach = (Vec3A::ONE - self.axis * self.axis)
            .max(Vec3A::ZERO)
            .map(f32::sqrt);
        let (eb, ea) = (reach * self.base_radius, reach * self.apex_radius);
        Aabb::new(
            (self.base - eb).min(self.apex - ea),
            (self.base + eb).max(self.apex + ea),
        )
    }

    /// The unit axis from base to apex.
    pub fn axis(&self) -> Vec3A {
        self.axis
    }

    /// The distance from base to apex.
    pub fn height(&self) -> f32 {
        self.height
    }
}

#[cfg(test)]
mod tests {
    use super::super::ray::strategies::{config, point, unit_vector};
    use super::*;
    use proptest::prelude::*;

    const INF: f32 = f32::INFINITY;

    /// Radius 1, from z = 0 to z = 2.
    fn cylinder() -> Cone {
        Cone::new(Vec3A::ZERO, 1.0, Vec3A::Z * 2.0, 1.0).unwrap()
    }

    /// Radius 1 at z = 0 to a tip at z = 1 (45 degrees).
    fn cone() -> Cone {
        Cone::new(Vec3A::ZERO, 1.0, Vec3A::Z, 0.0).unwrap()
    }

    /// Distance from the lateral surface, signed, in the axial plane.
    fn surface_distance(c: &Cone, p: Vec3A) -> f32 {
        let q = p - c.base;
        let s = q.dot(c.axis());
        let rho = (q - c.axis() * s).length();
        let r = c.base_radius + (c.apex_radius - c.base_radius) * s / c.height();
        (rho - r) * c.normal_scale
    }

    #[test]
    fn degenerate_cones_are_rejected() {
        assert!(Cone::new(Vec3A::ONE, 1.0, Vec3A::ONE, 2.0).is_none());
        assert!(Cone::new(Vec3A::ZERO, 0.0, Vec3A::Z, 0.0).is_none());
        assert!(Cone::new(Vec3A::ZERO, f32::NAN, Vec3A::Z, 1.0).is_none());
        assert!(Cone::new(Vec3A::ZERO, 1.0, Vec3A::splat(f32::INFINITY), 1.0).is_none());
        let neg = Cone::new(Vec3A::ZERO, -1.0, Vec3A::Z, -0.5).unwrap();
        assert_eq!((neg.base_radius, neg.apex_radius), (1.0, 0.5));
    }

    #[test]
    fn cylinder_hit_from_outside() {
        let r = Ray::new(Vec3A::new(-5.0, 0.0, 1.0), Vec3A::X);
        assert_eq!(cylinder().intersect(&r, 0.0, INF), Some(4.0));
    }

    #[test]
    fn cylinder_misses_beside_and_beyond_the_ends() {
        let beside = Ray::new(Vec3A::new(-5.0, 1.5, 1.0), Vec3A::X);
        assert_eq!(cylinder().intersect(&beside, 0.0, INF), None);
        let above = Ray::new(Vec3A::new(-5.0, 0.0, 2.5), Vec3A::X);
        assert_eq!(cylinder().intersect(&above, 0.0, INF), None);
        let behind = Ray::new(Vec3A::new(5.0, 0.0, 1.0), Vec3A::X);
        assert_eq!(cylinder().intersect(&behind, 0.0, INF), None);
    }

    #[test]
    fn from_inside_hits_the_inner_wall() {
        let r = Ray::new(Vec3A::new(0.0, 0.0, 1.0), Vec3A::Y);
        assert_eq!(cylinder().intersect(&r, 0.0, INF), Some(1.0));
        let r = Ray::new(Vec3A::new(0.0, 0.0, 0.5), Vec3A::X);
        let t = cone().intersect(&r, 0.0, INF).unwrap();
        assert!((t - 0.5).abs() < 1e-6);
    }

    #[test]
    fn through_the_open_end_sees_the_inner_wall() {
        // Enters above the top rim (near root clipped), hits the far wall.
        let r = Ray::new(Vec3A::new(-2.5, 0.0, 4.0), Vec3A::new(1.0, 0.0, -1.0));
        let t = cylinder().intersect(&r, 0.0, INF).unwrap();
        let p = r.at(t);
        assert!((p - Vec3A::new(1.0, 0.0, 0.5)).length() < 1e-5, "{p}");
        // Straight down the axis: parallel to the wall, no hit.
        let r = Ray::new(Vec3A::new(0.3, 0.0, 5.0), -Vec3A::Z);
        assert_eq!(cylinder().intersect(&r, 0.0, INF), None);
    }

    #[test]
    fn parallel_to_a_generator_gives_one_root() {
        // Direction along the cone's 45-degree generator, offset inwards.
        let d = Vec3A::new(-1.0, 0.0, 1.0);
        let r = Ray::new(Vec3A::new(0.5, 0.0, -0.5), d);
        let t = cone().intersect(&r, 0.0, INF).unwrap();
        assert!(t.is_finite());
        assert!(surface_distance(&cone(), r.at(t)).abs() < 1e-5);
        // Exactly on the surface along a generator: no NaN, no point hit.
        let on = Ray::new(Vec3A::new(1.0, 0.0, 0.0), d);
        if let Some(t) = cone().intersect(&on, 0.0, INF) {
            assert!(t.is_finite());
        }
        // Cylinder wall, ray along it (a = b = 0).
        let wall = Ray::new(Vec3A::new(1.0, 0.0, -1.0), Vec3A::Z);
        assert_eq!(cylinder().intersect(&wall, 0.0, INF), None);
    }

    #[test]
    fn grazing_tangent_ray() {
        let r = Ray::new(Vec3A::new(-5.0, 1.0, 1.0), Vec3A::X);
        let t = cylinder().intersect(&r, 0.0, INF);
        if let Some(t) = t {
            assert!((t - 5.0).abs() < 1e-2);
        }
        let r = Ray::new(Vec3A::new(-5.0, 1.0 + 1e-6, 1.0), Vec3A::X);
        if let Some(t) = cylinder().intersect(&r, 0.0, INF) {
            assert!(t.is_finite());
        }
    }

    /// A 2 mm rod seen from 5 m away (a pixel of jacks): the ray passes
    /// beside it, outside its bounding box, and used to hit it a tenth of
    /// its radius off its surface; a ray aimed at the rod's surface hits it
    /// there, to a small fraction of the radius.
    #[test]
    fn thin_cylinders_far_away_are_hit_on_their_surface_only() {
        let rod = Cone::new(
            Vec3A::new(0.074088, -0.250488, 2.0164),
            0.0018670176,
            Vec3A::new(0.13632192, -0.250488, 2.0164),
            0.0018670176,
        )
        .unwrap();
        let eye = Vec3A::new(3.2, -4.0, 2.6);
        let beside = Ray::new(eye, Vec3A::new(-0.6313017, 0.7662357, -0.11975373));
        assert_eq!(rod.bounds().intersect(&beside, 0.0, INF), None);
        assert_eq!(rod.intersect(&beside, 0.0, INF), None);
        for phi in [0.3f32, 1.9, 2.8, 4.0] {
            let target = Vec3A::new(0.1, -0.250488, 2.0164)
                + Vec3A::new(0.0, phi.cos(), phi.sin()) * 0.0018670176;
            let ray = Ray::new(eye, target - eye);
            if let Some(t) = rod.intersect(&ray, 0.0, INF) {
                let off = surface_distance(&rod, ray.at(t)).abs();
                assert!(off < 1e-2 * rod.base_radius, "{phi}: {off}");
            }
        }
    }

    #[test]
    fn the_mirror_nappe_beyond_the_tip_is_ignored() {
        let r = Ray::new(Vec3A::new(-5.0, 0.0, 1.5), Vec3A::X);
        assert_eq!(cone().intersect(&r, 0.0, INF), None);
    }

    #[test]
    fn normals_are_unit_and_outward() {
        let n = cylinder().normal_at(Vec3A::new(0.0, 1.0, 1.0));
        assert!((n - Vec3A::Y).length() < 1e-6);
        let n = cone().normal_at(Vec3A::new(0.5, 0.0, 0.5));
        assert!((n - Vec3A::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
        let widening = Cone::new(Vec3A::ZERO, 0.0, Vec3A::Z, 1.0).unwrap();
        let n = widening.normal_at(Vec3A::new(0.0, 0.5, 0.5));
        assert!((n - Vec3A::new(0.0, 1.0, -1.0).normalize()).length() < 1e-6);
        let tip = cone().normal_at(Vec3A::Z);
        assert!((tip.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn bounds_cover_the_end_discs() {
        assert_eq!(
            cylinder().bounds(),
            Aabb::new(Vec3A::new(-1.0, -1.0, 0.0), Vec3A::new(1.0, 1.0, 2.0))
        );
        let tilted = Cone::new(Vec3A::ZERO, 1.0, Vec3A::new(1.0, 1.0, 0.0), 0.5).unwrap();
        let b = tilted.bounds();
        let h = 0.5f32.sqrt();
        assert!((b.min - Vec3A::new(-h, -h, -1.0)).length() < 1e-6, "{b:?}");
        assert!((b.max - Vec3A::new(1.0 + 0.5 * h, 1.0 + 0.5 * h, 1.0)).length() < 1e-6);
    }

    proptest! {
        #![proptest_config(config())]

        #[test]
        fn rays_aimed_at_the_surface_hit_it(
            base in point(), axis in unit_vector(), height in 0.1f32..10.0,
            radii in (0.0f32..5.0, 0.0f32..5.0), s in 0.0f32..1.0, phi in 0.0f32..std::f32::consts::TAU,
            origin in point(),
        ) {
            prop_assume!(radii.0.max(radii.1) > 0.05);
            let c = Cone::new(base, radii.0, base + axis * height, radii.1).unwrap();
            let u = axis.any_orthonormal_vector();
            let v = axis.cross(u);
            let r_s = radii.0 + (radii.1 - radii.0) * s;
            prop_assume!(r_s > 1e-2);
            let target = base + axis * (height * s) + (u * phi.cos() + v * phi.sin()) * r_s;
            let n_target = c.normal_at(target);
            let to = target - origin;
            let cos = to.normalize().dot(n_target).abs();
            prop_assume!(to.length() > 1e-2 && cos > 0.05);
            let ray = Ray::new(origin, to);
            let scale = 1.0 + (origin - base).length() + height + radii.0 + radii.1;
            let tol = 2e-5 * scale / cos;
            let t = c.intersect(&ray, 0.0, INF);
            prop_assert!(t.is_some());
            let t = t.unwrap();
            prop_assert!(t <= to.length() + tol);
            let hit = ray.at(t);
            prop_assert!(surface_distance(&c, hit).abs() <= tol, "{}", surface_distance(&c, hit));
            let s_hit = (hit - base).dot(axis);
            prop_assert!(s_hit >= -tol && s_hit <= height + tol);
            let n = c.normal_at(hit);
            prop_assert!((n.length() - 1.0).abs() < 1e-5);
            // Outward: a small step along the normal leaves the solid.
            let step = 1e-3 * scale;
            prop_assert!(surface_distance(&c, hit + n * step) > 0.0);
            let b = c.bounds();
            prop_assert!(hit.cmpge(b.min - tol).all() && hit.cmple(b.max + tol).all());
            if (hit - target).length() <= tol {
                // Just past the hit: not the same point again.
                let off = 1e-4 * scale;
                if let Some(t2) = c.intersect(&ray, t + off, INF) {
                    prop_assert!(t2 - t > off);
                    prop_assert!(surface_distance(&c, ray.at(t2)).abs() <= tol);
                }
            }
        }
    }
}
