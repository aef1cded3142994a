//! Open cones and cylinders (no end caps).

use glam::Vec3A;

use super::{Aabb, Ray};

/// A truncated cone between `base` and `apex`, radii `base_radius` and
/// `apex_radius` (equal radii: a cylinder). Open at both ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    pub base: Vec3A,
    pub base_radius: f32,
    pub apex: Vec3A,
    pub apex_radius: f32,
}

impl Cone {
    /// `None` when base and apex coincide or both radii are zero.
    pub fn new(base: Vec3A, base_radius: f32, apex: Vec3A, apex_radius: f32) -> Option<Self> {
        todo!("{base} {base_radius} {apex} {apex_radius}")
    }

    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        todo!("{ray:?} {t_min} {t_max}")
    }

    pub fn normal_at(&self, point: Vec3A) -> Vec3A {
        todo!("{point}")
    }

    pub fn bounds(&self) -> Aabb {
        todo!()
    }
}
