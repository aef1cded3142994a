//! Planar polygons, possibly concave, split into triangles by ear clipping.

use glam::{Vec2, Vec3A};

/// Why a polygon cannot be triangulated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub(crate) enum PolygonError {
    #[error("a polygon needs at least 3 vertices, found {0}")]
    TooFewVertices(usize),
    #[error("the first three vertices are collinear, so they give no normal")]
    Degenerate,
}

/// Below this `|n|` relative to `|v1 - v0| |v2 - v0|` (the sine of the
/// first corner) the first three vertices count as collinear.
const COLLINEAR_SINE: f32 = 1e-6;

/// Splits a planar polygon into triangles (indices into `vertices`). Works
/// for concave polygons (the SPD gears); the first three vertices form a
/// convex corner that gives the polygon's normal and winding.
///
/// Ear clipping in the polygon's plane: the vertices are expressed in an
/// orthonormal basis of the plane of the first corner (an undistorted
/// projection, unlike dropping the normal's dominant axis, and centred on
/// the first vertex for precision). The polygon's orientation in that basis
/// is taken from its signed (shoelace) area, so a first corner that is not
/// convex after all does not flip the result. An ear is a strictly convex
/// vertex whose triangle contains no other reflex or flat vertex (boundary
/// included). Ear flags are kept per vertex and only the two neighbours of
/// a clipped ear are re-examined, so the work is O(n^2) at worst.
///
/// Always returns `n - 2` triangles in the polygon's own winding. When no
/// ear exists (a self-intersecting or non-planar outline, NaN coordinates)
/// the vertex with the most convex turn is clipped anyway, so the function
/// terminates and covers the outline as well as it can; it never panics.
/// Collinear and repeated vertices give zero-area triangles only when
/// unavoidable. Indices are `u32`: the renderer never holds 2^32 vertices.
pub(crate) fn triangulate_polygon(vertices: &[Vec3A]) -> Result<Vec<[u32; 3]>, PolygonError> {
    let n = vertices.len();
    if n < 3 {
        return Err(PolygonError::TooFewVertices(n));
    }
    let p0 = vertices[0];
    let (e1, e2) = (vertices[1] - p0, vertices[2] - p0);
    let normal = e1.cross(e2);
    // Written positively so NaN counts as degenerate too.
    let corner = normal.length() > COLLINEAR_SINE * e1.length() * e2.length();
    if !corner {
        return Err(PolygonError::Degenerate);
    }
    if n == 3 {
        return Ok(vec![[0, 1, 2]]);
    }
    let u = e1.normalize();
    let v = normal.normalize().cross(u);
    let pts: Vec<Vec2> = vertices
        .iter()
        .map(|&p| {
            let q = p - p0;
            Vec2::new(q.dot(u), q.dot(v))
        })
        .collect();
    let twice_area: f32 = (0..n).map(|i| pts[i].perp_dot(pts[(i + 1) % n])).sum();
    let orient = if twice_area < 0.0 { -1.0 } else { 1.0 };

    let mut ring = Ring {
        pts,
        orient,
        prev: (0..n).map(|i| (i + n - 1) % n).collect(),
        next: (0..n).map(|i| (i + 1) % n).collect(),
    };
    let mut ear: Vec<bool> = (0..n).map(|i| ring.is_ear(i)).collect();
    let mut triangles = Vec::with_capacity(n - 2);
    let mut remaining = n;
    let mut cur = 0;
    while remaining > 3 {
        let mut i = cur;
        let mut found = None;
        for _ in 0..remaining {
            if ear[i] {
                found = Some(i);
                break;
            }
            i = ring.next[i];
        }
        let i = found.unwrap_or_else(|| ring.most_convex(cur, remaining));
        let (a, c) = (ring.prev[i], ring.next[i]);
        triangles.push([a as u32, i as u32, c as u32]);
        ring.next[a] = c;
        ring.prev[c] = a;
        remaining -= 1;
        ear[a] = ring.is_ear(a);
        ear[c] = ring.is_ear(c);
        cur = c;
    }
    triangles.push([ring.prev[cur] as u32, cur as u32, ring.next[cur] as u32]);
    Ok(triangles)
}

