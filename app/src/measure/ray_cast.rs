//! `bench --rays`: the acceleration structure alone, without shading, on
//! the ray set of [`tracer::ray_set`] (the one Embree's figures are measured
//! on), each kind timed on its own: the median of `runs` casts after a
//! warm-up, on a pool of exactly the threads asked for.

use web_time::Instant;

use anyhow::{Context, Result};
use rayon::prelude::*;
use serde_json::{Value, json};
use tracer::accel::{AccelKind, SceneIndex};
use tracer::camera::Camera;
use tracer::ray_set::{RaySet, cast_eye, cast_shadow};
use tracer::stats::Counters;
use tracer::world::World;

/// Shadow rays a task casts: the ray list's chunks, as Embree's benchmark
/// hands them to its threads.
const SHADOW_CHUNK: usize = 4096;

/// What to measure.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RayBenchOptions {
    pub(crate) accel: AccelKind,
    pub(crate) grid_multiplier: f32,
    /// Timed casts of each kind (at least one), after one warm-up.
    pub(crate) runs: usize,
    /// Worker threads; `None` uses every core.
    pub(crate) threads: Option<usize>,
}

/// One kind of ray, cast `runs` times.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct KindTiming {
    pub(crate) rays: u64,
    /// Eye rays that hit a surface, shadow rays that are blocked.
    pub(crate) hits: u64,
    /// Median, fastest and slowest cast of all the rays, in seconds.
    pub(crate) seconds: f64,
    pub(crate) min_seconds: f64,
    pub(crate) max_seconds: f64,
    /// Structure nodes (grid cells) visited and primitives tested per ray.
    pub(crate) nodes_per_ray: f64,
    pub(crate) tests_per_ray: f64,
}

impl KindTiming {
    pub(crate) fn rays_per_second(&self) -> f64 {
        if self.seconds > 0.0 {
            self.rays as f64 / self.seconds
        } else {
            0.0
        }
    }

    fn json(&self) -> Value {
        json!({
            "rays": self.rays,
            "hits": self.hits,
            "seconds": self.seconds,
            "min_seconds": self.min_seconds,
            "max_seconds": self.max_seconds,
            "rays_per_second": self.rays_per_second(),
            "nodes_per_ray": self.nodes_per_ray,
            "tests_per_ray": self.tests_per_ray,
        })
    }
}

/// Both kinds on one structure.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RayBench {
    pub(crate) accel: AccelKind,
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) threads: usize,
    pub(crate) runs: usize,
    pub(crate) build_seconds: f64,
    pub(crate) eye: KindTiming,
    pub(crate) shadow: KindTiming,
}

/// Builds the structure, makes the ray set of `camera`'s frame and times
/// each kind of ray.
pub fn run(world: &World, camera: &Camera, options: &RayBenchOptions) -> Result<RayBench> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads.unwrap_or(0))
        .build()
        .context("could not start the threads")?;
    let runs = options.runs.max(1);
    pool.install(|| {
        let start = Instant::now();
        let index = SceneIndex::build(&world.shapes, options.accel, options.grid_multiplier);
        let build_seconds = start.elapsed().as_secs_f64();
        let set = RaySet::new(world, &index, camera);
        let tiles: Vec<_> = set.eye_tiles().collect();
        let eye = time_kind(set.eye.len(), runs, || {
            tiles
                .par_iter()
                .map(|rays| {
                    let mut counters = Counters::default();
                    let hits = cast_eye(&index, world, rays, set.hither, &mut counters);
                    (hits, counters)
                })
                .reduce(Default::default, add)
        });
        let shadow = time_kind(set.shadow.len(), runs, || {
            set.shadow
                .par_chunks(SHADOW_CHUNK)
                .map(|rays| {
                    let mut counters = Counters::default();
                    let blocked = cast_shadow(&index, world, rays, &mut counters);
                    (blocked, counters)
                })
                .reduce(Default::default, add)
        });
        Ok(RayBench {
            accel: options.accel,
            width: camera.width(),
            height: camera.height(),
            threads: rayon::current_num_threads(),
            runs,
            build_seconds,
            eye,
            shadow,
        })
    })
}

fn add(a: (u64, Counters), b: (u64, Counters)) -> (u64, Counters) {
    let mut counters = a.1;
    counters += b.1;
    (a.0 + b.0, counters)
}

/// Casts once to warm up, then `runs` times, timing each cast.
fn time_kind(rays: usize, runs: usize, mut cast: impl FnMut() -> (u64, Counters)) -> KindTiming {
    let (hits, counters) = cast();
    let mut seconds: Vec<f64> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(cast());
            start.elapsed().as_secs_f64()
        })
        .collect();
    seconds.sort_by(f64::total_cmp);
    let n = seconds.len();
    let median = if n % 2 == 1 {
        seconds[n / 2]
    } else {
        0.5 * (seconds[n / 2 - 1] + seconds[n / 2])
    };
    let per_ray = |v: u64| {
        if rays == 0 {
            0.0
        } else {
            v as f64 / rays as f64
        }
    };
    KindTiming {
        rays: rays as u64,
        hits,
        seconds: median,
        min_seconds: seconds[0],
        max_seconds: seconds[n - 1],
        nodes_per_ray: per_ray(counters.nodes_visited),
        tests_per_ray: per_ray(counters.intersection_tests),
    }
}

impl RayBench {
    /// One JSON object: the setup, then `eye` and `shadow`, each with
    /// `rays`, `hits`, `seconds` (the median), `rays_per_second`,
    /// `nodes_per_ray` and `tests_per_ray`.
    pub(crate) fn json(&self, scene: &str) -> Value {
        json!({
            "scene": scene,
            "structure": self.accel.name(),
            "width": self.width,
            "height": self.height,
            "threads": self.threads,
            "runs": self.runs,
            "build_seconds": self.build_seconds,
            "eye": self.eye.json(),
            "shadow": self.shadow.json(),
        })
    }

    /// A header line and one aligned row per kind.
    pub(crate) fn text(&self, scene: &str) -> String {
        let mut out = format!(
            "{scene}: {}x{}, {} (built in {:.1} ms), {} thread(s), median of {} run(s) after a warm-up\n\n",
            self.width,
            self.height,
            self.accel.name(),
            self.build_seconds * 1e3,
            self.threads,
            self.runs,
        );
        out += &format!(
            "{:<7} {:>9} {:>9} {:>9} {:>19} {:>9} {:>9} {:>9}\n",
            "kind", "rays", "hits", "ms", "min..max ms", "M rays/s", "nodes/ray", "tests/ray"
        );
        for (name, k) in [("eye", &self.eye), ("shadow", &self.shadow)] {
            out += &format!(
                "{:<7} {:>9} {:>9} {:>9.2} {:>19} {:>9.2} {:>9.2} {:>9.2}\n",
                name,
                k.rays,
                k.hits,
                k.seconds * 1e3,
                format!("{:.2}..{:.2}", k.min_seconds * 1e3, k.max_seconds * 1e3),
                k.rays_per_second() * 1e-6,
                k.nodes_per_ray,
                k.tests_per_ray,
            );
        }
        out
    }
}
