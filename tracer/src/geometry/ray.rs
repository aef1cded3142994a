//! Rays with their reciprocal direction precomputed, because every slab test
//! (boxes, BVH nodes, grid traversal) divides by the direction.

use glam::Vec3A;

/// A half-line `origin + t * dir`; `dir` is unit length for every ray the
/// renderer spawns, so `t` is a distance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3A,
    /// Its direction, unit length ([`Ray::new`] normalises it), so `t` is a distance.
    pub dir: Vec3A,
    /// `1 / dir` per component (infinite where a component is zero).
    pub inv_dir: Vec3A,
}

impl Ray {
    /// A ray from `origin` along `dir` (normalised here).
    pub fn new(origin: Vec3A, dir: Vec3A) -> Self {
        let dir = dir.normalize();
        Self {
            origin,
            dir,
            inv_dir: dir.recip(),
        }
    }

    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3A {
        self.origin + self.dir * t
    }
}

/// Seeded proptest strategies shared by the primitives' property tests.
#[cfg(test)]
pub(crate) mod strategies {
    use glam::Vec3A;
    use proptest::prelude::*;

    /// The fixed-seed configuration every geometry property test uses, so
    /// failures reproduce without regression files in the source tree.
    pub fn config() -> ProptestConfig {
        ProptestConfig {
            cases: 512,
            rng_seed: proptest::test_runner::RngSeed::Fixed(0x5EED),
            failure_persistence: None,
            ..ProptestConfig::default()
        }
    }

    /// A uniformly distributed unit vector.
    pub fn unit_vector() -> impl Strategy<Value = Vec3A> {
        (-1.0f32..1.0, 0.0f32..std::f32::consts::TAU).prop_map(|(z, phi)| {
            let s = (1.0 - z * z).sqrt();
            Vec3A::new(s * phi.cos(), s * phi.sin(), z)
        })
    }

    /// A point in the cube `[-20, 20]^3`.
    pub fn point() -> impl Strategy<Value = Vec3A> {
        (-20.0f32..20.0, -20.0f32..20.0, -20.0f32..20.0).prop_map(|(x, y, z)| Vec3A::new(x, y, z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_normalises_and_precomputes_the_reciprocal() {
        let r = Ray::new(Vec3A::ONE, Vec3A::new(0.0, 3.0, 4.0));
        assert!((r.dir - Vec3A::new(0.0, 0.6, 0.8)).length() < 1e-6);
        assert_eq!(r.inv_dir.x, f32::INFINITY);
        assert!((r.inv_dir.y * r.dir.y - 1.0).abs() < 1e-6);
        assert!((r.at(5.0) - Vec3A::new(1.0, 4.0, 5.0)).length() < 1e-5);
    }
}