/// The remaining outline as a doubly linked ring over the projected points.
struct Ring {
    pts: Vec<Vec2>,
    /// +1 for a counter-clockwise outline in the projection, -1 otherwise.
    orient: f32,
    prev: Vec<usize>,
    next: Vec<usize>,
}

impl Ring {
    /// Twice the signed area of the corner at `i`, positive when convex.
    fn turn(&self, i: usize) -> f32 {
        #[cfg(test)]
        tests::TURNS.with(|t| t.set(t.get() + 1));
        let (a, b, c) = (self.pts[self.prev[i]], self.pts[i], self.pts[self.next[i]]);
        self.orient * (b - a).perp_dot(c - b)
    }

    /// Whether the corner at `i` can be cut off without crossing the
    /// outline: strictly convex, and no reflex or flat vertex in (or on) its
    /// triangle. Vertices coinciding with a corner point are skipped, so
    /// repeated vertices do not block every ear. NaN makes it `false`.
    fn is_ear(&self, i: usize) -> bool {
        let convex = self.turn(i) > 0.0;
        if !convex {
            return false;
        }
        let (pa, pc) = (self.prev[i], self.next[i]);
        let (a, b, c) = (self.pts[pa], self.pts[i], self.pts[pc]);
        let inside = |p: Vec2| {
            self.orient * (b - a).perp_dot(p - a) >= 0.0
                && self.orient * (c - b).perp_dot(p - b) >= 0.0
                && self.orient * (a - c).perp_dot(p - c) >= 0.0
        };
        let mut j = self.next[pc];
        while j != pa {
            let p = self.pts[j];
            if p != a && p != b && p != c && self.turn(j) <= 0.0 && inside(p) {
                return false;
            }
            j = self.next[j];
        }
        true
    }

    /// The fallback when no ear exists: the remaining vertex with the
    /// largest turn sine (a zero-length edge scores 0, NaN never wins).
    fn most_convex(&self, start: usize, remaining: usize) -> usize {
        let mut best = (start, f32::NEG_INFINITY);
        let mut i = start;
        for _ in 0..remaining {
            let (a, b, c) = (self.pts[self.prev[i]], self.pts[i], self.pts[self.next[i]]);
            let lengths = (b - a).length() * (c - b).length();
            let sine = if lengths > 0.0 {
                self.turn(i) / lengths
            } else {
                0.0
            };
            if sine > best.1 {
                best = (i, sine);
            }
            i = self.next[i];
        }
        best.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{Mat3A, Vec3};
    use proptest::prelude::*;

    fn flat(points: &[(f32, f32)]) -> Vec<Vec3A> {
        points.iter().map(|&(x, y)| Vec3A::new(x, y, 0.0)).collect()
    }

    fn shoelace(p: &[Vec2]) -> f32 {
        (0..p.len())
            .map(|i| p[i].perp_dot(p[(i + 1) % p.len()]))
            .sum::<f32>()
            * 0.5
    }

    /// Crossing-number point-in-polygon test.
    fn inside(p: Vec2, poly: &[Vec2]) -> bool {
        let mut odd = false;
        let mut j = poly.len() - 1;
        for i in 0..poly.len() {
            let (a, b) = (poly[i], poly[j]);
            if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
                odd = !odd;
            }
            j = i;
        }
        odd
    }

