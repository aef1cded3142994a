//! The formulas of Whitted shading, free of any scene: mirror reflection,
//! Snell refraction, Fresnel reflectance and the Blinn-Phong lobe.

use glam::Vec3A;

/// Largest magnitude of any radiance a ray brings back, and of every factor
/// that scales one: a surface's colours times Kd or Ks, a light's colour,
/// the ambient share. 10^12 times white is far beyond anything an image
/// shows, yet leaves f32 room: with every factor at most `C = 10^12`, the
/// cosine and highlight terms at most 1 and a light's sample weights
/// summing to 1, a shading point adds up at most `ambient x diffuse +
/// lights x (diffuse + specular) x light colour + (specular + 1) x
/// reflected + refracted <= (2 lights + 3) C^2`, under 1.4 x 10^29 for
/// 65536 lights, and a film sums at most 4096 such samples per pixel. A
/// file's huge but finite numbers (`f 1e30 1e30 1e30 3e38 ...`) thus
/// render as very bright, never as infinity or as the NaN that `inf * 0`
/// or `inf - inf` would make.
pub(crate) const MAX_RADIANCE: f32 = 1e12;

/// `v` with every component clamped to `-MAX_RADIANCE..=MAX_RADIANCE`, and
/// NaN (which only an unbounded computation makes) as 0.
#[inline]
pub fn bounded(v: Vec3A) -> Vec3A {
    let clamped = v.clamp(Vec3A::splat(-MAX_RADIANCE), Vec3A::splat(MAX_RADIANCE));
    Vec3A::select(v.is_nan_mask(), Vec3A::ZERO, clamped)
}

/// Mirror reflection of the incoming direction `d` about the normal `n`
/// (both unit; `n` may face either way): `r = d - 2 (d . n) n`.
#[inline]
pub(crate) fn reflect(d: Vec3A, n: Vec3A) -> Vec3A {
    d - n * (2.0 * d.dot(n))
}

/// Snell refraction of the incoming unit direction `d` through a surface
/// with unit normal `n` facing the incoming side (`d . n < 0`), with
/// `eta = n_incident / n_transmitted`. `None` on total internal reflection.
#[inline]
pub(crate) fn refract(d: Vec3A, n: Vec3A, eta: f32) -> Option<Vec3A> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i).max(0.0);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((d * eta + n * (eta * cos_i - cos_t)).normalize())
}

/// Fresnel reflectance of an unpolarised wave at a dielectric boundary
/// (the exact equations, averaged over both polarisations): `cos_i` is the
/// cosine of the incidence angle, `eta = n_incident / n_transmitted`.
/// Returns 1 on total internal reflection.
pub fn fresnel(cos_i: f32, eta: f32) -> f32 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let r_s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_s * r_s + r_p * r_p)
}

/// The Blinn-Phong terms for one light: `(diffuse, specular)` factors,
/// `n . l` and `(n . h)^shine` with `h` halfway between the light direction
/// `l` and the direction to the viewer `v` (all unit, `n` facing the viewer).
/// Both are at most 1: `n . h` is clamped, as rounding can put it just
/// above 1, which a huge exponent would raise to infinity.
#[inline]
pub(crate) fn blinn_phong(n: Vec3A, l: Vec3A, v: Vec3A, shine: f32) -> (f32, f32) {
    let n_dot_l = n.dot(l).max(0.0);
    let h = (l + v).normalize_or_zero();
    let n_dot_h = n.dot(h).clamp(0.0, 1.0);
    let specular = if n_dot_l > 0.0 {
        n_dot_h.powf(shine)
    } else {
        0.0
    };
    (n_dot_l, specular)
}

#[cfg(test)]
mod tests {
    use super::*;

    const EPS: f32 = 1e-5;

    #[test]
    fn reflection_mirrors_about_the_normal() {
        let d = Vec3A::new(1.0, -1.0, 0.0).normalize();
        let r = reflect(d, Vec3A::Y);
        assert!((r - Vec3A::new(1.0, 1.0, 0.0).normalize()).length() < EPS);
        // Either side of the normal gives the same reflection.
        assert!((reflect(d, Vec3A::NEG_Y) - r).length() < EPS);
        // The course's form r = 2 (L . n) n - L with L = -d.
        let l = -d;
        assert!((r - (Vec3A::Y * 2.0 * l.dot(Vec3A::Y) - l)).length() < EPS);
    }

