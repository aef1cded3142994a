//! Counters of what the renderer does. Each worker thread owns a
//! [`Counters`] and they are merged per tile, so counting costs an add on a
//! local struct, never an atomic per ray.

use std::ops::AddAssign;
use std::time::Duration;

/// Work done while tracing, the same for every acceleration structure so
/// they compare on equal terms.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counters {
    /// Rays from the camera, one per sample.
    pub eye_rays: u64,
    /// Rays towards light samples.
    pub shadow_rays: u64,
    /// Mirror rays spawned at specular surfaces.
    pub reflection_rays: u64,
    /// Rays bent into or out of transmitters.
    pub refraction_rays: u64,
    /// Ray-primitive intersection tests.
    pub intersection_tests: u64,
    /// Closest-hit queries that found a surface.
    pub hits: u64,
    /// Acceleration nodes or grid cells visited.
    pub nodes_visited: u64,
    /// Shadow rays found blocked by the shape that last blocked a shadow
    /// ray towards the same light, without a traversal.
    pub shadow_cache_hits: u64,
}

impl Counters {
    /// Rays of every kind.
    pub fn total_rays(&self) -> u64 {
        self.eye_rays + self.shadow_rays + self.reflection_rays + self.refraction_rays
    }
}

impl AddAssign for Counters {
    fn add_assign(&mut self, o: Self) {
        self.eye_rays += o.eye_rays;
        self.shadow_rays += o.shadow_rays;
        self.reflection_rays += o.reflection_rays;
        self.refraction_rays += o.refraction_rays;
        self.intersection_tests += o.intersection_tests;
        self.hits += o.hits;
        self.nodes_visited += o.nodes_visited;
        self.shadow_cache_hits += o.shadow_cache_hits;
    }
}

/// What a scene holds, for the statistics panel and `render`'s summary.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SceneCounts {
    /// Objects as the file declares them, by command kind, sorted by name.
    pub objects_by_kind: Vec<(&'static str, usize)>,
    /// Primitives the renderer intersects (polygons and meshes become triangles).
    pub primitives: usize,
    /// Triangles among the primitives.
    pub triangles: usize,
    /// Lights, point and area.
    pub lights: usize,
}

impl SceneCounts {
    /// Objects declared in the file, of any kind.
    pub fn objects(&self) -> usize {
        self.objects_by_kind.iter().map(|(_, n)| n).sum()
    }
}

/// A snapshot of a render's progress and cost.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RenderStats {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Passes completed; each adds one sample to every pixel.
    pub passes_done: u32,
    /// Passes that make the target sample count.
    pub passes_target: u32,
    /// Rays traced, by kind.
    pub counters: Counters,
    /// Duration of each completed pass.
    pub pass_times: Vec<Duration>,
    /// Rays of all kinds traced in each completed pass.
    pub pass_rays: Vec<u64>,
    /// Time spent rendering so far (passes, including a partial one).
    pub render_time: Duration,
    /// Time spent building the acceleration structure.
    pub build_time: Duration,
    /// How an adaptive render has spent its samples (after the last
    /// completed pass); `None` for uniform sampling.
    pub adaptive: Option<AdaptiveStats>,
    /// Tiles rendered by each thread of the pool, by its index there (one
    /// entry for a render in time slices): that every worker took part.
    pub tiles_by_thread: Vec<u64>,
}

/// Where an adaptive render stands after a pass.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct AdaptiveStats {
    /// Pixels in the image.
    pub pixels: u64,
    /// Pixels that take more samples in the next pass.
    pub active_pixels: u64,
    /// Samples taken, every pixel's added up.
    pub samples: u64,
    /// The most samples one pixel took.
    pub max_spp: u32,
    /// Root mean square of the pixels' estimated errors (standard errors of
    /// their means, in display units 0..1): about the RMS difference to
    /// the converged image. Infinite before two samples.
    pub error: f32,
}

impl AdaptiveStats {
    /// The share of pixels still refining, 0..1.
    pub fn active_share(&self) -> f64 {
        self.active_pixels as f64 / self.pixels.max(1) as f64
    }

    /// Samples per pixel, on average.
    pub fn mean_spp(&self) -> f64 {
        self.samples as f64 / self.pixels.max(1) as f64
    }
}

impl RenderStats {
    /// Counts a tile rendered by the pool's thread `index` (`None`: a
    /// thread outside any pool, counted as the first).
    pub fn count_tile(&mut self, index: Option<usize>) {
        let index = index.unwrap_or(0);
        if self.tiles_by_thread.len() <= index {
            self.tiles_by_thread.resize(index + 1, 0);
        }
        self.tiles_by_thread[index] += 1;
    }

    /// Samples taken, every pixel's added up: an adaptive render's count,
    /// or a sample per pixel per uniform pass. What an adaptive render's
    /// sample budget is matched to.
    pub fn samples_taken(&self) -> u64 {
        match &self.adaptive {
            Some(a) => a.samples,
            None => u64::from(self.passes_done) * u64::from(self.width) * u64::from(self.height),
        }
    }

    /// Rays of all kinds per second of rendering.
    pub fn rays_per_second(&self) -> f64 {
        let secs = self.render_time.as_secs_f64();
        if secs > 0.0 {
            self.counters.total_rays() as f64 / secs
        } else {
            0.0
        }
    }
}
