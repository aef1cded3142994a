//! One render's fixed plan: the camera, the tiles and the order in which
//! passes visit the pixel strata. Rendering a tile of a pass is a pure
//! function of the plan, so any thread may do it.

use std::sync::Arc;

use glam::{Vec2, Vec3A};

use crate::accel::SceneIndex;
use crate::camera::{Camera, CameraError};
use crate::sampling::{SampleStream, concentric_disk, jittered, stratum_order};
use crate::stats::Counters;
use crate::world::World;

use super::trace::{NoRecord, TraceRecorder};
use super::view::{ViewRecorder, ViewSample};
use super::{RenderSettings, Tile, Tracer};

/// Side of a square tile, in pixels: small enough that cancellation and
/// the first pass's tile-by-tile display are prompt, large enough that the
/// per-tile bookkeeping is negligible.
pub const TILE_SIZE: u32 = 32;

/// A render's plan, shared by the threads that execute it.
pub struct Frame {
    pub world: Arc<World>,
    pub index: Arc<SceneIndex>,
    pub settings: RenderSettings,
    pub camera: Camera,
    pub tiles: Vec<Tile>,
    /// Stratum visited by each pass within one round of N x N passes.
    order: Vec<u32>,
}

impl Frame {
    pub fn new(
        world: Arc<World>,
        index: Arc<SceneIndex>,
        settings: RenderSettings,
    ) -> Result<Self, CameraError> {
        let (aperture, focal) = if settings.depth_of_field {
            (settings.aperture, settings.focal)
        } else {
            (0.0, 1.0)
        };
        let camera = Camera::new(
            &world.view,
            settings.width,
            settings.height,
            aperture,
            focal,
        )?;
        let spp = settings.samples_per_pixel();
        let n = (spp as f32).sqrt() as u32;
        Ok(Self {
            tiles: Tile::grid(settings.width, settings.height, TILE_SIZE),
            order: if spp > 1 { stratum_order(n) } else { vec![0] },
            world,
            index,
            settings,
            camera,
        })
    }

    /// The camera `settings` give for `world`: the scene's view, or the
    /// settings' pose when the user moved the camera; the lens only with
    /// depth of field on.
    pub fn camera(world: &World, settings: &RenderSettings) -> Result<Camera, CameraError> {
        let (aperture, focal) = if settings.depth_of_field {
            (settings.aperture, settings.focal)
        } else {
            (0.0, 1.0)
        };
        let mut view = world.view.clone();
        if let Some(pose) = &settings.camera {
            pose.apply(&mut view);
        }
        Camera::new(&view, settings.width, settings.height, aperture, focal)
    }

    /// Passes that reach the target of N x N samples per pixel (or one).
    pub fn passes_target(&self) -> u32 {
        self.order.len() as u32
    }

    /// Renders pass `pass` over `tile`: one sample per pixel, row-major.
    /// Passes past the target start a new round of strata with fresh
    /// random numbers.
    pub fn render_tile(&self, pass: u32, tile: &Tile, counters: &mut Counters) -> Vec<Vec3A> {
        let tracer = Tracer::new(&self.world, &self.index, &self.settings);
        let mut values = Vec::with_capacity(tile.pixel_count());
        for y in tile.y..tile.y + tile.height {
            for x in tile.x..tile.x + tile.width {
                values.push(self.sample(&tracer, x, y, pass, counters, &mut NoRecord));
            }
        }
        values
    }

    /// [`Frame::render_tile`] that also measures what each pixel's sample
    /// cost and saw, for the views: the same samples, traced by the same
    /// code, so the image is identical bit for bit.
    pub fn render_tile_with_views(
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

    /// Traces sample `pass` of pixel `(x, y)` and tells `recorder` every
    /// ray: the one place the render, the views and the inspector draw a
    /// pixel sample's random numbers, so they all trace the same rays.
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
        let stratum = self.order[(pass % self.passes_target()) as usize];
        let n = self.settings.samples.max(1);
        let aa = self.settings.antialiasing;
        let pixel = y * self.settings.width + x;
        let mut rng = SampleStream::new(self.settings.seed, pixel, pass);
        let offset = if aa {
            jittered(stratum, n, rng.next_2d())
        } else {
            Vec2::splat(0.5)
        };
        // Without anti-aliasing the lens alone is stratified; with it,
        // pixel strata already spread the samples, and a lens stratum
        // tied to the pixel stratum would correlate the two.
        let lens_point = match (self.camera.has_lens(), aa) {
            (false, _) => Vec2::ZERO,
            (true, false) => concentric_disk(jittered(stratum, n, rng.next_2d())),
            (true, true) => concentric_disk(rng.next_2d()),
        };
        let ray = self
            .camera
            .ray(x as f32 + offset.x, y as f32 + offset.y, lens_point);
        tracer.trace_eye_recorded(&ray, self.camera.hither(), &mut rng, counters, recorder)
    }
}
