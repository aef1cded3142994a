//! Render settings: plain, documented, comparable values. Everything here
//! changes the image, so a change restarts the render; display-only choices
//! (the output [`Encoding`], zoom) live apart.

use glam::Vec3A;

use crate::accel::AccelKind;
use crate::camera::{Camera, CameraError, CameraPose};
use crate::scene::{DEFAULT_NOISE_THRESHOLD, Lens, NOISE_THRESHOLD, Scene, Viewpoint};
pub use crate::scene::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES};

/// What to render and how.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default)
)]
pub struct RenderSettings {
    /// Image width in pixels, 1..=[`MAX_IMAGE_SIDE`].
    pub width: u32,
    /// Image height in pixels, 1..=[`MAX_IMAGE_SIDE`].
    pub height: u32,
    /// Secondary generations: depth 4 is an eye ray plus up to four bounces,
    /// as in the course and the SPD's "maximum tree depth 5".
    pub max_depth: u32,
    /// Ambient light intensity (white), times each surface's diffuse colour
    /// and Kd. Default 0.1: shadows stay readable without flattening the
    /// image; 0 gives the SPD's pure Whitted look.
    pub ambient: f32,
    /// Jittered stratified anti-aliasing with `samples` x `samples` samples.
    pub antialiasing: bool,
    /// N: the stratification of a pixel (N x N samples), of the lens and of
    /// soft shadows. The course's N.
    pub samples: u32,
    /// Lights have an area: point lights a square of `light_size`, `al`
    /// lights their own rectangle.
    pub soft_shadows: bool,
    /// Shadow rays: off, every light reaches every point that faces it,
    /// whatever lies between (local shading only, the first step of the
    /// course's Whitted ray tracing before shadows); no shadow ray is cast
    /// or counted, so what shadows cost and what they add can be measured.
    pub shadows: bool,
    /// Side of the square a point light becomes with soft shadows, in scene
    /// units.
    pub light_size: f32,
    /// Thin-lens depth of field, through [`RenderSettings::lens`].
    pub depth_of_field: bool,
    /// The user's lens in place of the scene's. The scene's viewpoint owns
    /// the lens, so an edit of it reaches every render without a copy; the
    /// settings only say what the user chose instead (a slider, a flag, a
    /// study's level).
    pub lens_override: LensOverride,
    /// The acceleration structure: none, grid or BVH.
    pub accel: AccelKind,
    /// The grid's cell multiplier m (cells per axis = trunc(m * dim * s) + 1).
    pub grid_multiplier: f32,
    /// Seed of every random number (jitter, lens, light samples).
    pub seed: u64,
    /// How the samples of anti-aliasing (or depth of field) are spent:
    /// N x N in every pixel, or adaptively where the image is still noisy.
    pub sampling: Sampling,
    /// Keep adding fresh samples after the N x N target is reached
    /// (uniform sampling; an adaptive render ends when it converges).
    pub keep_refining: bool,
    /// Where the camera is when the user has moved it; `None` keeps the
    /// scene's own view.
    pub camera: Option<CameraPose>,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 512,
            height: 512,
            max_depth: 4,
            ambient: 0.1,
            antialiasing: false,
            samples: 4,
            soft_shadows: false,
            shadows: true,
            light_size: 0.3,
            depth_of_field: false,
            lens_override: LensOverride::default(),
            accel: AccelKind::Bvh,
            grid_multiplier: 2.0,
            seed: 0,
            sampling: Sampling::Uniform,
            keep_refining: false,
            camera: None,
        }
    }
}

/// The parts of the lens the user chose in place of the scene's; `None`
/// keeps the scene's part.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default)
)]
pub struct LensOverride {
    /// Lens diameter in pixels.
    pub aperture: Option<f32>,
    /// Focal distance as a multiple of the view-plane distance.
    pub focal: Option<f32>,
}

impl LensOverride {
    /// The whole of `lens` in place of the scene's.
    pub fn all(lens: Lens) -> Self {
        Self {
            aperture: Some(lens.aperture),
            focal: Some(lens.focal),
        }
    }
}

