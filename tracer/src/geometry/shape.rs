//! The closed set of primitives the renderer intersects.

use glam::Vec3A;

use super::{AaBox, Aabb, Cone, Plane, Ray, Sphere, Triangle};

/// Normals at a surface point, both unit length and on the primitive's
/// "outside" (not yet flipped towards the incoming ray).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceNormal {
    /// The true surface normal: decides which side a point lies on and where
    /// secondary rays start.
    pub geometric: Vec3A,
    /// The normal used for lighting: interpolated for patches, otherwise the
    /// geometric one.
    pub shading: Vec3A,
}

/// Every primitive the renderer knows, as an enum so hot loops dispatch with
/// a match instead of a virtual call.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A sphere.
    Sphere(Sphere),
    /// An infinite plane: unbounded, so outside any grid or BVH.
    Plane(Plane),
    /// A triangle, flat or with vertex normals (polygons and meshes become these).
    Triangle(Triangle),
    /// An axis-aligned box.
    Box(AaBox),
    /// An open cone or cylinder.
    Cone(Cone),
}

impl Shape {
    /// The smallest `t` in the open interval `(t_min, t_max)` where `ray`
    /// meets the surface, if any.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        match self {
            Shape::Sphere(s) => s.intersect(ray, t_min, t_max),
            Shape::Plane(p) => p.intersect(ray, t_min, t_max),
            Shape::Triangle(t) => t.intersect(ray, t_min, t_max),
            Shape::Box(b) => b.intersect(ray, t_min, t_max),
            Shape::Cone(c) => c.intersect(ray, t_min, t_max),
        }
    }

    /// Normals at `point`, a point on the surface found by [`Shape::intersect`].
    pub(crate) fn normal_at(&self, point: Vec3A) -> SurfaceNormal {
        match self {
            Shape::Sphere(s) => SurfaceNormal::flat(s.normal_at(point)),
            Shape::Plane(p) => SurfaceNormal::flat(p.normal()),
            Shape::Triangle(t) => t.normal_at(point),
            Shape::Box(b) => SurfaceNormal::flat(b.normal_at(point)),
            Shape::Cone(c) => SurfaceNormal::flat(c.normal_at(point)),
        }
    }

    /// The bounding box, or `None` for unbounded primitives (planes), which
    /// acceleration structures keep outside and always test.
    pub fn bounds(&self) -> Option<Aabb> {
        match self {
            Shape::Sphere(s) => Some(s.bounds()),
            Shape::Plane(_) => None,
            Shape::Triangle(t) => Some(t.bounds()),
            Shape::Box(b) => Some(b.bounds()),
            Shape::Cone(c) => Some(c.bounds()),
        }
    }

    /// A short name for statistics ("sphere", "triangle", ...).
    pub fn kind_name(&self) -> &'static str {
        match self {
            Shape::Sphere(_) => "sphere",
            Shape::Plane(_) => "plane",
            Shape::Triangle(_) => "triangle",
            Shape::Box(_) => "box",
            Shape::Cone(_) => "cone",
        }
    }
}

impl SurfaceNormal {
    /// A surface whose shading normal is its geometric normal.
    pub fn flat(n: Vec3A) -> Self {
        Self {
            geometric: n,
            shading: n,
        }
    }
}
