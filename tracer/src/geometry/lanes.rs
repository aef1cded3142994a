//! One arithmetic for one primitive or for four: a ray-primitive test
//! written once over [`Lanes`] runs on `f32` (one primitive) and on `Vec4`
//! (four primitives, one a lane) with the same IEEE operations in the same
//! order in every lane. A BVH leaf testing four spheres (or triangles) at once
//! therefore gets, bit for bit, the distances testing each alone gives.

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Sub};

use glam::{BVec4A, Vec3A, Vec4};

/// A number, or four numbers tested side by side. Only exactly rounded
/// operations (no fused multiply-add, no approximate reciprocal), so one
/// lane computes what the scalar does.
pub(crate) trait Lanes:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    /// One truth value per lane.
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask>;
    /// A 3D vector per lane: `Vec3A` for one (its SIMD dot product is the
    /// scalar routines' own), [`V3`] for four.
    type Vector: Vector<Self>;

    fn splat(value: f32) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    /// `self` with the sign of `sign`.
    fn copysign(self, sign: Self) -> Self;
    fn lt(self, other: Self) -> Self::Mask;
    fn le(self, other: Self) -> Self::Mask;
    /// Per lane, `if_true` where `mask` holds, else `if_false`.
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self;
    /// Whether `mask` holds in any lane.
    fn any(mask: Self::Mask) -> bool;
    /// Whether `mask` holds in every lane.
    fn all(mask: Self::Mask) -> bool;
    /// How many numbers side by side.
    const LANES: usize;
}

impl Lanes for f32 {
    type Mask = bool;
    type Vector = Vec3A;
    const LANES: usize = 1;

    #[inline(always)]
    fn splat(value: f32) -> Self {
        value
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f32::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f32::abs(self)
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        f32::copysign(self, sign)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> bool {
        self < other
    }
    #[inline(always)]
    fn le(self, other: Self) -> bool {
        self <= other
    }
    #[inline(always)]
    fn select(mask: bool, if_true: Self, if_false: Self) -> Self {
        if mask { if_true } else { if_false }
    }
    #[inline(always)]
    fn any(mask: bool) -> bool {
        mask
    }
    #[inline(always)]
    fn all(mask: bool) -> bool {
        mask
    }
}

impl Lanes for Vec4 {
    type Mask = BVec4A;
    type Vector = V3<Vec4>;
    const LANES: usize = 4;

    #[inline(always)]
    fn splat(value: f32) -> Self {
        Vec4::splat(value)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        // Correctly rounded in every lane, like `f32::sqrt` (glam's `Vec4`
        // has no square root; this compiles to one `sqrtps`).
        Vec4::from_array(self.to_array().map(f32::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Vec4::abs(self)
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        Vec4::copysign(self, sign)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> BVec4A {
        self.cmplt(other)
    }
    #[inline(always)]
    fn le(self, other: Self) -> BVec4A {
        self.cmple(other)
    }
    #[inline(always)]
    fn select(mask: BVec4A, if_true: Self, if_false: Self) -> Self {
        Vec4::select(mask, if_true, if_false)
    }
    #[inline(always)]
    fn any(mask: BVec4A) -> bool {
        mask.any()
    }
    #[inline(always)]
    fn all(mask: BVec4A) -> bool {
        mask.all()
    }
}

/// The vector operations the tests use, per lane.
pub(crate) trait Vector<L>: Copy {
    fn sub(self, other: Self) -> Self;
    fn scale(self, s: L) -> Self;
    /// `(x x' + y y') + z z'`, the order of glam's `Vec3A::dot`.
    fn dot(self, other: Self) -> L;
    /// `self x other`, each coordinate `a.y b.z - a.z b.y` and so on, as
    /// glam's `Vec3A::cross` computes it.
    fn cross(self, other: Self) -> Self;
    /// `v` in every lane.
    fn splat(v: Vec3A) -> Self;
}

impl Vector<f32> for Vec3A {
    #[inline(always)]
    fn sub(self, other: Self) -> Self {
        self - other
    }
    #[inline(always)]
    fn scale(self, s: f32) -> Self {
        self * s
    }
    #[inline(always)]
    fn dot(self, other: Self) -> f32 {
        Vec3A::dot(self, other)
    }
    #[inline(always)]
    fn cross(self, other: Self) -> Self {
        Vec3A::cross(self, other)
    }
    #[inline(always)]
    fn splat(v: Vec3A) -> Self {
        v
    }
}

/// Three [`Lanes`], the coordinates of four points side by side.
#[derive(Clone, Copy)]
pub(crate) struct V3<L> {
    pub x: L,
    pub y: L,
    pub z: L,
}

impl<L: Lanes> Vector<L> for V3<L> {
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }
    #[inline(always)]
    fn scale(self, s: L) -> Self {
        Self {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }
    #[inline(always)]
    fn dot(self, o: Self) -> L {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    #[inline(always)]
    fn cross(self, o: Self) -> Self {
        Self {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }
    #[inline(always)]
    fn splat(v: Vec3A) -> Self {
        Self {
            x: L::splat(v.x),
            y: L::splat(v.y),
            z: L::splat(v.z),
        }
    }
}