    /// Checks a triangulation of a simple polygon lying in the plane
    /// spanned by `u` and `v` (orthonormal, 2D coordinates `poly`): count,
    /// valid indices, winding, total area and every centroid inside.
    fn check(vertices: &[Vec3A], poly: &[Vec2], tris: &[[u32; 3]]) {
        let n = vertices.len();
        assert_eq!(tris.len(), n - 2);
        // Newell's normal: the polygon's orientation even when the first
        // corner of a random test polygon happens to be reflex.
        let normal = (0..n)
            .map(|i| vertices[i].cross(vertices[(i + 1) % n]))
            .sum::<Vec3A>()
            .normalize();
        let area = shoelace(poly).abs();
        let mut sum = 0.0;
        for t in tris {
            assert!(t.iter().all(|&i| (i as usize) < n), "{t:?}");
            assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "{t:?}");
            let [a, b, c] = t.map(|i| vertices[i as usize]);
            let cross = (b - a).cross(c - a);
            // Same winding as the polygon.
            assert!(cross.dot(normal) >= -1e-4 * area, "{t:?} winds backwards");
            sum += cross.length() * 0.5;
            let [a, b, c] = t.map(|i| poly[i as usize]);
            if (b - a).perp_dot(c - a).abs() > 1e-6 * area {
                assert!(inside((a + b + c) / 3.0, poly), "{t:?} lies outside");
            }
        }
        assert!((sum - area).abs() <= 1e-4 * area, "area {sum} vs {area}");
    }

    fn check_flat(points: &[(f32, f32)]) -> Vec<[u32; 3]> {
        let vertices = flat(points);
        let poly: Vec<Vec2> = points.iter().map(|&(x, y)| Vec2::new(x, y)).collect();
        let tris = triangulate_polygon(&vertices).unwrap();
        check(&vertices, &poly, &tris);
        tris
    }

    /// A gear outline like the SPD's: `teeth` teeth, each a pair of outer
    /// vertices followed by a pair of inner ones, starting on a convex
    /// corner.
    fn gear(teeth: usize, outer: f32, inner: f32) -> Vec<(f32, f32)> {
        let n = teeth * 4;
        (0..n)
            .map(|k| {
                let angle = std::f32::consts::TAU * k as f32 / n as f32;
                let r = if (k / 2) % 2 == 0 { outer } else { inner };
                (r * angle.cos(), r * angle.sin())
            })
            .collect()
    }

    #[test]
    fn bad_input_is_an_error() {
        assert_eq!(
            triangulate_polygon(&flat(&[(0.0, 0.0), (1.0, 0.0)])),
            Err(PolygonError::TooFewVertices(2))
        );
        assert_eq!(
            triangulate_polygon(&[]),
            Err(PolygonError::TooFewVertices(0))
        );
        let collinear = flat(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (1.0, 1.0)]);
        assert_eq!(
            triangulate_polygon(&collinear),
            Err(PolygonError::Degenerate)
        );
        let repeated = flat(&[(0.0, 0.0), (0.0, 0.0), (2.0, 0.0), (1.0, 1.0)]);
        assert_eq!(
            triangulate_polygon(&repeated),
            Err(PolygonError::Degenerate)
        );
    }

    #[test]
    fn a_triangle_is_itself() {
        let t = flat(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]);
        assert_eq!(triangulate_polygon(&t), Ok(vec![[0, 1, 2]]));
    }

    #[test]
    fn convex_square() {
        check_flat(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
    }

    #[test]
    fn concave_l_shape() {
        check_flat(&[
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (1.0, 1.0),
            (1.0, 2.0),
            (0.0, 2.0),
        ]);
    }

    #[test]
    fn clockwise_polygon_keeps_its_winding() {
        // Clockwise seen from +z, starting on a convex corner.
        check_flat(&[
            (0.0, 2.0),
            (1.0, 2.0),
            (1.0, 1.0),
            (2.0, 1.0),
            (2.0, 0.0),
            (0.0, 0.0),
        ]);
    }

    #[test]
    fn collinear_and_repeated_vertices() {
        check_flat(&[
            (1.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (2.0, 2.0),
            (2.0, 2.0),
            (1.0, 2.0),
            (1.0, 1.0),
            (0.5, 1.0),
            (0.0, 1.0),
            (0.0, 0.0),
        ]);
    }

    #[test]
    fn comb_with_many_teeth() {
        let teeth = 20;
        let mut pts = vec![(0.0, 0.0), (teeth as f32 * 2.0, 0.0)];
        for k in (0..teeth).rev() {
            let x = k as f32 * 2.0;
            pts.extend([(x + 2.0, 5.0), (x + 1.0, 5.0), (x + 1.0, 1.0), (x, 1.0)]);
        }
        pts.pop();
        check_flat(&pts);
    }

    #[test]
    fn gear_outline_with_144_vertices() {
        let tris = check_flat(&gear(36, 1.0, 0.8));
        // A fan from vertex 0 would use vertex 0 in every triangle.
        assert!(tris.iter().filter(|t| t.contains(&0)).count() < tris.len());
    }

    #[test]
    fn gear_in_a_tilted_plane() {
        let rot = Mat3A::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.9);
        let offset = Vec3A::new(10.0, -3.0, 7.0);
        let points = gear(36, 2.0, 1.7);
        let vertices: Vec<Vec3A> = points
            .iter()
            .map(|&(x, y)| rot * Vec3A::new(x, y, 0.0) + offset)
            .collect();
        let poly: Vec<Vec2> = points.iter().map(|&(x, y)| Vec2::new(x, y)).collect();
        let tris = triangulate_polygon(&vertices).unwrap();
        check(&vertices, &poly, &tris);
    }

    thread_local! {
        /// Corner turns evaluated on this thread: the unit of work of the
        /// ear clipping, counted so its growth is checked without a clock.
        pub(super) static TURNS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
    }

    /// The turns `triangulate_polygon` evaluates on a star of `n` vertices.
    fn star_work(n: usize) -> u64 {
        let pts: Vec<(f32, f32)> = (0..n)
            .map(|k| {
                let angle = std::f32::consts::TAU * k as f32 / n as f32;
                let r = if k % 2 == 0 { 0.9 } else { 1.0 };
                (r * angle.cos(), r * angle.sin())
            })
            .collect();
        TURNS.with(|t| t.set(0));
        let tris = triangulate_polygon(&flat(&pts)).unwrap();
        assert_eq!(tris.len(), n - 2);
        TURNS.with(|t| t.get())
    }

    #[test]
    fn large_star_takes_quadratic_work() {
        // Doubling the vertices multiplies the work by 4 when it is O(n^2)
        // (each clip re-examines two neighbours, each an O(n) scan) and by
        // 8 when it is O(n^3) (every flag recomputed after each clip).
        let (small, large) = (star_work(1000), star_work(2000));
        let growth = large as f64 / small as f64;
        assert!(
            growth < 5.0,
            "work grows {growth:.2}x when the vertices double ({small} -> {large} turns)"
        );
        // n first ear checks and two per clip, each at most n + 1 turns.
        let bound = 3 * 2000 * 2001;
        assert!(
            large <= bound,
            "{large} turns for 2000 vertices, over {bound}"
        );
    }

    #[test]
    fn self_intersecting_and_nan_input_terminate() {
        let bowtie = flat(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]);
        assert_eq!(triangulate_polygon(&bowtie).unwrap().len(), 2);
        let mut nan = flat(&gear(5, 1.0, 0.5));
        nan[7] = Vec3A::NAN;
        nan[11] = Vec3A::splat(f32::INFINITY);
        assert_eq!(triangulate_polygon(&nan).unwrap().len(), nan.len() - 2);
        let all_same = flat(&[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.0, 1.0), (0.0, 1.0)]);
        assert_eq!(triangulate_polygon(&all_same).unwrap().len(), 3);
    }

    proptest! {
        #![proptest_config(super::super::ray::strategies::config())]

        #[test]
        fn star_shaped_polygons_are_covered_exactly(
            radii in proptest::collection::vec(0.2f32..1.0, 4..60),
            jitter in proptest::collection::vec(0.0f32..0.9, 60),
        ) {
            let n = radii.len();
            let points: Vec<(f32, f32)> = (0..n)
                .map(|k| {
                    let angle = std::f32::consts::TAU * (k as f32 + jitter[k]) / n as f32;
                    (radii[k] * angle.cos(), radii[k] * angle.sin())
                })
                .collect();
            let vertices = flat(&points);
            let poly: Vec<Vec2> = points.iter().map(|&(x, y)| Vec2::new(x, y)).collect();
            match triangulate_polygon(&vertices) {
                Ok(tris) => check(&vertices, &poly, &tris),
                Err(e) => prop_assert_eq!(e, PolygonError::Degenerate),
            }
        }

        #[test]
        fn arbitrary_input_never_panics(
            coords in proptest::collection::vec((-5.0f32..5.0, -5.0f32..5.0, -0.1f32..0.1), 0..40),
        ) {
            let vertices: Vec<Vec3A> = coords.iter().map(|&(x, y, z)| Vec3A::new(x, y, z)).collect();
            match triangulate_polygon(&vertices) {
                Ok(tris) => {
                    prop_assert_eq!(tris.len(), vertices.len() - 2);
                    for t in tris {
                        prop_assert!(t.iter().all(|&i| (i as usize) < vertices.len()));
                        prop_assert!(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
                    }
                }
                Err(PolygonError::TooFewVertices(k)) => prop_assert!(k < 3),
                Err(PolygonError::Degenerate) => {}
            }
        }
    }
}
