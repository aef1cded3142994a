//! Axis-aligned boxes as solid primitives (Kay-Kajiya slabs).

use glam::Vec3A;

use super::{Aabb, Ray};

/// A solid axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AaBox {
    /// The box's extent, which is also its bounding box.
    pub bounds: Aabb,
}

impl AaBox {
    /// The box spanned by two opposite corners; they are sorted per axis, so
    /// a file that swaps `min` and `max` still gives the intended box.
    pub fn new(min: Vec3A, max: Vec3A) -> Self {
        Self {
            bounds: Aabb::new(min.min(max), min.max(max)),
        }
    }

    /// The entry point in `(t_min, t_max)`, or the exit point when the
    /// entry is not in it (the ray starts inside, or `t_min` lies past the
    /// entry). A ray along a face counts as touching it (the slab test in
    /// [`Aabb::intersect`] is NaN-free for such rays).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        let (near, far) = self
            .bounds
            .intersect(ray, f32::NEG_INFINITY, f32::INFINITY)?;
        if near > t_min && near < t_max {
            Some(near)
        } else if far > t_min && far < t_max {
            Some(far)
        } else {
            None
        }
    }

    /// The outward unit normal of the face `point` lies on: the face whose
    /// plane is nearest. Distances are compared in absolute terms (the same
    /// as relative to one size for the whole box): a hit point's rounding
    /// error is about the same on every axis, so normalising per axis would
    /// pick a side face near the rim of a thin box's large face.
    pub(crate) fn normal_at(&self, point: Vec3A) -> Vec3A {
        let to_min = (point - self.bounds.min).abs();
        let to_max = (self.bounds.max - point).abs();
        let axis = to_min.min(to_max).min_position();
        let sign = if to_max[axis] < to_min[axis] {
            1.0
        } else {
            -1.0
        };
        let mut n = Vec3A::ZERO;
        n[axis] = sign;
        n
    }

    /// The box itself.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }
}

#[cfg(test)]
mod tests {
    use super::super::ray::strategies::{config, point};
    use super::*;
    use proptest::prelude::*;

    const INF: f32 = f32::INFINITY;

    fn cube() -> AaBox {
        AaBox::new(Vec3A::splat(-1.0), Vec3A::splat(1.0))
    }

    #[test]
    fn hit_from_outside_is_the_entry() {
        let r = Ray::new(Vec3A::new(-5.0, 0.2, 0.3), Vec3A::X);
        assert_eq!(cube().intersect(&r, 0.0, INF), Some(4.0));
    }

    #[test]
    fn miss_and_behind() {
        let r = Ray::new(Vec3A::new(-5.0, 2.0, 0.3), Vec3A::X);
        assert_eq!(cube().intersect(&r, 0.0, INF), None);
        let r = Ray::new(Vec3A::new(5.0, 0.0, 0.0), Vec3A::X);
        assert_eq!(cube().intersect(&r, 0.0, INF), None);
    }

    #[test]
    fn from_inside_is_the_exit() {
        let r = Ray::new(Vec3A::new(0.5, 0.0, 0.0), Vec3A::X);
        assert_eq!(cube().intersect(&r, 0.0, INF), Some(0.5));
        let r = Ray::new(Vec3A::new(-5.0, 0.0, 0.0), Vec3A::X);
        assert_eq!(cube().intersect(&r, 4.5, INF), Some(6.0));
        assert_eq!(cube().intersect(&r, 0.0, 3.0), None);
    }

    #[test]
    fn zero_direction_components_and_grazing() {
        // Parallel to two slabs, inside them.
        let r = Ray::new(Vec3A::new(0.3, -0.2, 9.0), -Vec3A::Z);
        assert_eq!(cube().intersect(&r, 0.0, INF), Some(8.0));
        // Parallel, outside a slab.
        let r = Ray::new(Vec3A::new(1.5, 0.0, 9.0), -Vec3A::Z);
        assert_eq!(cube().intersect(&r, 0.0, INF), None);
        // Along a face (x = 1): touches, NaN-free.
        let r = Ray::new(Vec3A::new(1.0, 0.0, 9.0), -Vec3A::Z);
        let t = cube().intersect(&r, 0.0, INF).unwrap();
        assert_eq!(t, 8.0);
        // Along an edge.
        let r = Ray::new(Vec3A::new(1.0, 1.0, 9.0), -Vec3A::Z);
        assert_eq!(cube().intersect(&r, 0.0, INF), Some(8.0));
    }

