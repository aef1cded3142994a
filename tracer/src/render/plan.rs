//! One render's fixed plan: the camera, the tiles and the order in which
//! passes visit the pixel strata. Rendering a tile of a pass is a pure
//! function of the plan, so any thread may do it.

use std::sync::Arc;

use glam::{Vec2, Vec3A};

use crate::accel::SceneIndex;
use crate::camera::{Camera, CameraError};
use crate::geometry::Ray;
use crate::sampling::{SampleStream, concentric_disk, jittered, pixel_digits, stratum_order};
use crate::stats::Counters;
use crate::world::World;

use super::adaptive::RoundOrder;
use super::trace::{NoRecord, TraceRecorder};
use super::view::{ViewRecorder, ViewSample};
use super::{RenderSettings, Tile, Tracer};

/// Side of a square tile, in pixels: small enough that cancellation and
/// the first pass's tile-by-tile display are prompt, large enough that the
/// per-tile bookkeeping is negligible.
pub const TILE_SIZE: u32 = 32;

/// What [`RenderPlan::render_samples`] made of a tile's planned samples.
pub(crate) struct PlannedSamples {
    /// The samples' values, pixel after pixel.
    pub values: Vec<Vec3A>,
    /// Each pixel's intersection tests over its samples (row-major): what
    /// its samples cost, for adaptive sampling.
    pub tests: Vec<u64>,
    /// The samples' view samples, when asked for.
    pub views: Option<Vec<ViewSample>>,
}

/// A render's plan, shared by the threads that execute it.
pub struct RenderPlan {
    /// The prepared scene.
    pub world: Arc<World>,
    /// The acceleration structure over its shapes.
    pub index: Arc<SceneIndex>,
    /// The settings the render follows.
    pub settings: RenderSettings,
    /// The camera, with the settings' lens.
    pub camera: Camera,
    /// The image cut into tiles, the unit of work of a pass.
    pub tiles: Vec<Tile>,
    /// Stratum visited by each pass within one round of N x N passes.
    order: Vec<u32>,
    /// With adaptive sampling, the order of a pixel's samples over its
    /// strata.
    adaptive_order: Option<RoundOrder>,
}

impl RenderPlan {
    /// Plans a render: the camera from `settings`, the image cut into tiles.
    pub fn new(
        world: Arc<World>,
        index: Arc<SceneIndex>,
        settings: RenderSettings,
    ) -> Result<Self, CameraError> {
        let camera = settings.render_camera(&world.view)?;
        let spp = settings.samples_per_pixel();
        let n = settings.strata();
        Ok(Self {
            tiles: Tile::grid(settings.width, settings.height, TILE_SIZE),
            order: if spp > 1 { stratum_order(n) } else { vec![0] },
            adaptive_order: settings.adaptive().map(|_| RoundOrder::new(n)),
            world,
            index,
            settings,
            camera,
        })
    }

    /// Passes that reach the target of N x N samples per pixel (or one);
    /// with adaptive sampling, the most passes the render may take.
    pub fn passes_target(&self) -> u32 {
        match self.settings.adaptive() {
            Some(a) => super::adaptive::passes(a),
            None => self.order.len() as u32,
        }
    }

    /// The uniform pass whose random numbers and stratum sample `sample` of
    /// a pixel takes: the sample itself for uniform sampling; for adaptive
    /// sampling, the round's lattice order (so each round of `m * m`
    /// samples takes the very samples of `m * m` uniform passes).
    #[inline]
    fn pass_of(&self, sample: u32, pixel: u32) -> u32 {
        let Some(order) = &self.adaptive_order else {
            return sample;
        };
        let round = order.len();
        let shift = pixel_digits(self.settings.seed, pixel);
        sample / round * round + order.pass(sample % round, shift)
    }

