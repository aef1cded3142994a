//! Infinite planes.

use glam::Vec3A;

use super::Ray;

/// The infinite plane `dot(p - point, normal) = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    pub point: Vec3A,
    normal: Vec3A,
}

impl Plane {
    /// The plane through three points, `None` when they are collinear.
    /// The normal is `(b - a) x (c - a)`, normalised.
    pub fn from_points(points: [Vec3A; 3]) -> Option<Self> {
        todo!("{points:?}")
    }

    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        todo!("{ray:?} {t_min} {t_max}")
    }

    pub fn normal(&self) -> Vec3A {
        self.normal
    }
}
