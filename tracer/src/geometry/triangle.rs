//! Triangles (Moller-Trumbore), flat or with per-vertex normals.

use glam::Vec3A;

use super::lanes::{Lanes, Vector};
use super::{Aabb, Ray, SurfaceNormal};

/// Below this `|e1 x e2|` relative to `|e1| |e2|` (the sine of the corner
/// angle) a triangle counts as degenerate, and below this `|det|` relative
/// to `|e1| |e2|` a ray counts as lying in the triangle's plane. f32
/// rounding noise in both is ~1e-7, so this only rejects what the noise
/// would decide at random.
const DEGENERATE_SINE: f32 = 1e-6;

/// A triangle, stored as one vertex and two edges as Moller-Trumbore wants.
#[derive(Debug, Clone, PartialEq)]
pub struct Triangle {
    /// The first vertex.
    pub v0: Vec3A,
    /// Edge from `v0` to the second vertex.
    pub e1: Vec3A,
    /// Edge from `v0` to the third vertex.
    pub e2: Vec3A,
    /// Unit vertex normals of a patch; boxed so a flat triangle stays at
    /// 64 bytes (this and `parallel_eps` fill the padding after `e2`).
    normals: Option<Box<[Vec3A; 3]>>,
    /// `|det|` at or below this means the ray is parallel to the plane.
    parallel_eps: f32,
}

impl Triangle {
    /// A flat triangle, `None` when degenerate (zero area) or not finite.
    pub fn new(a: Vec3A, b: Vec3A, c: Vec3A) -> Option<Self> {
        let (e1, e2) = (b - a, c - a);
        let scale = e1.length() * e2.length();
        let area2 = e1.cross(e2).length();
        // Written positively so NaN is rejected as well.
        let valid = area2 > DEGENERATE_SINE * scale && scale.is_finite() && a.is_finite();
        if !valid {
            return None;
        }
        Some(Self {
            v0: a,
            e1,
            e2,
            normals: None,
            parallel_eps: DEGENERATE_SINE * scale,
        })
    }

    /// A triangle with a normal per vertex, interpolated for shading.
    ///
    /// The normals are normalised (a zero or non-finite one is replaced by
    /// the geometric normal). When they point, on average, against
    /// `(b - a) x (c - a)`, the winding is reversed (b and c swapped, with
    /// their normals) so the geometric normal lies on the same side as the
    /// shading normals, as [`SurfaceNormal`] promises.
    pub(crate) fn with_normals(a: Vec3A, b: Vec3A, c: Vec3A, normals: [Vec3A; 3]) -> Option<Self> {
        let mut t = Self::new(a, b, c)?;
        let geometric = t.e1.cross(t.e2).normalize();
        let mut ns = normals.map(|n| n.normalize_or(geometric));
        if (ns[0] + ns[1] + ns[2]).dot(geometric) < 0.0 {
            std::mem::swap(&mut t.e1, &mut t.e2);
            ns.swap(1, 2);
        }
        t.normals = Some(Box::new(ns));
        Some(t)
    }

    /// The two-sided Moller-Trumbore test: the hit in `(t_min, t_max)`.
    /// Edges and vertices count as inside, so a mesh has no cracks. A ray
    /// (nearly) in the triangle's plane misses: its barycentrics would be
    /// rounding noise.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        intersect_edges(
            self.v0,
            self.e1,
            self.e2,
            self.parallel_eps,
            ray,
            t_min,
            t_max,
        )
    }

    /// The `|det|` below which [`Triangle::intersect`] counts a ray as
    /// parallel: with `v0`, `e1` and `e2`, all [`intersect_edges`] needs.
    pub(crate) fn parallel_eps(&self) -> f32 {
        self.parallel_eps
    }

    /// The geometric normal `normalize(e1 x e2)` and, for patches, the
    /// vertex normals interpolated with the barycentric coordinates of
    /// `point` (clamped to the triangle) and normalised.
    pub(crate) fn normal_at(&self, point: Vec3A) -> SurfaceNormal {
        let n = self.e1.cross(self.e2);
        let geometric = n * n.length_recip();
        let Some(ns) = &self.normals else {
            return SurfaceNormal::flat(geometric);
        };
        let [u, v] = self.barycentric(point, n);
        let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
        let w = (1.0 - u - v).max(0.0);
        let shading = (ns[0] * w + ns[1] * u + ns[2] * v).normalize_or(geometric);
        SurfaceNormal { geometric, shading }
    }

    /// The weights `[u, v]` of `v0 + e1` and `v0 + e2` for a point in the
    /// plane (`n = e1 x e2`): `p - v0 = u e1 + v e2`, solved with cross
    /// products against `n`.
    fn barycentric(&self, point: Vec3A, n: Vec3A) -> [f32; 2] {
        let w = point - self.v0;
        let inv = n.length_squared().recip();
        [w.cross(self.e2).dot(n) * inv, self.e1.cross(w).dot(n) * inv]
    }

    /// The three vertices, in the stored winding.
    pub fn vertices(&self) -> [Vec3A; 3] {
        [self.v0, self.v0 + self.e1, self.v0 + self.e2]
    }

    /// The unit vertex normals of a patch, `None` for a flat triangle.
    pub fn vertex_normals(&self) -> Option<&[Vec3A; 3]> {
        self.normals.as_deref()
    }

    /// The tight axis-aligned bounding box.
    pub fn bounds(&self) -> Aabb {
        edges_bounds(self.v0, self.e1, self.e2)
    }
}