    /// Renders the samples `plan` asks of the pixels of `tile` (row-major:
    /// pixel `i` takes samples `plan[i]`), with their view samples when
    /// `views`: the values pixel after pixel and each pixel's intersection
    /// tests, as [`Film::add_samples`] takes them.
    ///
    /// [`Film::add_samples`]: super::Film::add_samples
    pub(crate) fn render_samples(
        &self,
        tile: &Tile,
        plan: &[std::ops::Range<u32>],
        views: bool,
        counters: &mut Counters,
    ) -> PlannedSamples {
        let tracer = Tracer::new(&self.world, &self.index, &self.settings);
        let total: usize = plan.iter().map(|r| r.len()).sum();
        let mut values = Vec::with_capacity(total);
        let mut tests = Vec::with_capacity(plan.len());
        let mut samples = views.then(|| Vec::with_capacity(total));
        let pixels = (tile.y..tile.y + tile.height)
            .flat_map(|y| (tile.x..tile.x + tile.width).map(move |x| (x, y)));
        for ((x, y), range) in pixels.zip(plan) {
            let tests_before = counters.intersection_tests;
            for sample in range.clone() {
                let value = match &mut samples {
                    Some(samples) => {
                        let before = *counters;
                        let mut recorder = ViewRecorder::default();
                        let value = self.sample(&tracer, x, y, sample, counters, &mut recorder);
                        samples.push(recorder.finish(&self.world, &before, counters));
                        value
                    }
                    None => self.sample(&tracer, x, y, sample, counters, &mut NoRecord),
                };
                values.push(value);
            }
            tests.push(counters.intersection_tests - tests_before);
        }
        PlannedSamples {
            values,
            tests,
            views: samples,
        }
    }

    /// Renders pass `pass` over `tile`: one sample per pixel, row-major.
    /// Passes past the target start a new round of strata with fresh
    /// random numbers.
    ///
    /// A row's eye rays are made first, then traced: made one before each
    /// trace, each ray's square root and divisions waited alone; in a loop
    /// of their own the processor overlaps them across pixels. The rays
    /// and their random numbers are [`RenderPlan::sample`]'s.
    pub fn render_tile(&self, pass: u32, tile: &Tile, counters: &mut Counters) -> Vec<Vec3A> {
        let tracer = Tracer::new(&self.world, &self.index, &self.settings);
        let mut values = Vec::with_capacity(tile.pixel_count());
        let mut row = Vec::with_capacity(tile.width as usize);
        for y in tile.y..tile.y + tile.height {
            row.extend((tile.x..tile.x + tile.width).map(|x| self.eye_ray(x, y, pass)));
            for (ray, mut rng) in row.drain(..) {
                values.push(tracer.trace_eye_recorded(
                    &ray,
                    self.camera.hither(),
                    &mut rng,
                    counters,
                    &mut NoRecord,
                ));
            }
        }
        values
    }

    /// [`RenderPlan::render_tile`] that also measures what each pixel's sample
    /// cost and saw, for the views: the same samples, traced by the same
    /// code, so the image is identical bit for bit.
    pub(crate) fn render_tile_with_views(
        &self,
        pass: u32,
        tile: &Tile,
        counters: &mut Counters,
    ) -> (Vec<Vec3A>, Vec<ViewSample>) {
        let tracer = Tracer::new(&self.world, &self.index, &self.settings);
        let mut values = Vec::with_capacity(tile.pixel_count());
        let mut samples = Vec::with_capacity(tile.pixel_count());
        for y in tile.y..tile.y + tile.height {
            for x in tile.x..tile.x + tile.width {
                let before = *counters;
                let mut recorder = ViewRecorder::default();
                values.push(self.sample(&tracer, x, y, pass, counters, &mut recorder));
                samples.push(recorder.finish(&self.world, &before, counters));
            }
        }
        (values, samples)
    }

    /// Traces sample `pass` of pixel `(x, y)` (its `pass`-th sample, from
    /// 0) and tells `recorder` every ray: the one place the render, the
    /// views and the inspector draw a pixel sample's random numbers, so
    /// they all trace the same rays.
    #[inline(always)]
    pub fn sample<R: TraceRecorder>(
        &self,
        tracer: &Tracer,
        x: u32,
        y: u32,
        pass: u32,
        counters: &mut Counters,
        recorder: &mut R,
    ) -> Vec3A {
        let (ray, mut rng) = self.eye_ray(x, y, pass);
        tracer.trace_eye_recorded(&ray, self.camera.hither(), &mut rng, counters, recorder)
    }

