//! Triangles (Moller-Trumbore), flat or with per-vertex normals.

use glam::Vec3A;

use super::{Aabb, Ray, SurfaceNormal};

/// A triangle, stored as one vertex and two edges as Moller-Trumbore wants.
#[derive(Debug, Clone, PartialEq)]
pub struct Triangle {
    pub v0: Vec3A,
    pub e1: Vec3A,
    pub e2: Vec3A,
}

impl Triangle {
    /// A flat triangle, `None` when degenerate (zero area).
    pub fn new(a: Vec3A, b: Vec3A, c: Vec3A) -> Option<Self> {
        todo!("{a} {b} {c}")
    }

    /// A triangle with a normal per vertex, interpolated for shading.
    pub fn with_normals(a: Vec3A, b: Vec3A, c: Vec3A, normals: [Vec3A; 3]) -> Option<Self> {
        todo!("{a} {b} {c} {normals:?}")
    }

    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        todo!("{ray:?} {t_min} {t_max}")
    }

    pub fn normal_at(&self, point: Vec3A) -> SurfaceNormal {
        todo!("{point}")
    }

    pub fn bounds(&self) -> Aabb {
        todo!()
    }
}
