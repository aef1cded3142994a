//! 3D segments onto an image through a camera: clipped at the eye's near
//! plane (a segment reaching behind the camera keeps its part in front),
//! and, for the observer view, split where a rendered surface hides them.
//! The one projection the image overlays (window and command line) and the
//! observer view share.

use glam::{Vec2, Vec3A};
use tracer::camera::Camera;

/// Points nearer the eye than this fraction of the view-plane distance are
/// clipped away: their projection would run off to infinity.
const NEAR: f32 = 1e-3;

/// A camera to project through, with the near plane it clips at.
pub(crate) struct Projector<'a> {
    camera: &'a Camera,
    near: f32,
}

impl<'a> Projector<'a> {
    pub(crate) fn new(camera: &'a Camera) -> Self {
        let distance = camera.depth(
            camera.view_plane_point(0.5 * camera.width() as f32, 0.5 * camera.height() as f32),
        );
        Self {
            camera,
            near: (distance * NEAR).max(f32::MIN_POSITIVE),
        }
    }

    /// Where `point` lands in the image (continuous pixel coordinates), or
    /// `None` in front of the near plane.
    pub(crate) fn point(&self, point: Vec3A) -> Option<Vec2> {
        if self.camera.depth(point) < self.near {
            return None;
        }
        self.camera.project(point).filter(|p| p.is_finite())
    }

    /// The part of segment `a`-`b` in front of the near plane, as 3D ends,
    /// or `None` when all of it is behind.
    pub(crate) fn clip(&self, a: Vec3A, b: Vec3A) -> Option<[Vec3A; 2]> {
        let (da, db) = (self.camera.depth(a), self.camera.depth(b));
        if !(da.is_finite() && db.is_finite()) || (da < self.near && db < self.near) {
            return None;
        }
        let cut = |front: Vec3A, behind: Vec3A, df: f32, db: f32| {
            front + (behind - front) * ((df - self.near) / (df - db))
        };
        Some(match (da < self.near, db < self.near) {
            (true, false) => [cut(b, a, db, da), b],
            (false, true) => [a, cut(a, b, da, db)],
            _ => [a, b],
        })
    }

    /// Segment `a`-`b` in image coordinates, clipped at the near plane.
    pub(crate) fn segment(&self, a: Vec3A, b: Vec3A) -> Option<[Vec2; 2]> {
        let [a, b] = self.clip(a, b)?;
        Some([self.point(a)?, self.point(b)?])
    }

    /// How far `point` is from the eye, in scene units (what a rendered
    /// distance is compared with).
    pub(crate) fn distance(&self, point: Vec3A) -> f32 {
        (point - self.camera.eye()).length()
    }
}

/// The distance to the nearest surface along each pixel's eye ray, from a
/// render's distance view: what hides a line drawn into that image.
pub(crate) struct DepthMap {
    width: u32,
    height: u32,
    /// Row by row; `None` where the eye ray met nothing.
    distances: Vec<Option<f32>>,
}

/// A point counts as on the surface it lies on within this fraction of its
/// distance (a hit point, a normal's root, a line along a surface).
const ON_SURFACE: f32 = 0.02;

impl DepthMap {
    /// `None` unless there is one distance per pixel.
    pub(crate) fn new(width: u32, height: u32, distances: Vec<Option<f32>>) -> Option<Self> {
        (distances.len() == width as usize * height as usize).then_some(Self {
            width,
            height,
            distances,
        })
    }

    /// Whether a surface nearer than `point` covers it.
    pub(crate) fn hides(&self, projector: &Projector<'_>, point: Vec3A) -> bool {
        let Some(p) = projector.point(point) else {
            return false;
        };
        if p.x < 0.0 || p.y < 0.0 || p.x >= self.width as f32 || p.y >= self.height as f32 {
            return false;
        }
        self.nearer_than(p.x as u32, p.y as u32, projector.distance(point))
    }

    /// Whether the surface pixel `(x, y)` sees is nearer than `distance`.
    pub(crate) fn nearer_than(&self, x: u32, y: u32, distance: f32) -> bool {
        if x >= self.width || y >= self.height {
            return false;
        }
        self.distances[(y * self.width + x) as usize]
            .is_some_and(|surface| surface * (1.0 + ON_SURFACE) + 1e-4 < distance)
    }

