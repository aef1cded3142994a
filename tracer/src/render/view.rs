//! Views: what each pixel cost and what it saw, measured while the shaded
//! image renders. A [`ViewRecorder`] watches each pixel sample's trace and
//! the difference of the thread's [`Counters`] around it gives the work,
//! so the numbers are exact and come from the very rays of the image.
//! A [`ViewFilm`] averages them over the samples like the image's film.

use glam::Vec3A;
use image::Rgb;

use crate::geometry::Ray;
use crate::metrics::Palette;
use crate::stats::Counters;
use crate::world::World;

use super::trace::{RayKind, ShadowSample, SurfaceHit, TraceRecorder};
use super::{Encoding, Film, Tile};

/// A per-pixel quantity shown instead of the shaded image.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum View {
    /// The rendered image.
    #[default]
    Shaded,
    /// Ray-primitive intersection tests of every ray the pixel spawned.
    Tests,
    /// Acceleration-structure steps: BVH nodes visited, grid cells walked.
    Steps,
    /// Rays of every kind the pixel spawned.
    Rays,
    /// Shadow rays spawned.
    Shadow,
    /// The fraction of shadow rays that were blocked.
    Blocked,
    /// The deepest bounce reached (the eye ray is depth 0).
    Depth,
    /// Distance along the eye ray to its hit (no value on the background).
    Distance,
    /// The eye hit's shading normal as a colour.
    Normals,
    /// A stable false colour per scene object the eye ray hit.
    Objects,
    /// Samples the pixel took: N x N everywhere with uniform sampling;
    /// with adaptive sampling, where the image needed them.
    Samples,
}

impl View {
    /// Every view, in the order the selector cycles through them.
    pub const ALL: [View; 11] = [
        View::Shaded,
        View::Tests,
        View::Steps,
        View::Rays,
        View::Shadow,
        View::Blocked,
        View::Depth,
        View::Distance,
        View::Normals,
        View::Objects,
        View::Samples,
    ];

    /// The name the command line and reports use.
    pub fn name(self) -> &'static str {
        match self {
            View::Shaded => "shaded",
            View::Tests => "tests",
            View::Steps => "steps",
            View::Rays => "rays",
            View::Shadow => "shadow",
            View::Blocked => "blocked",
            View::Depth => "depth",
            View::Distance => "distance",
            View::Normals => "normals",
            View::Objects => "objects",
            View::Samples => "samples",
        }
    }

    /// The view called `name` (see [`View::name`]).
    pub fn from_name(name: &str) -> Option<View> {
        View::ALL.into_iter().find(|v| v.name() == name)
    }

    /// What one unit of the view's value is, for legends.
    pub fn unit(self) -> &'static str {
        match self {
            View::Tests => "tests per pixel",
            View::Steps => "steps per pixel",
            View::Rays => "rays per pixel",
            View::Shadow => "shadow rays per pixel",
            View::Blocked => "fraction of shadow rays blocked",
            View::Depth => "bounces",
            View::Distance => "scene units",
            View::Samples => "samples per pixel",
            View::Shaded | View::Normals | View::Objects => "",
        }
    }

    /// Whether the view is a number per pixel, drawn as a heat map (the
    /// others are colours).
    pub fn is_scalar(self) -> bool {
        !matches!(self, View::Shaded | View::Normals | View::Objects)
    }

    /// The next view, wrapping around: the key that cycles views.
    pub fn next(self) -> View {
        let i = View::ALL.iter().position(|&v| v == self).unwrap_or(0);
        View::ALL[(i + 1) % View::ALL.len()]
    }
}

/// What one sample of one pixel cost and saw.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct ViewSample {
    pub tests: u32,
    pub steps: u32,
    pub rays: u32,
    pub shadow_rays: u32,
    pub blocked: u32,
    pub depth: u32,
    /// The eye ray's hit, if any.
    pub eye_hit: Option<EyeHit>,
}

/// What the eye ray of a sample hit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EyeHit {
    pub distance: f32,
    pub normal: Vec3A,
    /// Index into the scene's objects.
    pub object: u32,
}

