//! A procedural sky cube, so generated scenes can ship a skybox (`env`)
//! without borrowing photographs: a vertical gradient from horizon haze to
//! a deep blue zenith, a sun disk with a glow, and darker ground below the
//! horizon. Up is +y, as in the OpenGL cube-map convention that
//! [`crate::skybox`] reads.

use glam::Vec3A;
use image::{Rgb, RgbImage};

/// Where the sun is: low in the sky, in front and to the right.
const SUN: Vec3A = Vec3A::new(0.55, 0.35, 0.76);
/// Cosine of the sun disk's angular radius (about 1.5 degrees).
const SUN_COS: f32 = 0.99966;
const ZENITH: Vec3A = Vec3A::new(0.08, 0.22, 0.55);
const HORIZON: Vec3A = Vec3A::new(0.78, 0.85, 0.92);
const GROUND: Vec3A = Vec3A::new(0.22, 0.2, 0.18);
const SUN_COLOUR: Vec3A = Vec3A::new(1.0, 0.97, 0.88);

/// The unit direction that [`crate::skybox::cube_face`] maps to `(face, s,
/// t)`: its inverse, with faces in the order +x, -x, +y, -y, +z, -z and
/// s to the right, t downwards. A face index above 5 is taken as 5.
pub(crate) fn face_direction(face: usize, s: f32, t: f32) -> Vec3A {
    let (a, b) = (2.0 * s - 1.0, 2.0 * t - 1.0);
    let d = match face {
        0 => Vec3A::new(1.0, -b, -a),
        1 => Vec3A::new(-1.0, -b, a),
        2 => Vec3A::new(a, 1.0, b),
        3 => Vec3A::new(a, -1.0, -b),
        4 => Vec3A::new(a, -b, 1.0),
        _ => Vec3A::new(-a, -b, -1.0),
    };
    d.normalize()
}

/// The sky's colour seen in `dir` (any length), each channel in [0, 1].
pub(crate) fn sky_colour(dir: Vec3A) -> Vec3A {
    let d = dir.normalize_or(Vec3A::Y);
    let base = if d.y >= 0.0 {
        // Haze fades quickly above the horizon, so most of the sky is blue.
        HORIZON.lerp(ZENITH, d.y.powf(0.45))
    } else {
        // A short blend below the horizon hides the seam.
        HORIZON.lerp(GROUND, (-d.y * 12.0).min(1.0))
    };
    let c = d.dot(SUN.normalize());
    let glow = if d.y >= -0.02 {
        0.6 * c.max(0.0).powi(256) + 0.25 * c.max(0.0).powi(16)
    } else {
        0.0
    };
    let sky = if c >= SUN_COS {
        SUN_COLOUR
    } else {
        base + SUN_COLOUR * glow
    };
    sky.clamp(Vec3A::ZERO, Vec3A::ONE)
}

/// The colour of face `face` at `(s, t)` in [0, 1]^2, as
/// [`crate::skybox::Skybox::from_fn`] expects.
pub(crate) fn paint_sky_face(face: usize, s: f32, t: f32) -> Vec3A {
    sky_colour(face_direction(face, s, t))
}

/// The six faces, `size` x `size` (at least 1), in the order right, left,
/// top, bottom, front, back ([`crate::skybox::FACE_NAMES`]), sampled at
/// pixel centres like [`crate::skybox::Skybox::sample`] reads them.
pub fn paint_sky(size: u32) -> [RgbImage; 6] {
    let size = size.max(1);
    std::array::from_fn(|face| {
        RgbImage::from_fn(size, size, |x, y| {
            let s = (x as f32 + 0.5) / size as f32;
            let t = (y as f32 + 0.5) / size as f32;
            let c = paint_sky_face(face, s, t) * 255.0;
            Rgb([c.x, c.y, c.z].map(|v| v.round().clamp(0.0, 255.0) as u8))
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skybox::cube_face;

    #[test]
    fn face_directions_round_trip_through_cube_face() {
        for face in 0..6 {
            for i in 0..=20 {
                for j in 0..=20 {
                    let (s, t) = (i as f32 / 20.0, j as f32 / 20.0);
                    let d = face_direction(face, s, t);
                    assert!((d.length() - 1.0).abs() < 1e-5);
                    let (f, s2, t2) = cube_face(d);
                    // On an edge two faces claim the direction; compare
                    // directions there instead of face indices.
                    let back = face_direction(f, s2, t2);
                    assert!(back.distance(d) < 1e-5, "{face} {s} {t}");
                    if (0.01..0.99).contains(&s) && (0.01..0.99).contains(&t) {
                        assert_eq!(f, face);
                        assert!((s2 - s).abs() < 1e-5 && (t2 - t).abs() < 1e-5);
                    }
                }
            }
        }
    }

    #[test]
    fn faces_point_along_their_axes() {
        let axes = [
            Vec3A::X,
            -Vec3A::X,
            Vec3A::Y,
            -Vec3A::Y,
            Vec3A::Z,
            -Vec3A::Z,
        ];
        for (face, axis) in axes.into_iter().enumerate() {
            assert!(face_direction(face, 0.5, 0.5).distance(axis) < 1e-6);
        }
        // Top of the side faces is up (+y): t grows downwards.
        assert!(face_direction(4, 0.5, 0.0).y > 0.5);
    }

    #[test]
    fn zenith_is_deep_blue_ground_is_dark_sun_is_bright() {
        let zenith = sky_colour(Vec3A::Y);
        assert!(zenith.z > 0.4 && zenith.x < 0.2);
        let horizon = sky_colour(Vec3A::new(-1.0, 0.01, 0.0));
        assert!(horizon.x > zenith.x);
        let ground = sky_colour(-Vec3A::Y);
        assert!(ground.max_element() < 0.3);
        assert!(sky_colour(SUN).min_element() > 0.85);
    }

    #[test]
    fn painted_faces_have_the_size_and_agree_with_the_painter() {
        let faces = paint_sky(8);
        assert!(faces.iter().all(|f| f.dimensions() == (8, 8)));
        let top = faces[2].get_pixel(4, 4);
        let bottom = faces[3].get_pixel(4, 4);
        assert!(top.0[2] > bottom.0[2]);
        assert_eq!(paint_sky(0)[0].dimensions(), (1, 1));
    }
}