/// How a render that takes several samples per pixel spends them.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Sampling {
    /// Every pixel gets the same N x N jittered samples.
    #[default]
    Uniform,
    /// Pixels get samples until their estimated error falls under a
    /// threshold: flat sky stops early, edges, penumbrae and lens blur
    /// keep refining (Cycles' adaptive sampling).
    Adaptive(AdaptiveSampling),
}

/// The knobs of [`Sampling::Adaptive`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default)
)]
pub struct AdaptiveSampling {
    /// A pixel at `min_spp` samples whose samples cost the film's average
    /// stops once the estimated error of its mean (pooled with its
    /// neighbours') is below this, in display units (the linear value
    /// clamped to 0..1, as the image is written: 0.01 is 2.55 levels of
    /// 255); with more or costlier samples, below this times its samples
    /// over `min_spp` times their relative cost
    /// (`adaptive::threshold_at`). 0 never stops a
    /// pixel before `max_spp`.
    pub noise_threshold: f32,
    /// Samples every pixel takes before its error is trusted.
    pub min_spp: u32,
    /// Samples no pixel goes beyond. Its square root (rounded down) is the
    /// side of the strata the samples fill, for the pixel, the lens and
    /// soft shadows alike.
    pub max_spp: u32,
    /// Where the render stops early, whatever the threshold: to compare
    /// it with another render at equal samples or equal time.
    pub budget: Option<Budget>,
}

/// An adaptive render's budget ([`AdaptiveSampling::budget`]). Its first
/// pass (a sample in every pixel) always runs, so the image has no hole.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Budget {
    /// At most this many samples in all: the pass that would go over
    /// refines only the pixels with the largest error estimates that fit,
    /// and is the last. The image stays a function of the settings.
    Samples(u64),
    /// No tile starts once the render has taken this long, and the pass
    /// under way is the last. The image depends on the machine's speed.
    Time(std::time::Duration),
}

impl Default for AdaptiveSampling {
    fn default() -> Self {
        Self::for_samples(4, DEFAULT_NOISE_THRESHOLD)
    }
}

impl AdaptiveSampling {
    /// Adaptive sampling in place of uniform N x N: at most (2N)^2 samples,
    /// so a small threshold can reach any error N x N reaches, and at least
    /// 4 (or N^2 / 4 when larger): two halves of two stratified samples
    /// for a first estimate. A flat pixel costs a quarter of uniform
    /// 4 x 4's; at 8, adaptive could not take less than half its time.
    pub fn for_samples(n: u32, noise_threshold: f32) -> Self {
        let n = n.clamp(1, MAX_SAMPLES);
        let max_spp = (2 * n).min(MAX_SAMPLES).pow(2);
        Self {
            noise_threshold,
            min_spp: (n * n / 4).max(4).min(max_spp),
            max_spp,
            budget: None,
        }
    }
}

impl RenderSettings {
    /// The settings a scene file asks for: its resolution, `spp` (and
    /// `adaptive`), `accel` and depth of field when its lens is open;
    /// everything else at its default.
    pub fn from_scene(scene: &Scene) -> Self {
        let mut settings = Self::default();
        settings.adopt_scene(scene);
        settings
    }

    /// Takes what `scene` asks for (its resolution, `spp`, `accel`, depth
    /// of field when its lens is open and its lens, the user's override
    /// dropped, and a light size that suits its scale) and keeps every
    /// other field: how a viewer keeps its user's choices when another
    /// scene opens. The light size is a tenth of the camera's distance to
    /// `at`, so the penumbra scales with the scene. Its `adaptive`
    /// threshold turns anti-aliasing on and samples adaptively with N's
    /// bounds; without one it samples uniformly.
    pub fn adopt_scene(&mut self, scene: &Scene) {
        let view = &scene.view;
        let spp = scene.spp.unwrap_or(0);
        self.width = view.width;
        self.height = view.height;
        self.antialiasing = spp > 0 || scene.adaptive.is_some();
        self.samples = if spp > 0 { spp } else { 4 };
        self.sampling = match scene.adaptive {
            Some(threshold) => {
                Sampling::Adaptive(AdaptiveSampling::for_samples(self.samples, threshold))
            }
            None => Sampling::Uniform,
        };
        self.follow_scene_lens(view);
        self.accel = match scene.accel {
            Some(0) => AccelKind::None,
            Some(1) => AccelKind::Grid,
            _ => AccelKind::Bvh,
        };
        // Finite even for absurd (huge but finite) camera coordinates.
        self.light_size = (0.1 * (view.at - view.from).length()).min(f32::MAX);
    }