/// Watches one pixel sample's trace for the views.
#[derive(Debug, Default)]
pub(crate) struct ViewRecorder {
    depth: u32,
    open_kind: Option<RayKind>,
    eye_hit: Option<SurfaceHit>,
    blocked: u32,
}

impl TraceRecorder for ViewRecorder {
    #[inline]
    fn ray(&mut self, kind: RayKind, depth: u32, _ray: &Ray, _weight: Vec3A) {
        self.depth = self.depth.max(depth);
        self.open_kind = Some(kind);
    }

    #[inline]
    fn hit(&mut self, hit: &SurfaceHit, _ambient: Vec3A) {
        if self.open_kind == Some(RayKind::Eye) {
            self.eye_hit = Some(*hit);
        }
    }

    #[inline]
    fn shadow(&mut self, sample: &ShadowSample) {
        self.blocked += u32::from(sample.blocked);
    }
}

impl ViewRecorder {
    /// The sample's numbers: the work is what `counters` gained since
    /// `before`.
    pub fn finish(self, world: &World, before: &Counters, after: &Counters) -> ViewSample {
        let diff = |a: u64, b: u64| (a - b).min(u32::MAX as u64) as u32;
        ViewSample {
            tests: diff(after.intersection_tests, before.intersection_tests),
            steps: diff(after.nodes_visited, before.nodes_visited),
            rays: diff(after.total_rays(), before.total_rays()),
            shadow_rays: diff(after.shadow_rays, before.shadow_rays),
            blocked: self.blocked,
            depth: self.depth,
            eye_hit: self.eye_hit.map(|h| EyeHit {
                distance: h.t,
                normal: h.normal,
                object: world
                    .shape_object
                    .get(h.shape as usize)
                    .copied()
                    .unwrap_or(0),
            }),
        }
    }
}

/// Running sums of one pixel's view samples.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct PixelSums {
    samples: u32,
    tests: f32,
    steps: f32,
    rays: f32,
    shadow_rays: f32,
    blocked: f32,
    depth: f32,
    /// The deepest bounce of any of the pixel's samples.
    deepest: u32,
    eye_hits: u32,
    distance: f32,
    normal: Vec3A,
    object_colour: Vec3A,
}

/// What [`ViewFilm::totals`] sums over a film.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ViewTotals {
    /// Shadow rays traced, over all samples.
    pub shadow_rays: f64,
    /// Shadow rays that met an occluder.
    pub blocked: f64,
    /// The deepest bounce of any sample (the eye ray is depth 0).
    pub deepest: u32,
}

/// Per-pixel sums of view samples, the views' counterpart of [`Film`].
#[derive(Debug, Clone, PartialEq)]
pub struct ViewFilm {
    width: u32,
    height: u32,
    pixels: Vec<PixelSums>,
}

impl ViewFilm {
    /// An empty film of `width` x `height` pixels, no sample recorded yet.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![PixelSums::default(); width as usize * height as usize],
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Adds one sample to each pixel of `tile`; `samples` is row-major
    /// within the tile.
    pub(crate) fn add_tile(&mut self, tile: &Tile, samples: &[ViewSample]) {
        for (start, chunk) in tile.rows(self.width, samples) {
            for (sums, s) in self.pixels[start..start + chunk.len()]
                .iter_mut()
                .zip(chunk)
            {
                sums.add(s);
            }
        }
    }

    /// Adds samples to the pixels of `tile` as [`Film::add_samples`] does:
    /// `counts[i]` samples of pixel `i`, pixel after pixel in `samples`.
    pub(crate) fn add_samples(&mut self, tile: &Tile, counts: &[u32], samples: &[ViewSample]) {
        let mut samples = samples.iter();
        for (start, row) in tile.rows(self.width, counts) {
            for (sums, &count) in self.pixels[start..start + row.len()].iter_mut().zip(row) {
                for s in samples.by_ref().take(count as usize) {
                    sums.add(s);
                }
            }
        }
    }
}