    #[test]
    fn refraction_obeys_snell() {
        let n = Vec3A::Y;
        for deg in [0.0f32, 10.0, 30.0, 45.0, 60.0, 80.0] {
            let a = deg.to_radians();
            let d = Vec3A::new(a.sin(), -a.cos(), 0.0);
            let t = refract(d, n, 1.0 / 1.5).unwrap();
            assert!((t.length() - 1.0).abs() < EPS);
            let sin_t = t.x;
            assert!((a.sin() - 1.5 * sin_t).abs() < 1e-5, "{deg}");
            assert!(t.y < 0.0, "transmitted ray continues through the surface");
        }
        // Normal incidence passes straight through.
        let t = refract(Vec3A::NEG_Y, n, 1.0 / 1.5).unwrap();
        assert!((t - Vec3A::NEG_Y).length() < EPS);
    }

    #[test]
    fn total_internal_reflection_beyond_the_critical_angle() {
        let n = Vec3A::Y;
        let eta = 1.5f32; // from glass into air
        let critical = (1.0 / eta).asin();
        let below = critical - 0.01;
        let above = critical + 0.01;
        let d = |a: f32| Vec3A::new(a.sin(), -a.cos(), 0.0);
        assert!(refract(d(below), n, eta).is_some());
        assert!(refract(d(above), n, eta).is_none());
        assert_eq!(fresnel(above.cos(), eta), 1.0);
        assert!(fresnel(below.cos(), eta) < 1.0);
    }

    #[test]
    fn fresnel_at_normal_and_grazing_incidence() {
        // Normal incidence: ((n1 - n2) / (n1 + n2))^2 = 0.04 for glass.
        assert!((fresnel(1.0, 1.0 / 1.5) - 0.04).abs() < 1e-6);
        assert!((fresnel(1.0, 1.5) - 0.04).abs() < 1e-6);
        // Grazing incidence reflects everything.
        assert!(fresnel(1e-4, 1.0 / 1.5) > 0.99);
        // Matched media do not reflect.
        assert!(fresnel(0.7, 1.0) < 1e-12);
        // Reflectance grows with the angle.
        let mut last = 0.0;
        for deg in (0..90).step_by(10) {
            let r = fresnel((deg as f32).to_radians().cos(), 1.0 / 1.5);
            assert!(r >= last);
            last = r;
        }
    }

    #[test]
    fn blinn_phong_values() {
        let n = Vec3A::Y;
        let l = Vec3A::new(1.0, 1.0, 0.0).normalize();
        let v = Vec3A::new(-1.0, 1.0, 0.0).normalize();
        let (d, s) = blinn_phong(n, l, v, 10.0);
        assert!((d - std::f32::consts::FRAC_1_SQRT_2).abs() < EPS);
        // The mirror configuration: h equals n, the highlight peaks at 1.
        assert!((s - 1.0).abs() < EPS);
        // Away from the mirror direction it falls off as cos^shine.
        let v2 = Vec3A::Y;
        let (_, s2) = blinn_phong(n, l, v2, 10.0);
        let h = (l + v2).normalize();
        assert!((s2 - h.dot(n).powf(10.0)).abs() < EPS);
        // A light behind the surface contributes nothing.
        assert_eq!(blinn_phong(n, -l, v, 10.0), (0.0, 0.0));
        // Nor one behind it whose halfway vector still leans towards n.
        let behind = Vec3A::new(0.6, -0.8, 0.0);
        assert!(n.dot((behind + Vec3A::Y).normalize()) > 0.0);
        assert_eq!(blinn_phong(n, behind, Vec3A::Y, 10.0), (0.0, 0.0));
    }

    /// In the mirror configuration rounding can make `n . h` a hair above
    /// 1, which the huge but finite exponent a file may give (`3e38`)
    /// raised to infinity: the highlight must stay at most 1.
    #[test]
    fn a_huge_exponent_keeps_the_highlight_at_most_one() {
        for i in 1..200 {
            let n = Vec3A::new(1.0, i as f32 * 0.37, 2.0 - i as f32 * 0.11).normalize();
            let (d, s) = blinn_phong(n, n, n, 3e38);
            assert!(d > 0.0 && s <= 1.0, "n = {n}: ({d}, {s})");
        }
    }

    #[test]
    fn bounded_clamps_and_zeroes_nan() {
        let v = bounded(Vec3A::new(f32::INFINITY, f32::NAN, -3e38));
        assert_eq!(v, Vec3A::new(MAX_RADIANCE, 0.0, -MAX_RADIANCE));
        assert_eq!(
            bounded(Vec3A::new(0.5, -2.0, 1e11)),
            Vec3A::new(0.5, -2.0, 1e11)
        );
    }
}
