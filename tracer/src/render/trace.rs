//! Whitted's recursive ray tracing: Blinn-Phong for every light the surface
//! faces, shadow rays, mirror reflection weighted by the specular colour,
//! refraction with Fresnel weighting and total internal reflection.

use std::cell::Cell;

use glam::Vec3A;

use crate::accel::{Hit, SceneIndex};
use crate::geometry::Ray;
use crate::optics::{MAX_RADIANCE, blinn_phong, bounded, fresnel, reflect, refract};
use crate::sampling::{SampleStream, multi_jittered};
use crate::stats::Counters;
use crate::world::{Light, Surface, World, perpendicular_basis};

use super::{RenderSettings, adaptive};

/// Why a ray was traced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RayKind {
    /// From the camera through a pixel.
    Eye,
    /// Mirrored off a specular surface.
    Reflection,
    /// Bent through a transmitting surface.
    Refraction,
    /// From a surface towards a light sample, testing visibility.
    Shadow,
}

impl RayKind {
    /// Its lower-case name, as views and reports print it.
    pub fn name(self) -> &'static str {
        match self {
            RayKind::Eye => "eye",
            RayKind::Reflection => "reflection",
            RayKind::Refraction => "refraction",
            RayKind::Shadow => "shadow",
        }
    }
}

/// Where a ray met a surface, as the shading saw it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceHit {
    /// Distance along the ray to the hit.
    pub t: f32,
    /// Index into the world's shapes.
    pub shape: u32,
    /// The hit point, in world space.
    pub point: Vec3A,
    /// The shading normal, facing the side the ray came from.
    pub normal: Vec3A,
    /// Whether the ray arrived from outside the surface.
    pub outside: bool,
}

/// One shadow ray's outcome.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadowSample {
    /// Index into the world's lights.
    pub light: usize,
    /// The shadow ray, from the surface towards the light sample.
    pub ray: Ray,
    /// Distance to the light's sample point: the ray's extent.
    pub distance: f32,
    /// An occluder stood between surface and light.
    pub blocked: bool,
    /// Light this sample adds to its surface (zero when blocked), before the
    /// weights of the rays above it.
    pub radiance: Vec3A,
}

/// Watches a trace as it happens, so the cost views and the ray-tree
/// inspector read the very rays the shaded render traces instead of a
/// second tracer that could drift from it. Every method does nothing by
/// default: the render's `NoRecord` compiles away entirely.
///
/// Calls nest: [`TraceRecorder::ray`] opens a ray, then come its hit (or
/// background), its shadow samples and its child rays, and
/// [`TraceRecorder::end`] closes it with its radiance.
pub trait TraceRecorder {
    /// A ray starts; its radiance reaches its parent times `weight`.
    fn ray(&mut self, _kind: RayKind, _depth: u32, _ray: &Ray, _weight: Vec3A) {}
    /// The open ray hit a surface; `ambient` is the light it adds directly:
    /// the ambient term, and with shadows off the whole local shading (no
    /// shadow ray carries it).
    fn hit(&mut self, _hit: &SurfaceHit, _ambient: Vec3A) {}
    /// The open ray hit a transmitter: Fresnel reflectance `kr`, and whether
    /// the refraction was lost to total internal reflection.
    fn fresnel(&mut self, _kr: f32, _total_internal_reflection: bool) {}
    /// The open ray left the scene and took `background`.
    fn background(&mut self, _background: Vec3A) {}
    /// A shadow ray from the open ray's hit point.
    fn shadow(&mut self, _sample: &ShadowSample) {}
    /// The open ray is done and brings `radiance`.
    fn end(&mut self, _radiance: Vec3A) {}
}

/// The recorder of a plain render: records nothing, costs nothing.
pub(crate) struct NoRecord;

impl TraceRecorder for NoRecord {}