impl PixelSums {
    /// Adds one view sample.
    fn add(&mut self, s: &ViewSample) {
        self.samples += 1;
        self.tests += s.tests as f32;
        self.steps += s.steps as f32;
        self.rays += s.rays as f32;
        self.shadow_rays += s.shadow_rays as f32;
        self.blocked += s.blocked as f32;
        self.depth += s.depth as f32;
        self.deepest = self.deepest.max(s.depth);
        if let Some(hit) = s.eye_hit {
            self.eye_hits += 1;
            self.distance += hit.distance;
            self.normal += hit.normal;
            self.object_colour += object_colour(hit.object);
        }
    }
}

impl ViewFilm {
    /// The value of a scalar view at every pixel, row-major: the mean over
    /// the pixel's samples; `None` before the first sample, and where the
    /// view has no value (distance on the background, blocked without
    /// shadow rays). Colour views have no numbers: all `None`.
    pub fn values(&self, view: View) -> Vec<Option<f32>> {
        self.pixels.iter().map(|p| scalar(p, view)).collect()
    }

    /// Shadow rays, blocked shadow rays and the deepest bounce over the
    /// whole film: a frame's statistics that the counters do not keep.
    pub fn totals(&self) -> ViewTotals {
        let mut totals = ViewTotals::default();
        for p in &self.pixels {
            totals.shadow_rays += f64::from(p.shadow_rays);
            totals.blocked += f64::from(p.blocked);
            totals.deepest = totals.deepest.max(p.deepest);
        }
        totals
    }

    /// The value of a scalar view at one pixel (see [`ViewFilm::values`]).
    pub fn value(&self, view: View, x: u32, y: u32) -> Option<f32> {
        let p = self
            .pixels
            .get(y as usize * self.width as usize + x as usize)?;
        scalar(p, view)
    }

    /// The colour views (normals, objects) as RGBA8, row-major; pixels
    /// without a sample are transparent, the background black. `None` for
    /// the other views.
    pub(crate) fn colours_rgba8(&self, view: View) -> Option<Vec<u8>> {
        if !matches!(view, View::Normals | View::Objects) {
            return None;
        }
        let mut out = Vec::with_capacity(self.pixels.len() * 4);
        for p in &self.pixels {
            if p.samples == 0 {
                out.extend_from_slice(&[0, 0, 0, 0]);
                continue;
            }
            // Background samples count as black, so silhouettes blend.
            let coverage = p.eye_hits as f32 / p.samples as f32;
            let c = match view {
                View::Normals if p.eye_hits > 0 => {
                    ((p.normal / p.eye_hits as f32) * 0.5 + 0.5) * coverage
                }
                View::Normals => Vec3A::ZERO,
                _ => p.object_colour / p.samples as f32,
            };
            let e = |v: f32| Encoding::Linear.encode(v);
            out.extend_from_slice(&[e(c.x), e(c.y), e(c.z), 255]);
        }
        Some(out)
    }
}

fn scalar(p: &PixelSums, view: View) -> Option<f32> {
    if p.samples == 0 {
        return None;
    }
    let n = p.samples as f32;
    match view {
        View::Tests => Some(p.tests / n),
        View::Steps => Some(p.steps / n),
        View::Rays => Some(p.rays / n),
        View::Shadow => Some(p.shadow_rays / n),
        View::Blocked => (p.shadow_rays > 0.0).then(|| p.blocked / p.shadow_rays),
        View::Depth => Some(p.depth / n),
        View::Distance => (p.eye_hits > 0).then(|| p.distance / p.eye_hits as f32),
        View::Samples => Some(n),
        View::Shaded | View::Normals | View::Objects => None,
    }
}

/// A stable, well-spread false colour for object `index`: golden-ratio
/// steps around the hue circle, so neighbours in the file differ.
pub(crate) fn object_colour(index: u32) -> Vec3A {
    let hue = (index as f32 * 0.618_034).fract();
    let sector = hue * 6.0;
    let x = 1.0 - (sector % 2.0 - 1.0).abs();
    let (r, g, b) = match sector as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    // Not fully saturated, so shapes stay readable.
    Vec3A::new(r, g, b) * 0.75 + 0.2
}