    /// Sets N; adaptive sampling, when chosen, takes N's bounds
    /// ([`AdaptiveSampling::for_samples`]) and keeps its threshold and
    /// budget, so that it stays adaptive sampling "in place of N x N".
    pub fn set_samples(&mut self, n: u32) {
        self.samples = n;
        if let Sampling::Adaptive(adaptive) = &mut self.sampling {
            *adaptive = AdaptiveSampling {
                budget: adaptive.budget,
                ..AdaptiveSampling::for_samples(n, adaptive.noise_threshold)
            };
        }
    }

    /// Samples adaptively, with the knobs in force (or, when sampling
    /// uniformly, adaptive sampling in place of N x N: N's bounds, the
    /// default threshold) changed by `edit`: what a checkbox,
    /// `--sampling adaptive` and a threshold study all start from. Whether
    /// anti-aliasing turns on is the caller's: adaptive sampling spreads
    /// the samples anti-aliasing or depth of field takes.
    pub fn sample_adaptively(&mut self, edit: impl FnOnce(&mut AdaptiveSampling)) {
        let mut knobs = match self.sampling {
            Sampling::Adaptive(knobs) => knobs,
            Sampling::Uniform => {
                AdaptiveSampling::for_samples(self.samples, DEFAULT_NOISE_THRESHOLD)
            }
        };
        edit(&mut knobs);
        self.sampling = Sampling::Adaptive(knobs);
    }

    /// Renders through `view`'s own lens again, with depth of field when
    /// it is open: what opening a scene does, and an edit of its camera,
    /// as a scene file stating the edited lens would.
    pub fn follow_scene_lens(&mut self, view: &Viewpoint) {
        self.depth_of_field = view.aperture > 0.0;
        self.lens_override = LensOverride::default();
    }

    /// The lens chosen for renders of `view`, whether depth of field is on
    /// or not (what the sliders show): the view's, each part the user
    /// overrode replaced.
    pub fn chosen_lens(&self, view: &Viewpoint) -> Lens {
        let scene = view.lens();
        Lens {
            aperture: self.lens_override.aperture.unwrap_or(scene.aperture),
            focal: self.lens_override.focal.unwrap_or(scene.focal),
        }
    }

    /// The lens a render of `view` sees through: the chosen lens with
    /// depth of field on, none (a pinhole) without.
    pub fn lens(&self, view: &Viewpoint) -> Option<Lens> {
        self.depth_of_field.then(|| self.chosen_lens(view))
    }

    /// The one camera a render of `view` with these settings uses, so the
    /// image, its overlays, picking and the figures all agree: the view,
    /// or the settings' pose when the user moved the camera; the view's
    /// lens, or the settings' override of it, only with depth of field on
    /// ([`RenderSettings::lens`]).
    pub fn render_camera(&self, view: &Viewpoint) -> Result<Camera, CameraError> {
        Camera::posed(
            view,
            self.camera.as_ref(),
            self.lens(view),
            self.width,
            self.height,
        )
    }

    /// Samples per pixel to reach the target: N x N when anti-aliasing or
    /// depth of field spread samples over the pixel or the lens, else one;
    /// adaptive sampling's maximum (the most a pixel may take).
    pub fn samples_per_pixel(&self) -> u32 {
        if let Some(adaptive) = self.adaptive() {
            adaptive.max_spp
        } else if self.antialiasing || self.depth_of_field {
            self.samples.max(1).pow(2)
        } else {
            1
        }
    }

    /// The adaptive sampling in force: chosen, and with anti-aliasing or
    /// depth of field asking for several samples.
    pub fn adaptive(&self) -> Option<&AdaptiveSampling> {
        match &self.sampling {
            Sampling::Adaptive(a) if self.antialiasing || self.depth_of_field => Some(a),
            _ => None,
        }
    }

