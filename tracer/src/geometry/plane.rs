//! Infinite planes.

use glam::Vec3A;

use super::Ray;

/// The infinite plane `dot(p - point, normal) = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// A point on the plane.
    pub point: Vec3A,
    normal: Vec3A,
}

/// Below this `|n|` relative to `|b - a| |c - a|` (the sine of the corner
/// angle) three points count as collinear: f32 rounding noise is ~1e-7.
const COLLINEAR_SINE: f32 = 1e-6;

impl Plane {
    /// The plane through three points, `None` when they are collinear.
    /// The normal is `(b - a) x (c - a)`, normalised.
    pub(crate) fn from_points(points: [Vec3A; 3]) -> Option<Self> {
        let [a, b, c] = points;
        let (ab, ac) = (b - a, c - a);
        let n = ab.cross(ac);
        let len = n.length();
        // Written positively so NaN input is rejected too.
        let valid = len > COLLINEAR_SINE * ab.length() * ac.length() && a.is_finite();
        valid.then(|| Self {
            point: a,
            normal: n / len,
        })
    }

    /// The hit in `(t_min, t_max)`, from either side; `None` for a ray
    /// parallel to the plane (even one lying in it: the hit is not a point).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        let denom = self.normal.dot(ray.dir);
        if denom == 0.0 {
            return None;
        }
        let t = self.normal.dot(self.point - ray.origin) / denom;
        // A nearly parallel ray gives a huge or infinite t, rejected here
        // unless it fits the interval; NaN fails both comparisons.
        (t > t_min && t < t_max).then_some(t)
    }

    /// The unit normal, on the side from which `from_points`' corner is
    /// counter-clockwise.
    pub fn normal(&self) -> Vec3A {
        self.normal
    }
}

#[cfg(test)]
mod tests {
    use super::super::ray::strategies::{config, point, unit_vector};
    use super::*;
    use proptest::prelude::*;

    const INF: f32 = f32::INFINITY;

    fn floor() -> Plane {
        Plane::from_points([Vec3A::ZERO, Vec3A::Z, Vec3A::X]).unwrap()
    }

    #[test]
    fn normal_follows_the_corner_winding() {
        assert_eq!(floor().normal(), Vec3A::Y);
        let p = Plane::from_points([Vec3A::ZERO, Vec3A::X * 3.0, Vec3A::Y * 0.5]).unwrap();
        assert_eq!(p.normal(), Vec3A::Z);
    }

    #[test]
    fn collinear_or_coincident_points_give_none() {
        assert!(Plane::from_points([Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0]).is_none());
        assert!(Plane::from_points([Vec3A::ONE, Vec3A::ONE, Vec3A::X]).is_none());
        assert!(
            Plane::from_points([Vec3A::ZERO, Vec3A::X, Vec3A::new(f32::NAN, 1.0, 0.0)]).is_none()
        );
    }

    #[test]
    fn hit_from_both_sides() {
        let above = Ray::new(Vec3A::new(1.0, 2.0, 3.0), -Vec3A::Y);
        assert_eq!(floor().intersect(&above, 0.0, INF), Some(2.0));
        let below = Ray::new(Vec3A::new(1.0, -2.0, 3.0), Vec3A::new(0.0, 1.0, 1.0));
        let t = floor().intersect(&below, 0.0, INF).unwrap();
        assert!((t - 2.0 * 2f32.sqrt()).abs() < 1e-5);
    }

    #[test]
    fn behind_the_origin_and_beyond_t_max_miss() {
        let away = Ray::new(Vec3A::new(1.0, 2.0, 3.0), Vec3A::Y);
        assert_eq!(floor().intersect(&away, 0.0, INF), None);
        let down = Ray::new(Vec3A::new(1.0, 2.0, 3.0), -Vec3A::Y);
        assert_eq!(floor().intersect(&down, 0.0, 2.0), None);
        assert_eq!(floor().intersect(&down, 2.0, INF), None);
    }

    #[test]
    fn parallel_rays_miss_without_nan() {
        let off = Ray::new(Vec3A::new(0.0, 1.0, 0.0), Vec3A::X);
        assert_eq!(floor().intersect(&off, 0.0, INF), None);
        let inside = Ray::new(Vec3A::ZERO, Vec3A::new(1.0, 0.0, 1.0));
        assert_eq!(floor().intersect(&inside, 0.0, INF), None);
        let grazing = Ray::new(Vec3A::new(0.0, 1.0, 0.0), Vec3A::new(1.0, -1e-7, 0.0));
        if let Some(t) = floor().intersect(&grazing, 0.0, INF) {
            assert!(t.is_finite() && t > 1e6);
        }
    }

    proptest! {
        #![proptest_config(config())]

        #[test]
        fn rays_aimed_at_the_plane_hit_it(
            a in point(), n in unit_vector(), along in point(), origin in point(),
        ) {
            let u = n.any_orthonormal_vector();
            let v = n.cross(u);
            let p = Plane::from_points([a, a + u, a + v]).unwrap();
            prop_assert!((p.normal().length() - 1.0).abs() < 1e-5);
            prop_assert!((p.normal() - n).length() < 1e-4);
            let target = a + u * along.x + v * along.y;
            let to = target - origin;
            let height = (origin - a).dot(n);
            prop_assume!(height.abs() > 1e-2 && to.length() > 1e-2);
            let r = Ray::new(origin, to);
            let scale = 1.0 + (origin - a).length() + along.length();
            let tol = 1e-5 * scale;
            let t = p.intersect(&r, 0.0, INF);
            prop_assert!(t.is_some());
            let t = t.unwrap();
            prop_assert!((r.at(t) - target).length() <= tol / r.dir.dot(n).abs().max(1e-3));
            prop_assert!((r.at(t) - a).dot(p.normal()).abs() <= tol);
            // A plane is crossed once: nothing just past the hit.
            prop_assert_eq!(p.intersect(&r, t + 1e-4 * scale, INF), None);
        }
    }
}