/// How a heat map's top end is chosen.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum HeatScale {
    /// The largest value.
    #[default]
    Max,
    /// The 99th percentile: a few extreme pixels do not flatten the rest.
    P99,
    /// A fixed value, to compare images made apart.
    Fixed(f32),
}

/// How view values become colours: `0 .. top` over the palette, linearly or
/// on `log(1 + v)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewHeatmap {
    /// The value that takes the palette's last colour; larger values clamp to it.
    pub top: f32,
    /// Scale by `log(1 + v)`, so small values stay apart when a few are large.
    pub log: bool,
}

/// The palette of every heat map, so legends agree.
pub const HEAT_PALETTE: Palette = Palette::Magma;

impl ViewHeatmap {
    /// The heat map whose top is `scale` of all values of all `sides`
    /// together: the shared scale of a comparison.
    pub fn fit(scale: HeatScale, log: bool, sides: &[&[Option<f32>]]) -> ViewHeatmap {
        let top = match scale {
            HeatScale::Fixed(v) => v,
            HeatScale::Max | HeatScale::P99 => {
                let mut all: Vec<f32> = sides
                    .iter()
                    .flat_map(|s| s.iter().flatten().copied())
                    .collect();
                let summary = ViewSummary::of_sorted(sort(&mut all));
                match (scale, summary) {
                    (_, None) => 0.0,
                    (HeatScale::P99, Some(s)) => s.p99,
                    (_, Some(s)) => s.max,
                }
            }
        };
        ViewHeatmap {
            top: if top.is_finite() && top > 0.0 {
                top
            } else {
                1.0
            },
            log,
        }
    }

    /// Where `value` falls on the palette, 0 to 1 (clamped).
    pub fn position(&self, value: f32) -> f32 {
        let t = if self.log {
            value.max(0.0).ln_1p() / self.top.ln_1p()
        } else {
            value / self.top
        };
        t.clamp(0.0, 1.0)
    }

    /// The palette colour of `value` on this scale.
    pub fn colour(&self, value: f32) -> Rgb<u8> {
        HEAT_PALETTE.colour(self.position(value))
    }

    /// `values` as RGBA8: no sample yet is transparent, no value (the
    /// background of a distance view) a dark grey.
    pub fn rgba8(&self, values: &[Option<f32>], sampled: impl Fn(usize) -> bool) -> Vec<u8> {
        let mut out = Vec::with_capacity(values.len() * 4);
        for (i, v) in values.iter().enumerate() {
            match v {
                Some(v) => {
                    let [r, g, b] = self.colour(*v).0;
                    out.extend_from_slice(&[r, g, b, 255]);
                }
                None if sampled(i) => out.extend_from_slice(&NO_VALUE),
                None => out.extend_from_slice(&[0, 0, 0, 0]),
            }
        }
        out
    }
}

/// The colour of a pixel whose view has no value.
pub const NO_VALUE: [u8; 4] = [48, 48, 56, 255];

impl ViewFilm {
    /// Whether pixel `i` (row-major) has a sample.
    pub fn sampled(&self, i: usize) -> bool {
        self.pixels.get(i).is_some_and(|p| p.samples > 0)
    }

    /// The view as RGBA8: the heat map of a scalar view, the colours of
    /// normals and objects; `None` for the shaded view, which is the
    /// image's [`Film`].
    pub fn to_rgba8(&self, view: View, heat: &ViewHeatmap) -> Option<Vec<u8>> {
        if view.is_scalar() {
            Some(heat.rgba8(&self.values(view), |i| self.sampled(i)))
        } else {
            self.colours_rgba8(view)
        }
    }
}

/// Summary numbers of a view over the pixels that have a value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewSummary {
    /// Pixels with a value (those summarised).
    pub pixels: usize,
    /// Mean value.
    pub mean: f32,
    /// Median value.
    pub median: f32,
    /// 99th percentile: a scale top that ignores the rarest extremes.
    pub p99: f32,
    /// Largest value.
    pub max: f32,
}