/// How shadow rays sample a light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ShadowMode {
    /// No shadow ray: every light lights, from its position, every point
    /// that faces it (shadows off, local shading only).
    Off,
    /// One ray to the light's position (an area light's centre).
    Hard,
    /// N x N multi-jittered rays over the light's area, each weighted 1/N^2:
    /// the course's soft shadows without anti-aliasing, where a pixel takes
    /// one sample. Multi-jittered rather than only stratified, so an
    /// occluder's edge along the light's side is met within one sample
    /// (jittered strata miss it by up to N samples).
    Stratified(u32),
    /// One ray per pixel sample: the course's soft shadows with anti-aliasing,
    /// where the pixel's samples average them. The pixel's N x N samples
    /// take the points of one multi-jittered pattern, so they too see the
    /// light's visible fraction within one sample (independent random points
    /// were off by about 1/(2N)). With adaptive sampling a pixel's first
    /// samples take several points each ([`adaptive::light_points`]).
    OnePerSample(u32),
}

/// Relative offset that lifts secondary ray origins off the surface, scaled
/// by the magnitude of the hit point's coordinates (float error grows with
/// it), so scenes of any scale are free of acne without visible gaps.
const RELATIVE_OFFSET: f32 = 3e-5;

/// Where a ray met a surface: the point, the geometric and shading
/// normals turned towards the ray's side, and how far rays leaving it
/// start off the surface.
struct Contact {
    point: Vec3A,
    ng: Vec3A,
    ns: Vec3A,
    /// The ray came from the side the geometric normal points to.
    outside: bool,
    offset: f32,
}

impl Contact {
    /// The point lifted off the surface on the ray's side.
    #[inline(always)]
    fn above(&self) -> Vec3A {
        self.point + self.ng * self.offset
    }
}

/// A surface point that light reaches: where its shadow rays start, its
/// shading normal, the way back to the viewer and its material.
struct Receiver<'a> {
    origin: Vec3A,
    normal: Vec3A,
    to_viewer: Vec3A,
    surface: &'a Surface,
}

/// Traces rays through one world with one set of settings.
///
/// A tracer belongs to one thread (each render thread makes its own per
/// tile): it remembers, per light, the shape that last blocked a shadow
/// ray towards it.
pub struct Tracer<'a> {
    world: &'a World,
    index: &'a SceneIndex,
    settings: &'a RenderSettings,
    shadow_mode: ShadowMode,
    /// The ambient share of the settings, at most [`MAX_RADIANCE`] like
    /// every other factor of the shading.
    ambient: f32,
    /// Offset floor: a millionth of the scene's size.
    min_offset: f32,
    /// POV-Ray's shadow cache: per light, the shape that blocked the last
    /// shadow ray towards it (none if that ray was unblocked). Neighbouring
    /// points tend to be shadowed by the same shape, so it is tested first,
    /// and when it blocks the ray no traversal is needed. Which shape
    /// blocks never changes *whether* the ray is blocked, so images are the
    /// same with or without it.
    last_occluder: Vec<OwnLine<Cell<Option<u32>>>>,
    /// Per light, the points an adaptive pixel's early samples take with
    /// soft shadows ([`adaptive::light_points`]).
    early_light_points: Vec<u32>,
}

/// A value alone on its cache line. The shadow cache is written on every
/// shadow ray, and a tracer's small allocation could share a line with
/// data the other render threads read on every ray (false sharing: with
/// some heap layouts, which the length of an argument shifts, frames were
/// slower).
#[derive(Debug, Default)]
#[repr(align(64))]
struct OwnLine<T>(T);

impl<'a> Tracer<'a> {
    /// A tracer of `world` through `index`, with the depth, sampling and sky of `settings`.
    pub fn new(world: &'a World, index: &'a SceneIndex, settings: &'a RenderSettings) -> Self {
        let shadow_mode = match (
            settings.shadows,
            settings.soft_shadows,
            settings.samples_per_pixel(),
        ) {
            (false, _, _) => ShadowMode::Off,
            (true, false, _) => ShadowMode::Hard,
            (true, true, 1) => ShadowMode::Stratified(settings.samples.max(1)),
            (true, true, _) => ShadowMode::OnePerSample(settings.strata()),
        };
        let power = |light: &Light| light.color.element_sum();
        let brightest = world.lights.iter().map(power).fold(0.0, f32::max);
        let size = if world.bounds.is_empty() {
            1.0
        } else {
            world.bounds.extent().length()
        };
        Self {
            world,
            index,
            settings,
            shadow_mode,
            ambient: settings.ambient.min(MAX_RADIANCE),
            min_offset: 1e-6 * size.min(1e30),
            last_occluder: (0..world.lights.len())
                .map(|_| OwnLine::default())
                .collect(),
            early_light_points: world
                .lights
                .iter()
                .map(|light| adaptive::early_light_points(power(light), brightest))
                .collect(),
        }
    }