/// The box of the triangle stored as `v0` and its edges `e1`, `e2`: one
/// body for [`Triangle::bounds`] and the acceleration structures' packed
/// copies.
pub(crate) fn edges_bounds(v0: Vec3A, e1: Vec3A, e2: Vec3A) -> Aabb {
    let [a, b, c] = [v0, v0 + e1, v0 + e2];
    Aabb::new(a.min(b).min(c), a.max(b).max(c))
}

/// Moller-Trumbore on a triangle's stored form (see [`Triangle::intersect`]):
/// one body for [`Triangle`] and for the copies acceleration structures
/// pack for their hot loops, so both give bit-identical distances.
#[inline]
pub(crate) fn intersect_edges(
    v0: Vec3A,
    e1: Vec3A,
    e2: Vec3A,
    parallel_eps: f32,
    ray: &Ray,
    t_min: f32,
    t_max: f32,
) -> Option<f32> {
    let edges = [v0, e1, e2];
    let (hit, t) = intersect_triangles(edges, parallel_eps, ray.origin, ray.dir, t_min, t_max)?;
    hit.then_some(t)
}

/// [`intersect_edges`] for one triangle (`f32`) or four side by side
/// (`Vec4`, a triangle a lane; `[v0, e1, e2]`), with the same operations in
/// every lane: which lanes are hit in `(t_min, t_max)` and at what
/// distance. One triangle gives up (`None`) as soon as it cannot be hit;
/// four go through to the end: whether any lane is still in play is a
/// branch the CPU mostly guesses wrong on shadow rays, which pass close
/// to the triangles they miss, and the arithmetic it skipped cost less.
#[inline(always)]
pub(crate) fn intersect_triangles<L: Lanes>(
    [v0, e1, e2]: [L::Vector; 3],
    parallel_eps: L,
    origin: L::Vector,
    dir: L::Vector,
    t_min: L,
    t_max: L,
) -> Option<(L::Mask, L)> {
    let give_up = |hit: L::Mask| L::LANES == 1 && !L::any(hit);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    // Range tests are written so that NaN fails them.
    let mut hit = parallel_eps.lt(det.abs());
    if give_up(hit) {
        return None;
    }
    let inv_det = L::splat(1.0) / det;
    let s = origin.sub(v0);
    let u = s.dot(p) * inv_det;
    hit = hit & L::splat(0.0).le(u) & u.le(L::splat(1.0));
    if give_up(hit) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv_det;
    hit = hit & L::splat(0.0).le(v) & (u + v).le(L::splat(1.0));
    if give_up(hit) {
        return None;
    }
    let t = e2.dot(q) * inv_det;
    Some((hit & t_min.lt(t) & t.lt(t_max), t))
}

#[cfg(test)]
mod tests {
    use super::super::ray::strategies::{config, point, unit_vector};
    use super::*;
    use proptest::prelude::*;

    const INF: f32 = f32::INFINITY;

    /// In the plane z = 0, counter-clockwise seen from +z.
    fn tri() -> Triangle {
        Triangle::new(Vec3A::ZERO, Vec3A::X * 2.0, Vec3A::Y * 2.0).unwrap()
    }

    #[test]
    fn flat_triangle_stays_small() {
        assert_eq!(std::mem::size_of::<Triangle>(), 64);
    }