    #[test]
    fn swapped_corners_are_sorted() {
        let b = AaBox::new(Vec3A::new(1.0, -1.0, 1.0), Vec3A::new(-1.0, 1.0, -1.0));
        assert_eq!(b, cube());
    }

    #[test]
    fn normal_is_right_on_all_six_faces() {
        let b = AaBox::new(Vec3A::new(0.0, 0.0, 0.0), Vec3A::new(4.0, 2.0, 0.1));
        let c = b.bounds.centre();
        for axis in 0..3 {
            for sign in [-1.0f32, 1.0] {
                let mut p = c;
                p[axis] = if sign > 0.0 {
                    b.bounds.max[axis]
                } else {
                    b.bounds.min[axis]
                };
                let mut want = Vec3A::ZERO;
                want[axis] = sign;
                assert_eq!(b.normal_at(p), want, "axis {axis} sign {sign}");
                // Off-centre on the face, near (but not at) an edge.
                let other = (axis + 1) % 3;
                p[other] = b.bounds.max[other] - 0.01 * b.bounds.extent()[other];
                assert_eq!(b.normal_at(p), want, "axis {axis} sign {sign} near edge");
            }
        }
    }

    #[test]
    fn thin_box_large_face_near_the_rim() {
        let b = AaBox::new(Vec3A::new(0.0, 0.0, 0.0), Vec3A::new(100.0, 100.0, 0.01));
        let p = Vec3A::new(99.99, 50.0, 0.01);
        assert_eq!(b.normal_at(p), Vec3A::Z);
    }

    proptest! {
        #![proptest_config(config())]

        #[test]
        fn rays_aimed_at_the_surface_hit_it(
            corner in point(), size in (0.05f32..10.0, 0.05f32..10.0, 0.05f32..10.0),
            face in 0usize..6, uv in (0.0f32..1.0, 0.0f32..1.0), origin in point(),
            from_inside in proptest::bool::ANY,
        ) {
            let size = Vec3A::new(size.0, size.1, size.2);
            let b = AaBox::new(corner, corner + size);
            let (axis, high) = (face % 3, face >= 3);
            let mut target = corner + size * Vec3A::new(uv.0, uv.1, uv.0 * 0.7 + 0.1);
            target[axis] = if high { b.bounds.max[axis] } else { b.bounds.min[axis] };
            let origin = if from_inside { b.bounds.centre() } else { origin };
            let to = target - origin;
            prop_assume!(to.length() > 1e-2);
            let r = Ray::new(origin, to);
            let scale = 1.0 + (origin - b.bounds.centre()).length() + size.length();
            let tol = 2e-5 * scale;
            let t = b.intersect(&r, 0.0, INF);
            prop_assert!(t.is_some());
            let t = t.unwrap();
            prop_assert!(t <= to.length() + tol);
            let hit = r.at(t);
            let d_face = (hit - b.bounds.min).abs().min((b.bounds.max - hit).abs()).min_element();
            prop_assert!(d_face <= tol);
            prop_assert!(hit.cmpge(b.bounds.min - tol).all() && hit.cmple(b.bounds.max + tol).all());
            let n = b.normal_at(hit);
            prop_assert!((n.length() - 1.0).abs() < 1e-6);
            // Outward: the centre lies behind the face.
            prop_assert!((b.bounds.centre() - hit).dot(n) < 0.0);
            let cos = r.dir.dot(n).abs();
            if cos > 0.05 {
                // Entering a convex solid: the next hit is the exit, not
                // the same point again; from inside there is none.
                let off = 1e-4 * scale;
                let again = b.intersect(&r, t + off, INF);
                let inside_start = b.bounds.min.cmplt(origin).all() && origin.cmplt(b.bounds.max).all();
                if inside_start {
                    prop_assert_eq!(again, None);
                } else if let Some(t2) = again {
                    prop_assert!(t2 - t > off);
                    let exit = r.at(t2);
                    let d_exit = (exit - b.bounds.min).abs().min((b.bounds.max - exit).abs()).min_element();
                    prop_assert!(d_exit <= tol);
                }
            }
        }
    }
}
