//! Pieces every generator shares: a small seeded PRNG (so scenes are
//! reproducible without a dependency) and a scene builder that keeps
//! materials in the order the P3F writer needs to round-trip them.

use glam::Vec3;

use crate::scene::{LightSpec, Material, Object, Primitive, Scene, Viewpoint};

/// The SPD background colour, used by every SPD scene.
pub(super) const SPD_BACKGROUND: Vec3 = Vec3::new(0.078, 0.361, 0.753);

/// SplitMix64 (Steele, Lea and Flood): tiny, fast, and good enough for
/// terrain noise and colour jitter; the same seed always gives the same
/// stream on every platform.
#[derive(Debug, Clone)]
pub(super) struct Rng(u64);

impl Rng {
    pub(super) fn new(seed: u64) -> Self {
        Self(seed)
    }

    pub(super) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1), from the top 53 bits.
    pub(super) fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    pub(super) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// Standard normal deviate (Box-Muller; one of the pair is dropped to
    /// keep the stream simple).
    pub(super) fn gaussian(&mut self) -> f64 {
        let u1 = 1.0 - self.unit(); // in (0, 1], so ln is finite
        let u2 = self.unit();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// A material with a white specular colour, as NFF's 8-number form has.
pub(super) fn material(
    diffuse: Vec3,
    kd: f32,
    ks: f32,
    shine: f32,
    transmittance: f32,
    ior: f32,
) -> Material {
    Material {
        diffuse,
        kd,
        specular: Vec3::ONE,
        ks,
        shine,
        transmittance,
        ior,
    }
}

/// The SPD camera conventions: 45 degrees, 512 x 512, z up, pinhole.
pub(super) fn spd_view(from: Vec3, at: Vec3) -> Viewpoint {
    Viewpoint {
        from,
        at,
        up: Vec3::Z,
        angle: 45.0,
        hither: 0.01,
        width: 512,
        height: 512,
        aperture: 0.0,
        focal: 1.0,
    }
}

/// Builds a [`Scene`] whose objects use materials in declaration order,
/// each material in one contiguous run: that is the only order a P3F file
/// can express, so the written file parses back to an equal scene.
pub(super) struct SceneBuilder {
    scene: Scene,
}

impl SceneBuilder {
    /// A scene suggesting the BVH (generated scenes are large) and 2 x 2
    /// anti-aliasing, as the course's `balls_medium.p3f` does.
    pub(super) fn new(view: Viewpoint, background: Vec3) -> Self {
        Self {
            scene: Scene {
                view,
                background,
                accel: Some(2),
                spp: Some(2),
                ..Scene::default()
            },
        }
    }

    /// A white point light of intensity 1.
    pub(super) fn light(&mut self, position: Vec3) {
        self.scene.lights.push(LightSpec::Point {
            position,
            color: Some(Vec3::ONE),
        });
    }

    /// Starts a new material for the objects added after it.
    pub(super) fn material(&mut self, material: Material) {
        self.scene.materials.push(material);
    }

    /// Adds an object with the latest material (call [`Self::material`] first).
    pub(super) fn add(&mut self, primitive: Primitive) {
        debug_assert!(!self.scene.materials.is_empty(), "material before objects");
        let material = self.scene.materials.len().saturating_sub(1) as u32;
        self.scene.objects.push(Object {
            primitive,
            material,
        });
    }

    /// Room for `n` more objects, so large scenes grow once.
    pub(super) fn reserve(&mut self, n: usize) {
        self.scene.objects.reserve(n);
    }

    pub(super) fn finish(self) -> Scene {
        self.scene
    }
}

/// Helpers the generator tests share.
#[cfg(test)]
pub(super) mod test_util {
    use crate::scene::{Primitive, Scene};

    /// How many objects of each kind: (spheres, cones, polygons, mesh triangles).
    pub(crate) fn counts(scene: &Scene) -> (usize, usize, usize, usize) {
        let mut c = (0, 0, 0, 0);
        for o in &scene.objects {
            match &o.primitive {
                Primitive::Sphere { .. } => c.0 += 1,
                Primitive::Cone { .. } => c.1 += 1,
                Primitive::Polygon { .. } => c.2 += 1,
                Primitive::Mesh { triangles, .. } => c.3 += triangles.len(),
                _ => {}
            }
        }
        c
    }

    /// Every object's material index is valid and indices never go back.
    pub(crate) fn assert_material_runs(scene: &Scene) {
        let mut last = 0;
        for o in &scene.objects {
            assert!((o.material as usize) < scene.materials.len());
            assert!(o.material >= last, "material order goes back");
            last = o.material;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rng_is_deterministic_and_in_range() {
        let mut a = Rng::new(7);
        let mut b = Rng::new(7);
        for _ in 0..1000 {
            let x = a.unit();
            assert_eq!(x, b.unit());
            assert!((0.0..1.0).contains(&x));
            assert!(a.gaussian().is_finite());
            b.gaussian();
        }
        assert_ne!(Rng::new(1).next_u64(), Rng::new(2).next_u64());
    }

    #[test]
    fn gaussian_has_unit_variance_roughly() {
        let mut r = Rng::new(3);
        let n = 20000;
        let xs: Vec<f64> = (0..n).map(|_| r.gaussian()).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        assert!(
            mean.abs() < 0.05 && (var - 1.0).abs() < 0.05,
            "{mean} {var}"
        );
    }
}