    #[test]
    fn degenerate_triangles_are_rejected() {
        assert!(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0).is_none());
        assert!(Triangle::new(Vec3A::ZERO, Vec3A::ZERO, Vec3A::X).is_none());
        assert!(Triangle::new(Vec3A::ONE, Vec3A::ONE, Vec3A::ONE).is_none());
        assert!(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::splat(f32::NAN)).is_none());
        assert!(Triangle::new(Vec3A::ZERO, Vec3A::X, Vec3A::splat(f32::INFINITY)).is_none());
        let n = [Vec3A::Z; 3];
        assert!(Triangle::with_normals(Vec3A::ZERO, Vec3A::X, Vec3A::X * 2.0, n).is_none());
    }

    #[test]
    fn hit_from_both_sides() {
        let down = Ray::new(Vec3A::new(0.5, 0.5, 3.0), -Vec3A::Z);
        assert_eq!(tri().intersect(&down, 0.0, INF), Some(3.0));
        let up = Ray::new(Vec3A::new(0.5, 0.5, -3.0), Vec3A::Z);
        assert_eq!(tri().intersect(&up, 0.0, INF), Some(3.0));
    }

    #[test]
    fn miss_outside_each_edge() {
        for (x, y) in [(-0.1, 0.5), (0.5, -0.1), (1.2, 1.2)] {
            let r = Ray::new(Vec3A::new(x, y, 1.0), -Vec3A::Z);
            assert_eq!(tri().intersect(&r, 0.0, INF), None, "{x} {y}");
        }
    }

    #[test]
    fn edges_and_vertices_are_inside() {
        for (x, y) in [(0.0, 0.5), (0.5, 0.0), (1.0, 1.0), (0.0, 0.0), (2.0, 0.0)] {
            let r = Ray::new(Vec3A::new(x, y, 1.0), -Vec3A::Z);
            assert_eq!(tri().intersect(&r, 0.0, INF), Some(1.0), "{x} {y}");
        }
    }

    #[test]
    fn behind_the_origin_and_t_range() {
        let r = Ray::new(Vec3A::new(0.5, 0.5, 3.0), Vec3A::Z);
        assert_eq!(tri().intersect(&r, 0.0, INF), None);
        let r = Ray::new(Vec3A::new(0.5, 0.5, 3.0), -Vec3A::Z);
        assert_eq!(tri().intersect(&r, 0.0, 3.0), None);
        assert_eq!(tri().intersect(&r, 3.0, INF), None);
    }

    #[test]
    fn parallel_and_in_plane_rays_miss_without_nan() {
        let above = Ray::new(Vec3A::new(-1.0, 0.5, 1.0), Vec3A::X);
        assert_eq!(tri().intersect(&above, 0.0, INF), None);
        let in_plane = Ray::new(Vec3A::new(-1.0, 0.5, 0.0), Vec3A::X);
        assert_eq!(tri().intersect(&in_plane, 0.0, INF), None);
        // Tilted triangle, ray in its plane along a non-axis direction.
        let a = Vec3A::new(0.1, 0.2, 0.3);
        let (e1, e2) = (Vec3A::new(1.0, 0.3, -0.2), Vec3A::new(-0.2, 0.9, 0.7));
        let t = Triangle::new(a, a + e1, a + e2).unwrap();
        let r = Ray::new(a - (e1 + e2) * 0.7, e1 + e2);
        if let Some(hit) = t.intersect(&r, 0.0, INF) {
            assert!(hit.is_finite());
        }
        // Grazing but not parallel: a valid hit.
        let graze = Ray::new(Vec3A::new(-1.0, 0.5, 1e-3), Vec3A::new(1.5, 0.0, -1e-3));
        let t = tri().intersect(&graze, 0.0, INF).unwrap();
        assert!(graze.at(t).z.abs() < 1e-6);
    }

    #[test]
    fn flat_normal_follows_the_winding() {
        let n = tri().normal_at(Vec3A::new(0.5, 0.5, 0.0));
        assert_eq!(n, SurfaceNormal::flat(Vec3A::Z));
        let cw = Triangle::new(Vec3A::ZERO, Vec3A::Y, Vec3A::X).unwrap();
        assert_eq!(cw.normal_at(Vec3A::splat(0.2)).geometric, -Vec3A::Z);
        assert!(cw.vertex_normals().is_none());
    }

    fn patch() -> (Triangle, [Vec3A; 3]) {
        let ns = [
            Vec3A::new(0.0, 0.0, 2.0),
            Vec3A::new(1.0, 0.0, 1.0),
            Vec3A::new(0.0, 1.0, 1.0),
        ];
        let t = Triangle::with_normals(Vec3A::ZERO, Vec3A::X, Vec3A::Y, ns).unwrap();
        (t, ns.map(Vec3A::normalize))
    }

    #[test]
    fn patch_normals_interpolate_to_the_vertex_normals() {
        let (t, ns) = patch();
        for (v, n) in t.vertices().into_iter().zip(ns) {
            let got = t.normal_at(v);
            assert!(
                (got.shading - n).length() < 1e-6,
                "{v}: {} vs {n}",
                got.shading
            );
            assert_eq!(got.geometric, Vec3A::Z);
        }
        let mid = t.normal_at(Vec3A::new(0.5, 0.0, 0.0)).shading;
        assert!((mid - (ns[0] + ns[1]).normalize()).length() < 1e-6);
        let centre = t.normal_at(Vec3A::splat(1.0 / 3.0).with_z(0.0)).shading;
        assert!((centre - (ns[0] + ns[1] + ns[2]).normalize()).length() < 1e-6);
        assert!((centre.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn patch_against_its_winding_is_flipped_to_agree() {
        let ns = [-Vec3A::Z, -Vec3A::Z, Vec3A::new(0.0, 0.6, -0.8)];
        let (a, b, c) = (Vec3A::ZERO, Vec3A::X, Vec3A::Y);
        let t = Triangle::with_normals(a, b, c, ns).unwrap();
        assert_eq!(t.normal_at(a).geometric, -Vec3A::Z);
        for (v, n) in [a, b, c].into_iter().zip(ns) {
            assert!((t.normal_at(v).shading - n).length() < 1e-6);
        }
        let r = Ray::new(Vec3A::new(0.2, 0.2, 1.0), -Vec3A::Z);
        assert_eq!(t.intersect(&r, 0.0, INF), Some(1.0));
    }

    #[test]
    fn zero_vertex_normal_falls_back_to_geometric() {
        let ns = [Vec3A::ZERO, Vec3A::Z, Vec3A::Z];
        let t = Triangle::with_normals(Vec3A::ZERO, Vec3A::X, Vec3A::Y, ns).unwrap();
        assert_eq!(t.vertex_normals(), Some(&[Vec3A::Z; 3]));
        // Opposing normals that cancel: still a unit shading normal.
        let ns = [Vec3A::X, -Vec3A::X, Vec3A::Z];
        let t = Triangle::with_normals(Vec3A::ZERO, Vec3A::X, Vec3A::Y, ns).unwrap();
        let n = t.normal_at(Vec3A::new(0.5, 0.0, 0.0)).shading;
        assert!((n.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn bounds_cover_the_vertices() {
        let t = Triangle::new(
            Vec3A::new(1.0, -1.0, 0.0),
            Vec3A::new(-2.0, 0.0, 3.0),
            Vec3A::Y,
        )
        .unwrap();
        assert_eq!(
            t.bounds(),
            Aabb::new(Vec3A::new(-2.0, -1.0, 0.0), Vec3A::new(1.0, 1.0, 3.0))
        );
    }

    proptest! {
        #![proptest_config(config())]

        #[test]
        fn rays_aimed_at_the_surface_hit_it(
            a in point(), b in point(), c in point(), w in (0.0f32..1.0, 0.0f32..1.0),
            origin in point(), ns in [unit_vector(), unit_vector(), unit_vector()],
        ) {
            let t = Triangle::with_normals(a, b, c, ns);
            prop_assume!(t.is_some());
            let t = t.unwrap();
            let (u, v) = if w.0 + w.1 > 1.0 { (1.0 - w.0, 1.0 - w.1) } else { w };
            let target = t.v0 + t.e1 * u + t.e2 * v;
            let n = t.normal_at(target);
            let to = target - origin;
            let cos = to.normalize().dot(n.geometric).abs();
            prop_assume!(to.length() > 1e-2 && cos > 0.05);
            let r = Ray::new(origin, to);
            let scale = 1.0 + (origin - a).length() + (b - a).length() + (c - a).length();
            let tol = 1e-5 * scale / cos;
            let hit = t.intersect(&r, 0.0, INF);
            prop_assert!(hit.is_some());
            let hit = r.at(hit.unwrap());
            prop_assert!((hit - target).length() <= tol);
            prop_assert!((hit - t.v0).dot(n.geometric).abs() <= tol);
            prop_assert!((n.geometric.length() - 1.0).abs() < 1e-5);
            prop_assert!((n.shading.length() - 1.0).abs() < 1e-5);
            // Crossed once: nothing just past the hit.
            let t_hit = (hit - origin).length();
            prop_assert_eq!(t.intersect(&r, t_hit + 1e-4 * scale, INF), None);
        }

        #[test]
        fn vertex_normals_are_reproduced(
            a in point(), b in point(), c in point(), ns in [unit_vector(), unit_vector(), unit_vector()],
        ) {
            let t = Triangle::with_normals(a, b, c, ns);
            prop_assume!(t.is_some());
            let t = t.unwrap();
            let stored = *t.vertex_normals().unwrap();
            for (v, n) in t.vertices().into_iter().zip(stored) {
                prop_assert!((t.normal_at(v).shading - n).length() < 1e-3);
            }
            // The stored normals are the inputs, maybe reordered by a flip.
            for n in stored {
                prop_assert!(ns.iter().any(|m| (*m - n).length() < 1e-5));
            }
        }
    }
}