    /// Whether anything blocks `shadow` before `distance`: the shape that
    /// blocked the last ray towards light `light` first (one intersection
    /// test), then the acceleration structure, whose answer is kept.
    pub(super) fn shadowed(
        &self,
        light: usize,
        shadow: &Ray,
        distance: f32,
        counters: &mut Counters,
    ) -> bool {
        let shapes = &self.world.shapes;
        let cached = &self.last_occluder[light].0;
        if let Some(id) = cached.get() {
            counters.intersection_tests += 1;
            if shapes[id as usize]
                .intersect(shadow, 0.0, distance)
                .is_some()
            {
                counters.shadow_cache_hits += 1;
                return true;
            }
        }
        let occluder = self.index.occluder(shapes, shadow, 0.0, distance, counters);
        // An unblocked ray empties the cache: lit points come in runs too,
        // and there the cached shape would only cost a test per ray.
        cached.set(occluder);
        occluder.is_some()
    }

    /// Radiance along an eye ray, ignoring hits nearer than `t_min` (hither).
    pub fn trace_eye(
        &self,
        ray: &Ray,
        t_min: f32,
        rng: &mut SampleStream,
        counters: &mut Counters,
    ) -> Vec3A {
        self.trace_eye_recorded(ray, t_min, rng, counters, &mut NoRecord)
    }

    /// [`Tracer::trace_eye`], telling `recorder` every ray it traces.
    #[inline]
    pub(crate) fn trace_eye_recorded<R: TraceRecorder>(
        &self,
        ray: &Ray,
        t_min: f32,
        rng: &mut SampleStream,
        counters: &mut Counters,
        recorder: &mut R,
    ) -> Vec3A {
        counters.eye_rays += 1;
        recorder.ray(RayKind::Eye, 0, ray, Vec3A::ONE);
        self.trace(ray, t_min, 0, rng, counters, recorder)
    }

    /// Radiance along a ray already announced to `recorder`; closes it.
    /// Within [`MAX_RADIANCE`], so that a chain of bright mirrors cannot
    /// multiply it past f32 (see there).
    fn trace<R: TraceRecorder>(
        &self,
        ray: &Ray,
        t_min: f32,
        depth: u32,
        rng: &mut SampleStream,
        counters: &mut Counters,
        recorder: &mut R,
    ) -> Vec3A {
        let radiance =
            match self
                .index
                .closest_hit(&self.world.shapes, ray, t_min, f32::INFINITY, counters)
            {
                Some(hit) => self.shade(ray, hit, depth, rng, counters, recorder),
                None => {
                    let background = self.world.background(ray.dir);
                    recorder.background(background);
                    background
                }
            };
        let radiance = bounded(radiance);
        recorder.end(radiance);
        radiance
    }

    fn shade<R: TraceRecorder>(
        &self,
        ray: &Ray,
        hit: Hit,
        depth: u32,
        rng: &mut SampleStream,
        counters: &mut Counters,
        recorder: &mut R,
    ) -> Vec3A {
        let surface = self.world.surface(hit.shape);
        let contact = self.contact(ray, &hit);
        let lit = Receiver {
            origin: contact.above(),
            normal: contact.ns,
            to_viewer: -ray.dir,
            surface,
        };
        let mut color = surface.diffuse * self.ambient;
        // Without shadows no ray leaves for the lights: the local shading is
        // light the hit adds directly, as the ambient term is, so a ray
        // tree's contributions still sum to the pixel's colour.
        let shadows = self.shadow_mode != ShadowMode::Off;
        if !shadows {
            color += self.direct_light(&lit, rng, counters, &mut NoRecord);
        }
        recorder.hit(
            &SurfaceHit {
                t: hit.t,
                shape: hit.shape,
                point: contact.point,
                normal: contact.ns,
                outside: contact.outside,
            },
            color,
        );
        if shadows {
            color += self.direct_light(&lit, rng, counters, recorder);
        }
        if depth >= self.settings.max_depth {
            return color;
        }
        color + self.secondary(ray, &contact, surface, depth, rng, counters, recorder)
    }