    /// The side of the strata a pixel's samples fill (pixel, lens and
    /// soft-shadow patterns): N, or the square root of adaptive sampling's
    /// maximum, so that a pixel taking every sample fills them as N x N
    /// uniform sampling with that N does.
    pub fn strata(&self) -> u32 {
        match self.adaptive() {
            Some(a) => (a.max_spp.max(1) as f32).sqrt() as u32,
            None => self.samples.max(1),
        }
    }
}

/// Deepest recursion allowed.
pub const MAX_DEPTH: u32 = 64;
/// Largest grid multiplier (cells grow with its cube).
pub const MAX_GRID_MULTIPLIER: f32 = 32.0;

/// A setting outside what the renderer accepts.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{name} = {value} is out of range: {expected}")]
pub struct SettingsError {
    /// The setting, e.g. "samples".
    pub name: &'static str,
    /// The value given.
    pub value: String,
    /// The valid range.
    pub expected: String,
}

impl RenderSettings {
    /// Checks every value, so that a bad command line or slider can never
    /// allocate absurdly or produce NaN images.
    pub fn validate(&self) -> Result<(), SettingsError> {
        self.validate_image()?;
        if let Sampling::Adaptive(a) = &self.sampling {
            a.validate()?;
        }
        self.validate_numbers()
    }

    /// The image's size and samples a pixel.
    fn validate_image(&self) -> Result<(), SettingsError> {
        let side = 1..=MAX_IMAGE_SIDE;
        let sides = format!("1 to {MAX_IMAGE_SIDE}");
        require(side.contains(&self.width), "width", self.width, &sides)?;
        require(side.contains(&self.height), "height", self.height, &sides)?;
        let pixels = self.width as u64 * self.height as u64;
        require(
            pixels <= MAX_IMAGE_PIXELS,
            "width x height",
            pixels,
            format!("at most {MAX_IMAGE_PIXELS} pixels"),
        )?;
        require(
            (1..=MAX_SAMPLES).contains(&self.samples),
            "samples",
            self.samples,
            format!("1 to {MAX_SAMPLES}"),
        )
    }

    /// The depth, and the shading, lens and grid numbers: finite, in
    /// their ranges.
    fn validate_numbers(&self) -> Result<(), SettingsError> {
        require(
            self.max_depth <= MAX_DEPTH,
            "depth",
            self.max_depth,
            format!("0 to {MAX_DEPTH}"),
        )?;
        let aperture = self.lens_override.aperture.unwrap_or(0.0);
        let checks = [
            ("ambient", self.ambient, 0.0, f32::MAX),
            ("light size", self.light_size, 0.0, f32::MAX),
            ("aperture", aperture, 0.0, f32::MAX),
            (
                "grid multiplier",
                self.grid_multiplier,
                f32::MIN_POSITIVE,
                MAX_GRID_MULTIPLIER,
            ),
        ];
        for (name, value, min, max) in checks {
            let expected = format!("a number from {min} to {max}");
            require(value >= min && value <= max, name, value, expected)?;
        }
        match self.lens_override.focal {
            Some(focal) => require(
                focal > 0.0 && focal.is_finite(),
                "focal",
                focal,
                "a number > 0",
            ),
            None => Ok(()),
        }
    }
}

impl AdaptiveSampling {
    /// The sample bounds and the threshold.
    fn validate(&self) -> Result<(), SettingsError> {
        let most = MAX_SAMPLES * MAX_SAMPLES;
        require(
            (1..=most).contains(&self.max_spp),
            "max spp",
            self.max_spp,
            format!("1 to {most}"),
        )?;
        require(
            (1..=self.max_spp).contains(&self.min_spp),
            "min spp",
            self.min_spp,
            format!("1 to the max spp, {}", self.max_spp),
        )?;
        let threshold = self.noise_threshold;
        let (low, high) = NOISE_THRESHOLD.into_inner();
        require(
            NOISE_THRESHOLD.contains(&threshold),
            "noise threshold",
            threshold,
            format!("a number from {low} to {high}"),
        )
    }
}