    /// The eye ray of sample `pass` of pixel `(x, y)`, and the pixel
    /// sample's random numbers past those the camera drew, for the trace.
    #[inline(always)]
    fn eye_ray(&self, x: u32, y: u32, sample: u32) -> (Ray, SampleStream) {
        let pixel = y * self.settings.width + x;
        let pass = self.pass_of(sample, pixel);
        let stratum = self.order[pass as usize % self.order.len()];
        let n = self.settings.strata();
        let aa = self.settings.antialiasing;
        let mut rng = SampleStream::new(self.settings.seed, pixel, pass);
        // Adaptive samples draw their lens and light points in the pixel's
        // own order, stratified in every prefix where the pixel may stop.
        let ranked = self.adaptive_order.is_some();
        if ranked {
            rng = rng.ranked(sample);
        }
        let offset = if aa {
            jittered(stratum, n, rng.next_2d())
        } else {
            Vec2::splat(0.5)
        };
        // Without anti-aliasing the lens alone is stratified; with it,
        // pixel strata already spread the samples, and a lens stratum
        // tied to the pixel stratum would correlate the two: uniform
        // sampling's lens points are then independent, adaptive's follow
        // their own scrambled sequence.
        let lens_point = match (self.camera.has_lens(), aa) {
            (false, _) => Vec2::ZERO,
            (true, false) => concentric_disk(jittered(stratum, n, rng.next_2d())),
            (true, true) if ranked => concentric_disk(rng.next_2d_across_samples(n)),
            (true, true) => concentric_disk(rng.next_2d()),
        };
        let ray = self
            .camera
            .ray(x as f32 + offset.x, y as f32 + offset.y, lens_point);
        (ray, rng)
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::accel::AccelKind;
    use crate::camera::CameraPose;
    use crate::render::LensOverride;
    use crate::scene::{Limits, parse_scene};

    fn scene(from: &str) -> String {
        format!(
            "v from {from} at 0 0 0.5 up 0 0 1 angle 45 hither 0.01 resolution 24 18\n\
             l 3 -3 5\nf 0.8 0.8 0.8 1 1 1 1 0.2 20 0 1\n\
             p 4 -4 -4 0 4 -4 0 4 4 0 -4 4 0\nf 0.9 0.2 0.1 0.7 1 1 1 0.3 30 0 1\n\
             s -1 0 0.7 0.7\ns 1 -0.5 0.6 0.6\n"
        )
    }

    /// The frame of scene `text` on a BVH, with `settings` over the
    /// scene's own.
    fn frame_of(text: &str, settings: impl FnOnce(RenderSettings) -> RenderSettings) -> RenderPlan {
        let scene = parse_scene(text, None, &Limits::default()).unwrap();
        let world = Arc::new(World::build(&scene));
        let index = Arc::new(crate::accel::SceneIndex::build(
            &world.shapes,
            AccelKind::Bvh,
            2.0,
        ));
        let settings = settings(RenderSettings::from_scene(&scene));
        RenderPlan::new(world, index, settings).unwrap()
    }

    fn film(text: &str, camera: Option<CameraPose>) -> Vec<Vec3A> {
        let frame = frame_of(text, |s| RenderSettings { camera, ..s });
        let mut counters = Counters::default();
        frame
            .tiles
            .iter()
            .flat_map(|tile| frame.render_tile(0, tile, &mut counters))
            .collect()
    }

    /// A moved camera renders what a scene file standing there renders,
    /// bit for bit: the window's orbit moves the image, not only its
    /// overlays.
    #[test]
    fn the_settings_camera_is_the_one_that_renders() {
        let moved = CameraPose {
            from: Vec3::new(3.0, -4.0, 2.5),
            at: Vec3::new(0.0, 0.0, 0.5),
            up: Vec3::Z,
        };
        let from_file = film(&scene("3 -4 2.5"), None);
        let posed = film(&scene("0 -5 2"), Some(moved));
        assert_eq!(posed, from_file);
        assert_ne!(film(&scene("0 -5 2"), None), from_file);
    }

    /// A tile rendered with its rows' eye rays made first gives the very
    /// values and counts of tracing each pixel's sample as it is made, in
    /// every mode that draws random numbers (jitter, lens, soft shadows).
    #[test]
    fn a_tile_is_its_pixels_samples() {
        let frame = frame_of(&scene("3 -4 2.5"), |s| RenderSettings {
            antialiasing: true,
            samples: 2,
            depth_of_field: true,
            lens_override: LensOverride {
                aperture: Some(4.0),
                ..Default::default()
            },
            soft_shadows: true,
            light_size: 0.5,
            ..s
        });
        for pass in 0..frame.passes_target() {
            for tile in &frame.tiles {
                // A tile's own tracer, as `render_tile` makes: the same
                // shadow cache, so the same tests are counted.
                let tracer = Tracer::new(&frame.world, &frame.index, &frame.settings);
                let (mut by_tile, mut by_pixel) = (Counters::default(), Counters::default());
                let values = frame.render_tile(pass, tile, &mut by_tile);
                let mut one_by_one = Vec::new();
                for y in tile.y..tile.y + tile.height {
                    for x in tile.x..tile.x + tile.width {
                        let value = frame.sample(&tracer, x, y, pass, &mut by_pixel, &mut NoRecord);
                        one_by_one.push(value);
                    }
                }
                assert_eq!(values, one_by_one, "pass {pass}, {tile:?}");
                assert_eq!(by_tile, by_pixel);
            }
        }
    }
}
