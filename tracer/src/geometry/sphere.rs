//! Spheres.

use glam::Vec3A;

use super::{Aabb, Ray};

/// A sphere; hit from outside or from inside.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    pub centre: Vec3A,
    pub radius: f32,
}

impl Sphere {
    pub fn new(centre: Vec3A, radius: f32) -> Self {
        Self { centre, radius }
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