/// `Ok` when `ok`, else the error naming setting `name`, its `value` and
/// what was `expected`.
fn require(
    ok: bool,
    name: &'static str,
    value: impl ToString,
    expected: impl Into<String>,
) -> Result<(), SettingsError> {
    if ok {
        Ok(())
    } else {
        Err(SettingsError {
            name,
            value: value.to_string(),
            expected: expected.into(),
        })
    }
}

/// How linear radiance becomes 8-bit values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Encoding {
    /// Clamp and write directly, as the course and the SPD scenes expect.
    #[default]
    Linear,
    /// The sRGB transfer curve.
    Srgb,
}

impl Encoding {
    /// The 8-bit value of a linear component.
    #[inline]
    pub fn encode(self, v: f32) -> u8 {
        let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let v = match self {
            Encoding::Linear => v,
            Encoding::Srgb if v <= 0.003_130_8 => 12.92 * v,
            Encoding::Srgb => 1.055 * v.powf(1.0 / 2.4) - 0.055,
        };
        (v * 255.0 + 0.5) as u8
    }

    /// The 8-bit values of a linear colour, the same as [`Encoding::encode`]
    /// on each component: the linear encoding takes all three at once
    /// (turning a film into bytes is a visible part of a whole `workbench
    /// render`).
    #[inline]
    pub(crate) fn encode_rgb(self, c: Vec3A) -> [u8; 3] {
        match self {
            Encoding::Linear => {
                // `max` takes its second operand when the first is NaN,
                // which is the scalar path's NaN -> 0.
                let v = c.max(Vec3A::ZERO).min(Vec3A::ONE) * 255.0 + Vec3A::splat(0.5);
                // In [0.5, 255.5]: truncated, each fits a byte.
                v.as_uvec3().to_array().map(|n| n as u8)
            }
            Encoding::Srgb => [self.encode(c.x), self.encode(c.y), self.encode(c.z)],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodings() {
        assert_eq!(Encoding::Linear.encode(0.5), 128);
        assert_eq!(Encoding::Linear.encode(2.0), 255);
        assert_eq!(Encoding::Linear.encode(-1.0), 0);
        assert_eq!(Encoding::Linear.encode(f32::NAN), 0);
        assert_eq!(Encoding::Srgb.encode(0.5), 188);
        assert_eq!(Encoding::Srgb.encode(0.0), 0);
        assert_eq!(Encoding::Srgb.encode(1.0), 255);
    }

    proptest::proptest! {
        /// Both encodings of a colour at once give each component's byte,
        /// whatever the value: NaN, infinities, negatives, the edges of
        /// every byte's interval (`bits` covers every float).
        #[test]
        fn encoding_a_colour_is_encoding_each_component(
            bits in proptest::array::uniform3(proptest::num::u32::ANY),
            byte in 0u32..256,
        ) {
            let edge = byte as f32 / 255.0 - 0.5 / 255.0;
            for c in [
                Vec3A::from_array(bits.map(f32::from_bits)),
                Vec3A::new(edge, f32::from_bits(edge.to_bits() + 1), byte as f32 / 255.0),
                Vec3A::new(f32::NAN, f32::INFINITY, f32::NEG_INFINITY),
            ] {
                for e in [Encoding::Linear, Encoding::Srgb] {
                    proptest::prop_assert_eq!(
                        e.encode_rgb(c),
                        [e.encode(c.x), e.encode(c.y), e.encode(c.z)],
                        "{:?} {:?}", e, c
                    );
                }
            }
        }
    }

    #[test]
    fn validation_rejects_out_of_range_values() {
        assert!(RenderSettings::default().validate().is_ok());
        let bad = [
            RenderSettings {
                width: 0,
                ..Default::default()
            },
            RenderSettings {
                height: MAX_IMAGE_SIDE + 1,
                ..Default::default()
            },
            RenderSettings {
                width: 16384,
                height: 16384,
                ..Default::default()
            },
            RenderSettings {
                samples: 0,
                ..Default::default()
            },
            RenderSettings {
                samples: MAX_SAMPLES + 1,
                ..Default::default()
            },
            RenderSettings {
                max_depth: 1000,
                ..Default::default()
            },
            RenderSettings {
                ambient: f32::NAN,
                ..Default::default()
            },
            RenderSettings {
                light_size: -1.0,
                ..Default::default()
            },
            RenderSettings {
                lens_override: LensOverride {
                    aperture: Some(f32::INFINITY),
                    ..Default::default()
                },
                ..Default::default()
            },
            RenderSettings {
                lens_override: LensOverride {
                    focal: Some(0.0),
                    ..Default::default()
                },
                ..Default::default()
            },
            RenderSettings {
                grid_multiplier: 0.0,
                ..Default::default()
            },
            RenderSettings {
                sampling: Sampling::Adaptive(AdaptiveSampling {
                    min_spp: 65,
                    max_spp: 64,
                    ..Default::default()
                }),
                ..Default::default()
            },
            RenderSettings {
                sampling: Sampling::Adaptive(AdaptiveSampling {
                    max_spp: 0,
                    min_spp: 0,
                    ..Default::default()
                }),
                ..Default::default()
            },
            RenderSettings {
                sampling: Sampling::Adaptive(AdaptiveSampling {
                    noise_threshold: f32::NAN,
                    ..Default::default()
                }),
                ..Default::default()
            },
        ];
        for s in bad {
            assert!(s.validate().is_err(), "{s:?}");
        }
    }

    #[test]
    fn samples_per_pixel_follow_aa_and_dof() {
        let mut s = RenderSettings {
            samples: 3,
            ..RenderSettings::default()
        };
        assert_eq!(s.samples_per_pixel(), 1);
        s.depth_of_field = true;
        assert_eq!(s.samples_per_pixel(), 9);
        s.depth_of_field = false;
        s.antialiasing = true;
        assert_eq!(s.samples_per_pixel(), 9);
        assert_eq!(s.strata(), 3);
        s.sampling = Sampling::Adaptive(AdaptiveSampling::for_samples(3, 0.01));
        assert_eq!((s.samples_per_pixel(), s.strata()), (36, 6));
        s.antialiasing = false;
        assert_eq!(s.samples_per_pixel(), 1, "adaptive spends AA's samples");
    }

    #[test]
    fn adaptive_bounds_follow_n_and_keep_the_threshold_and_budget() {
        let budget = Some(Budget::Samples(1000));
        let mut s = RenderSettings {
            sampling: Sampling::Adaptive(AdaptiveSampling {
                budget,
                ..AdaptiveSampling::for_samples(4, 0.003)
            }),
            ..RenderSettings::default()
        };
        s.set_samples(12);
        let expected = AdaptiveSampling {
            budget,
            ..AdaptiveSampling::for_samples(12, 0.003)
        };
        assert_eq!(s.sampling, Sampling::Adaptive(expected));
        assert_eq!((expected.min_spp, expected.max_spp), (36, 576));

        let mut uniform = RenderSettings::default();
        uniform.set_samples(12);
        assert_eq!((uniform.samples, uniform.sampling), (12, Sampling::Uniform));
    }

    #[test]
    fn a_scene_file_chooses_adaptive_or_uniform_sampling() {
        let scene = |text: &str| Scene {
            spp: text.contains("spp 12").then_some(12),
            adaptive: text.contains("adaptive").then_some(0.007),
            ..Scene::default()
        };
        let mut s = RenderSettings::from_scene(&scene("spp 12 adaptive"));
        assert!(s.antialiasing);
        let showcase = AdaptiveSampling::for_samples(12, 0.007);
        assert_eq!(s.sampling, Sampling::Adaptive(showcase));

        s.adopt_scene(&scene("spp 12"));
        assert_eq!((s.samples, s.sampling), (12, Sampling::Uniform));

        // `adaptive` alone turns anti-aliasing on, with N = 4's bounds.
        s.adopt_scene(&scene("adaptive"));
        assert!(s.antialiasing);
        let four = AdaptiveSampling::for_samples(4, 0.007);
        assert_eq!((s.samples, s.sampling), (4, Sampling::Adaptive(four)));
    }
}