    /// Where `ray` met the surface of `hit`, its normals turned towards
    /// the side the ray came from.
    #[inline(always)]
    fn contact(&self, ray: &Ray, hit: &Hit) -> Contact {
        let point = ray.at(hit.t);
        let normals = self.world.shapes[hit.shape as usize].normal_at(point);
        let outside = ray.dir.dot(normals.geometric) < 0.0;
        let (ng, mut ns) = if outside {
            (normals.geometric, normals.shading)
        } else {
            (-normals.geometric, -normals.shading)
        };
        if ns.dot(ng) <= 0.0 {
            ns = ng;
        }
        Contact {
            point,
            ng,
            ns,
            outside,
            offset: self.min_offset + RELATIVE_OFFSET * point.abs().max_element(),
        }
    }

    /// The light the reflected and refracted rays bring back from a
    /// contact, Fresnel-weighted for transparent surfaces.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn secondary<R: TraceRecorder>(
        &self,
        ray: &Ray,
        contact: &Contact,
        surface: &Surface,
        depth: u32,
        rng: &mut SampleStream,
        counters: &mut Counters,
        recorder: &mut R,
    ) -> Vec3A {
        let (ng, ns) = (contact.ng, contact.ns);
        let mut reflect_weight = surface.specular;
        let mut refraction = None;
        if surface.transmittance > 0.0 {
            let ior = if surface.ior > 0.0 { surface.ior } else { 1.0 };
            let eta = if contact.outside { 1.0 / ior } else { ior };
            let kr = fresnel(-ray.dir.dot(ns), eta);
            reflect_weight += Vec3A::splat(surface.transmittance * kr);
            if let Some(dir) = refract(ray.dir, ns, eta).filter(|t| t.dot(ng) < 0.0) {
                refraction = Some((dir, surface.transmittance * (1.0 - kr)));
            }
            recorder.fresnel(kr, refraction.is_none());
        }
        let mut color = Vec3A::ZERO;
        if reflect_weight.max_element() > 0.0 {
            let mut dir = reflect(ray.dir, ns);
            if dir.dot(ng) <= 0.0 {
                dir = reflect(ray.dir, ng);
            }
            counters.reflection_rays += 1;
            let bounce = Ray::new(contact.above(), dir);
            recorder.ray(RayKind::Reflection, depth + 1, &bounce, reflect_weight);
            let bounced = self.trace(&bounce, 0.0, depth + 1, rng, counters, recorder);
            color += reflect_weight * bounced;
        }
        if let Some((dir, weight)) = refraction.filter(|(_, w)| *w > 0.0) {
            counters.refraction_rays += 1;
            let below = Ray::new(contact.point - ng * contact.offset, dir);
            recorder.ray(RayKind::Refraction, depth + 1, &below, Vec3A::splat(weight));
            let through = self.trace(&below, 0.0, depth + 1, rng, counters, recorder);
            color += through * weight;
        }
        color
    }

    /// Diffuse and specular light from every light the surface faces, with
    /// shadow rays from the receiver's origin (already lifted off the
    /// surface), unless shadows are off.
    fn direct_light<R: TraceRecorder>(
        &self,
        at: &Receiver,
        rng: &mut SampleStream,
        counters: &mut Counters,
        recorder: &mut R,
    ) -> Vec3A {
        let mut total = Vec3A::ZERO;
        for (light_index, light) in self.world.lights.iter().enumerate() {
            let mut from_light = Vec3A::ZERO;
            let mut add =
                |target: Vec3A, weight: f32, counters: &mut Counters, recorder: &mut R| {
                    from_light +=
                        self.light_point(at, light_index, target, weight, counters, recorder);
                };
            match self.shadow_mode {
                ShadowMode::Off | ShadowMode::Hard => add(light.position, 1.0, counters, recorder),
                ShadowMode::Stratified(n) => {
                    let (u, v) = self.light_area(light, at.origin);
                    let weight = 1.0 / (n * n) as f32;
                    let pattern = rng.next_u32();
                    for k in 0..n * n {
                        let s = multi_jittered(k, n, pattern) - 0.5;
                        add(
                            light.position + u * s.x + v * s.y,
                            weight,
                            counters,
                            recorder,
                        );
                    }
                }
                ShadowMode::OnePerSample(n) => {
                    let (u, v) = self.light_area(light, at.origin);
                    let early = self.early_light_points[light_index];
                    let indices = |rank| match self.settings.adaptive() {
                        Some(a) => adaptive::light_points(rank, early, a),
                        None => rank..rank + 1,
                    };
                    rng.next_light_points(n, indices, |s, weight| {
                        let s = s - 0.5;
                        add(
                            light.position + u * s.x + v * s.y,
                            weight,
                            counters,
                            recorder,
                        );
                    });
                }
            }
            total += from_light * light.color;
        }
        total
    }

    /// What point `target` of light `light_index` adds at `at`, `weight`
    /// times its shading (before the light's colour), tracing its shadow
    /// ray unless shadows are off: nothing when blocked or behind.
    #[inline(always)]
    fn light_point<R: TraceRecorder>(
        &self,
        at: &Receiver,
        light_index: usize,
        target: Vec3A,
        weight: f32,
        counters: &mut Counters,
        recorder: &mut R,
    ) -> Vec3A {
        let to_light = target - at.origin;
        let distance = to_light.length();
        if distance <= 0.0 {
            return Vec3A::ZERO;
        }
        // The shadow ray's unit direction is the light's: one
        // normalisation, not a division by the distance and then the ray's
        // own (a chain of two square roots and three divisions on every
        // shadow ray, measured in docs/PERFORMANCE.md).
        let shadow = Ray::new(at.origin, to_light);
        let l = shadow.dir;
        // A sample point beyond f32's range (on a huge `al` light) leaves
        // a NaN direction: nothing to shade with.
        let cos = at.normal.dot(l);
        if cos.is_nan() || cos <= 0.0 {
            return Vec3A::ZERO;
        }
        let mut sample = ShadowSample {
            light: light_index,
            ray: shadow,
            distance,
            blocked: true,
            radiance: Vec3A::ZERO,
        };
        if self.shadow_mode != ShadowMode::Off {
            counters.shadow_rays += 1;
            if self.shadowed(light_index, &shadow, distance, counters) {
                recorder.shadow(&sample);
                return Vec3A::ZERO;
            }
        }
        let surface = at.surface;
        // The highlight's power is the costliest term: only lit points of
        // specular surfaces pay for it.
        let (diffuse, specular) = if surface.specular.max_element() > 0.0 {
            blinn_phong(at.normal, l, at.to_viewer, surface.shine)
        } else {
            (at.normal.dot(l), 0.0)
        };
        let lit = (surface.diffuse * diffuse + surface.specular * specular) * weight;
        sample.blocked = false;
        sample.radiance = lit * self.world.lights[light_index].color;
        recorder.shadow(&sample);
        lit
    }

    /// The two edge vectors of a light's area as seen from `point`: an area
    /// light's own rectangle, or for a point light a square of the
    /// light-size setting facing the point.
    fn light_area(&self, light: &Light, point: Vec3A) -> (Vec3A, Vec3A) {
        if let Some(area) = light.area {
            return area;
        }
        let axis = (point - light.position).normalize_or(Vec3A::Y);
        let (u, v) = perpendicular_basis(axis);
        let size = self.settings.light_size.max(0.0);
        (u * size, v * size)
    }
}
