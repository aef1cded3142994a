//! Axis-aligned boxes as solid primitives (Kay-Kajiya slabs).

use glam::Vec3A;

use super::{Aabb, Ray};

/// A solid axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AaBox {
    pub bounds: Aabb,
}

impl AaBox {
    pub fn new(min: Vec3A, max: Vec3A) -> Self {
        Self {
            bounds: Aabb::new(min, max),
        }
    }

    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        todo!("{ray:?} {t_min} {t_max}")
    }

    pub fn normal_at(&self, point: Vec3A) -> Vec3A {
        todo!("{point}")
    }

    pub fn bounds(&self) -> Aabb {
        self.bounds
    }
}