impl ViewSummary {
    /// The summary of `values`; `None` when no pixel has a value.
    pub fn of(values: &[Option<f32>]) -> Option<ViewSummary> {
        let mut all: Vec<f32> = values.iter().flatten().copied().collect();
        Self::of_sorted(sort(&mut all))
    }

    fn of_sorted(sorted: &[f32]) -> Option<ViewSummary> {
        let last = sorted.len().checked_sub(1)?;
        let at = |q: f32| sorted[((last as f32 * q).round() as usize).min(last)];
        let sum: f64 = sorted.iter().map(|&v| v as f64).sum();
        Some(ViewSummary {
            pixels: sorted.len(),
            mean: (sum / sorted.len() as f64) as f32,
            median: at(0.5),
            p99: at(0.99),
            max: sorted[last],
        })
    }
}

fn sort(values: &mut [f32]) -> &[f32] {
    values.sort_unstable_by(f32::total_cmp);
    values
}

/// The image of a film and its view film under `view`: the shaded image
/// for [`View::Shaded`] (or when there is no view film).
pub(crate) fn view_rgba8(
    film: &Film,
    views: Option<&ViewFilm>,
    view: View,
    heat: &ViewHeatmap,
    encoding: Encoding,
) -> Vec<u8> {
    views
        .and_then(|v| v.to_rgba8(view, heat))
        .unwrap_or_else(|| film.to_rgba8(encoding))
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::accel::{AccelKind, SceneIndex};
    use crate::render::{JobOptions, RenderJob, RenderPlan, RenderSettings};
    use crate::scene::{Limits, parse_scene};

    /// A sphere of radius 1 at the origin, seen from 5 units away: the
    /// centre pixel hits it at distance 4, the corners miss.
    const ONE_SPHERE: &str = "\
v from 0 -5 0 at 0 0 0 up 0 0 1 angle 30 hither 0.01 resolution 9 9
l 0 -5 5
f 1 1 1 1 0 0 0 1
s 0 0 0 1
";

    fn views_of(text: &str, accel: AccelKind, settings: RenderSettings) -> (ViewFilm, Film) {
        let scene = parse_scene(text, None, &Limits::default()).expect("test scene parses");
        let world = Arc::new(crate::world::World::build(&scene));
        let index = Arc::new(SceneIndex::build(&world.shapes, accel, 2.0));
        let job = RenderJob::start(
            world,
            Some(index),
            RenderSettings { accel, ..settings },
            JobOptions {
                threads: Some(1),
                views: true,
                ..JobOptions::default()
            },
        )
        .unwrap();
        let (film, views, _, _) = job.wait_with_views();
        (views.expect("the job measured views"), film)
    }

    fn plain(width: u32, height: u32) -> RenderSettings {
        RenderSettings {
            width,
            height,
            ..RenderSettings::default()
        }
    }

    #[test]
    fn one_sphere_without_structure_counts_each_ray_test() {
        let (v, _) = views_of(ONE_SPHERE, AccelKind::None, plain(9, 9));
        // A miss: the eye ray alone, one test of the one primitive, no step.
        assert_eq!(v.value(View::Tests, 0, 0), Some(1.0));
        assert_eq!(v.value(View::Steps, 0, 0), Some(0.0));
        assert_eq!(v.value(View::Rays, 0, 0), Some(1.0));
        assert_eq!(v.value(View::Shadow, 0, 0), Some(0.0));
        assert_eq!(v.value(View::Blocked, 0, 0), None);
        assert_eq!(v.value(View::Depth, 0, 0), Some(0.0));
        assert_eq!(v.value(View::Distance, 0, 0), None);
        // A hit on a matte sphere: the eye ray and one shadow ray, one test each.
        assert_eq!(v.value(View::Tests, 4, 4), Some(2.0));
        assert_eq!(v.value(View::Rays, 4, 4), Some(2.0));
        assert_eq!(v.value(View::Shadow, 4, 4), Some(1.0));
        assert_eq!(v.value(View::Blocked, 4, 4), Some(0.0));
        assert_eq!(v.value(View::Steps, 4, 4), Some(0.0));
        let d = v.value(View::Distance, 4, 4).unwrap();
        assert!((d - 4.0).abs() < 1e-3, "{d}");
    }

    #[test]
    fn structures_count_their_steps() {
        for accel in [AccelKind::Grid, AccelKind::Bvh] {
            let (v, _) = views_of(ONE_SPHERE, accel, plain(9, 9));
            let hit = v.value(View::Steps, 4, 4).unwrap();
            assert!(hit >= 1.0, "{accel:?}: {hit}");
            // The sphere fills the structure, and only its rays' steps count.
            let total: f32 = v.values(View::Steps).iter().flatten().sum();
            assert!(total > hit, "{accel:?}");
        }
    }

    #[test]
    fn a_blocker_blocks_the_shadow_ray_and_a_mirror_bounces() {
        // A small ball between the light and the sphere's front.
        let blocked = format!("{ONE_SPHERE}s 0 -3 3 0.5\n");
        let (v, _) = views_of(&blocked, AccelKind::None, plain(9, 9));
        assert_eq!(v.value(View::Blocked, 4, 4), Some(1.0));
        // The ball blocked the pixel before's shadow ray too, so the
        // shadow cache tests it first, and only it.
        assert_eq!(
            v.value(View::Tests, 4, 4),
            Some(3.0),
            "2 eye tests + 1 shadow test"
        );

        let mirror = ONE_SPHERE.replace("f 1 1 1 1 0 0 0 1", "f 1 1 1 0.5 0.5 10 0 1");
        let (v, _) = views_of(&mirror, AccelKind::None, plain(9, 9));
        // The reflection leaves the sphere: depth 1, one more ray.
        assert_eq!(v.value(View::Depth, 4, 4), Some(1.0));
        assert_eq!(v.value(View::Rays, 4, 4), Some(3.0));
        assert_eq!(v.value(View::Depth, 0, 0), Some(0.0));
        assert_eq!(v.totals().deepest, 1);
    }

    #[test]
    fn totals_count_blocked_shadow_rays_over_the_film() {
        // A small ball: it shadows part of the sphere, not all of it.
        let blocked = format!("{ONE_SPHERE}s 0 -3 3 0.15\n");
        let (v, _) = views_of(&blocked, AccelKind::None, plain(9, 9));
        let totals = v.totals();
        let sum = |view| v.values(view).iter().flatten().sum::<f32>();
        assert_eq!(totals.shadow_rays, f64::from(sum(View::Shadow)));
        let per_pixel: f32 = (0..81)
            .filter_map(|i| {
                let (x, y) = (i % 9, i / 9);
                Some(v.value(View::Blocked, x, y)? * v.value(View::Shadow, x, y)?)
            })
            .sum();
        assert!(totals.blocked >= 1.0 && totals.blocked < totals.shadow_rays);
        assert_eq!(totals.blocked, f64::from(per_pixel));
        assert_eq!(totals.deepest, 0, "a matte scene does not bounce");
    }

    #[test]
    fn views_average_the_samples_and_leave_the_image_alone() {
        let scene = format!("{ONE_SPHERE}s 0 -3 3 0.5\n");
        let settings = RenderSettings {
            antialiasing: true,
            samples: 2,
            soft_shadows: true,
            light_size: 2.0,
            ..plain(9, 9)
        };
        let (v, film) = views_of(&scene, AccelKind::Bvh, settings.clone());
        let parsed = parse_scene(&scene, None, &Limits::default()).unwrap();
        let world = Arc::new(crate::world::World::build(&parsed));
        let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
        let (plain_film, stats) = crate::render::render(world, index, settings, Some(1)).unwrap();
        assert_eq!(film, plain_film, "views must not change the image");
        // The per-pixel means times the 4 samples add up to the render's counts.
        let total = |view| v.values(view).iter().flatten().sum::<f32>() * 4.0;
        assert_eq!(total(View::Tests), stats.counters.intersection_tests as f32);
        assert_eq!(total(View::Rays), stats.counters.total_rays() as f32);
        assert_eq!(total(View::Steps), stats.counters.nodes_visited as f32);
        // Part of the light is hidden behind the blocker: a fraction.
        let blocked = v.value(View::Blocked, 4, 4).unwrap();
        assert!(blocked > 0.0 && blocked <= 1.0, "{blocked}");
    }

    #[test]
    fn objects_and_normals_are_colours() {
        let two = format!("{ONE_SPHERE}s 0 -3 3 0.5\n");
        let (v, _) = views_of(&two, AccelKind::Bvh, plain(9, 9));
        let objects = v.colours_rgba8(View::Objects).unwrap();
        let at =
            |rgba: &[u8], x: usize, y: usize| rgba[(y * 9 + x) * 4..(y * 9 + x) * 4 + 4].to_vec();
        assert_eq!(at(&objects, 0, 0), [0, 0, 0, 255], "background is black");
        let e = |c: Vec3A| [c.x, c.y, c.z].map(|v| Encoding::Linear.encode(v));
        assert_eq!(at(&objects, 4, 4)[..3], e(object_colour(0)));
        assert_ne!(object_colour(0), object_colour(1));
        // The centre's normal faces the camera (-y): green channel low.
        let normals = v.colours_rgba8(View::Normals).unwrap();
        assert!(at(&normals, 4, 4)[1] < 30, "{:?}", at(&normals, 4, 4));
        assert!(v.colours_rgba8(View::Tests).is_none());
    }

    #[test]
    fn heat_scales_are_shared_and_summaries_are_right() {
        let a: Vec<Option<f32>> = (1..=100).map(|v| Some(v as f32)).collect();
        let b = vec![Some(400.0), None];
        let max = ViewHeatmap::fit(HeatScale::Max, false, &[&a, &b]);
        assert_eq!(max.top, 400.0);
        assert_eq!(ViewHeatmap::fit(HeatScale::P99, false, &[&a]).top, 99.0);
        assert_eq!(
            ViewHeatmap::fit(HeatScale::Fixed(7.0), false, &[&a]).top,
            7.0
        );
        assert_eq!(ViewHeatmap::fit(HeatScale::Max, false, &[&[None]]).top, 1.0);
        assert_eq!(max.position(200.0), 0.5);
        assert_eq!(max.position(1e9), 1.0);
        let log = ViewHeatmap {
            top: 99.0,
            log: true,
        };
        assert!((log.position(9.0) - 0.5).abs() < 1e-6);
        let s = ViewSummary::of(&a).unwrap();
        assert_eq!((s.pixels, s.mean, s.max, s.p99), (100, 50.5, 100.0, 99.0));
        assert!(ViewSummary::of(&[None]).is_none());
    }

    #[test]
    fn views_cycle_through_every_name() {
        let mut v = View::Shaded;
        for _ in 0..View::ALL.len() {
            assert_eq!(View::from_name(v.name()), Some(v));
            v = v.next();
        }
        assert_eq!(v, View::Shaded);
    }

    #[test]
    fn the_frame_samples_views_and_image_alike() {
        let scene = parse_scene(ONE_SPHERE, None, &Limits::default()).unwrap();
        let world = Arc::new(crate::world::World::build(&scene));
        let index = Arc::new(SceneIndex::build(&world.shapes, AccelKind::Bvh, 2.0));
        let plan = RenderPlan::new(world, index, plain(9, 9)).unwrap();
        let tile = plan.tiles[0];
        let mut a = Counters::default();
        let mut b = Counters::default();
        let (values, samples) = plan.render_tile_with_views(0, &tile, &mut a);
        assert_eq!(values, plan.render_tile(0, &tile, &mut b));
        assert_eq!(a, b);
        assert_eq!(samples.len(), 81);
    }
}
