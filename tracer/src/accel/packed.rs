//! Primitives packed for the traversal's hot loop: spheres and flat
//! triangles (and patches) copied into 48-byte records, in leaf order, half the size of
//! the general [`Shape`] enum (whose cones make it 96 bytes), with the
//! world index inside, so a leaf's primitives are one short run of memory.
//! Every other shape stays a [`Shape`] in the world, reached through the
//! index. Intersections run the primitives' own routines on the copied
//! fields: same arithmetic, same bits as testing the [`Shape`].

use glam::{Vec3A, Vec4};

use crate::geometry::{Aabb, Ray, Shape, Sphere, intersect_edges};

use super::Primitive;

/// What a record holds, stored as float bits in `b.w`.
const SPHERE: u32 = 0;
const TRIANGLE: u32 = 1;
/// Any other shape: tested through the world's [`Shape`].
const OTHER: u32 = 2;

/// One primitive: a sphere is `a = (centre, radius)`; a triangle is
/// `a = (v0, parallel_eps)`, `b = e1`, `c = e2`; `b.w` is the kind and
/// `c.w` the index in the world's shapes, both as float bits.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(16))]
pub(super) struct PackedShape {
    a: Vec4,
    b: Vec4,
    c: Vec4,
}

impl PackedShape {
    /// The record of `shape`, which is shape `id` of the world.
    pub(super) fn new(shape: &Shape, id: u32) -> Self {
        let (a, b, c, kind) = match shape {
            Shape::Sphere(s) => (s.centre.extend(s.radius), Vec3A::ZERO, Vec3A::ZERO, SPHERE),
            // Patches intersect like flat triangles (their normals, in the
            // world's shape, only matter for shading): packed too.
            Shape::Triangle(t) => (t.v0.extend(t.parallel_eps()), t.e1, t.e2, TRIANGLE),
            _ => (Vec4::ZERO, Vec3A::ZERO, Vec3A::ZERO, OTHER),
        };
        Self {
            a,
            b: b.extend(f32::from_bits(kind)),
            c: c.extend(f32::from_bits(id)),
        }
    }

    /// The bounding box of a packed sphere or triangle, `None` for other
    /// shapes (whose data stays in the world), for validation.
    pub(super) fn bounds(&self) -> Option<Aabb> {
        let a = Vec3A::from_vec4(self.a);
        match self.b.w.to_bits() {
            SPHERE => Some(Sphere::new(a, self.a.w).bounds()),
            TRIANGLE => {
                let [b, c] = [self.b, self.c].map(|e| a + Vec3A::from_vec4(e));
                Some(Aabb::new(a.min(b).min(c), a.max(b).max(c)))
            }
            _ => None,
        }
    }
}

impl Primitive for PackedShape {
    #[inline(always)]
    fn id(&self) -> u32 {
        self.c.w.to_bits()
    }

    /// The same as `shapes[self.id()].intersect(ray, t_min, t_max)`, bit
    /// for bit.
    #[inline(always)]
    fn intersect(&self, shapes: &[Shape], ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        match self.b.w.to_bits() {
            SPHERE => Sphere::new(Vec3A::from_vec4(self.a), self.a.w).intersect(ray, t_min, t_max),
            TRIANGLE => intersect_edges(
                Vec3A::from_vec4(self.a),
                Vec3A::from_vec4(self.b),
                Vec3A::from_vec4(self.c),
                self.a.w,
                ray,
                t_min,
                t_max,
            ),
            _ => shapes[self.id() as usize].intersect(ray, t_min, t_max),
        }
    }
}