    /// Segment `a`-`b` cut into `pieces` equal parts, each with whether it
    /// is hidden (tested at its middle), neighbours of the same kind merged.
    pub(crate) fn split(
        &self,
        projector: &Projector<'_>,
        [a, b]: [Vec3A; 2],
        pieces: usize,
    ) -> Vec<([Vec3A; 2], bool)> {
        self.split_params(projector, [a, b], pieces)
            .into_iter()
            .map(|([t0, t1], hidden)| ([a + (b - a) * t0, a + (b - a) * t1], hidden))
            .collect()
    }

    /// [`DepthMap::split`] as parameters along the segment (0 at `a`, 1 at
    /// `b`), for drawing part of it (an animation growing the segment).
    pub(crate) fn split_params(
        &self,
        projector: &Projector<'_>,
        [a, b]: [Vec3A; 2],
        pieces: usize,
    ) -> Vec<([f32; 2], bool)> {
        let pieces = pieces.max(1);
        let mut parts: Vec<([f32; 2], bool)> = Vec::new();
        for i in 0..pieces {
            let (t0, t1) = (i as f32 / pieces as f32, (i + 1) as f32 / pieces as f32);
            let hidden = self.hides(projector, a + (b - a) * ((t0 + t1) * 0.5));
            match parts.last_mut() {
                Some((range, was_hidden)) if *was_hidden == hidden => range[1] = t1,
                _ => parts.push(([t0, t1], hidden)),
            }
        }
        parts
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use tracer::scene::Viewpoint;

    use super::*;

    /// A 100 x 100 pinhole at z = 5 looking at the origin, 90 degrees wide.
    fn camera() -> Camera {
        let view = Viewpoint {
            from: Vec3::new(0.0, 0.0, 5.0),
            at: Vec3::ZERO,
            up: Vec3::Y,
            angle: 90.0,
            width: 100,
            height: 100,
            ..Viewpoint::default()
        };
        Camera::new(&view, 100, 100, 0.0, 1.0).unwrap()
    }

    #[test]
    fn a_segment_behind_the_eye_keeps_its_part_in_front() {
        let camera = camera();
        let projector = Projector::new(&camera);
        let (front, behind) = (Vec3A::new(1.0, 0.0, 0.0), Vec3A::new(1.0, 0.0, 10.0));
        let [a, b] = projector.clip(front, behind).unwrap();
        assert_eq!(a, front);
        assert!(camera.depth(b) > 0.0 && camera.depth(b) < 0.01, "{b}");
        assert!(projector.segment(front, behind).is_some());
        let far_behind = Vec3A::new(0.0, 0.0, 20.0);
        assert!(projector.clip(behind, far_behind).is_none());
        // The origin is the image's centre.
        let centre = projector.point(Vec3A::ZERO).unwrap();
        assert!((centre - Vec2::splat(50.0)).length() < 1e-3, "{centre}");
    }

    #[test]
    fn a_surface_hides_what_is_behind_it_and_not_what_is_on_it() {
        let camera = camera();
        let projector = Projector::new(&camera);
        // A wall at z = 0 over the whole image: every eye ray meets it at
        // the distance from the eye to its point of the wall.
        let mut distances = Vec::new();
        for y in 0..100 {
            for x in 0..100 {
                let p = camera.view_plane_point(x as f32 + 0.5, y as f32 + 0.5);
                let d = (p - camera.eye()).normalize();
                distances.push(Some(5.0 / -d.z));
            }
        }
        let depth = DepthMap::new(100, 100, distances).unwrap();
        assert!(!depth.hides(&projector, Vec3A::new(0.5, 0.5, 0.0)), "on it");
        assert!(
            !depth.hides(&projector, Vec3A::new(0.5, 0.5, 1.0)),
            "in front"
        );
        assert!(
            depth.hides(&projector, Vec3A::new(0.5, 0.5, -1.0)),
            "behind"
        );
        // A segment through the wall: visible, then hidden.
        let parts = depth.split(
            &projector,
            [Vec3A::new(0.2, 0.1, 2.0), Vec3A::new(0.2, 0.1, -2.0)],
            16,
        );
        let hidden: Vec<bool> = parts.iter().map(|(_, h)| *h).collect();
        assert_eq!(hidden, [false, true]);
        assert!(parts[0].0[1].z.abs() < 0.26, "cut near the wall");
        assert!(DepthMap::new(2, 2, vec![None; 3]).is_none());
    }
}
