//! The observer figure: the scene seen from outside, as 3D segments to
//! draw through an observer's camera: the scene camera (eye, frustum, image
//! plane, lens and focal plane), the lights, the recorded rays of pinned
//! pixels generation by generation, and the acceleration structure with an
//! eye ray's walk through it. The window and `workbench observe` draw the
//! same segments.

pub(crate) mod draw;

use std::sync::Arc;

use anyhow::{Result, anyhow};
use glam::{Vec3, Vec3A};
use serde::Serialize;
use tracer::accel::{AccelKind, SceneIndex, StructureLayer, Visit};
use tracer::camera::{Camera, CameraPose};
use tracer::render::{Film, Outcome, RayKind, RayTree, RenderSettings, View, render_with_views};
use tracer::world::World;

use crate::figures::overlay::{Colour, VisitStep};
use crate::figures::projection::DepthMap;

/// What a segment shows, for its colour and style.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case", tag = "part")]
pub(crate) enum Part {
    /// A ray of a recorded tree (a lit shadow ray among them).
    Ray { kind: RayKindName },
    /// A shadow ray ending at what blocked it.
    BlockedShadow,
    /// A short tick along the shading normal at a hit.
    Normal,
    /// The scene camera's eye to a corner of its image.
    Frustum,
    /// The outline of the image plane, at the view distance.
    ImagePlane,
    /// The lens disk (depth of field on).
    Lens,
    /// The outline of the plane in focus.
    FocalPlane,
    /// Light `index`: a marker, its soft-shadow square or `al` rectangle.
    Light { index: usize },
    /// The acceleration structure (BVH boxes at a depth, grid lattice).
    Structure,
    /// A box of the pinned eye ray's walk, coloured by its place in it or
    /// as the step's own (see [`VisitStep`]).
    Visit { colour: Colour },
}

/// [`RayKind`]'s name, for JSON and labels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub(crate) enum RayKindName {
    Eye,
    Reflection,
    Refraction,
    Shadow,
}

impl From<RayKind> for RayKindName {
    fn from(kind: RayKind) -> Self {
        match kind {
            RayKind::Eye => RayKindName::Eye,
            RayKind::Reflection => RayKindName::Reflection,
            RayKind::Refraction => RayKindName::Refraction,
            RayKind::Shadow => RayKindName::Shadow,
        }
    }
}

/// One straight piece of the figure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Segment {
    pub(crate) ends: [Vec3A; 2],
    pub(crate) part: Part,
    /// 0 for side A, 1 for side B: their trees are drawn in two styles.
    pub(crate) side: u8,
    /// When the animation draws it: eye rays 0, bounce generation `d` at
    /// `d`, shadow rays after every bounce; the rest at 0.
    pub(crate) phase: u32,
    /// A ray's bounces above it (the eye ray and its shadow rays: 0).
    pub(crate) depth: u32,
    /// A ray's share of its pixel ([`ray_shares`]); 1 for the rest.
    pub(crate) share: f32,
}

impl Segment {
    fn still(ends: [Vec3A; 2], part: Part) -> Self {
        Self {
            ends,
            part,
            side: 0,
            phase: 0,
            depth: 0,
            share: 1.0,
        }
    }
}

/// Which recorded rays the observer draws: with many pixels' trees the
/// rays that matter drown among those that add nothing, so a student
/// hides what left the scene, what adds too little to its pixel, and the
/// bounces not reached yet (growing the tree one depth at a time).
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, Serialize)]
#[serde(default)]
pub struct RayFilter {
    /// Hide the rays that hit nothing (they took the background).
    pub hide_misses: bool,
    /// Hide the rays whose share of their pixel ([`ray_shares`]) is below
    /// this, from 0 (hide nothing) to 1.
    pub(crate) min_share: f32,
    /// The deepest bounce drawn (0: the eye rays and their shadow rays);
    /// `None` draws every bounce.
    pub max_depth: Option<u32>,
}

impl Default for RayFilter {
    fn default() -> Self {
        Self {
            hide_misses: false,
            min_share: 0.0,
            max_depth: None,
        }
    }
}

/// Each node's share of the pixel: the luminance of what it and the rays
/// it spawned add to the sample's colour, over the colour's. The eye ray's
/// is 1; a blocked shadow ray's is 0. A black sample gives every ray a
/// share of 1, there being nothing to divide.
pub(crate) fn ray_shares(tree: &RayTree) -> Vec<f32> {
    let luminance = |c: Vec3A| 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    let mut brought: Vec<Vec3A> = tree.nodes.iter().map(|n| n.contribution).collect();
    // Parents come before their children: adding each node to its parent
    // from the last makes every node hold its whole subtree.
    for i in (0..tree.nodes.len()).rev() {
        if let Some(parent) = tree.nodes[i].parent {
            let subtree = brought[i];
            brought[parent] += subtree;
        }
    }
    let total: f32 = tree
        .nodes
        .iter()
        .zip(&brought)
        .filter(|(n, _)| n.parent.is_none())
        .map(|(_, b)| luminance(*b))
        .sum();
    brought
        .iter()
        .map(|&b| {
            if total > 0.0 {
                (luminance(b) / total).clamp(0.0, 1.0)
            } else {
                1.0
            }
        })
        .collect()
}

/// Length of a ray that leaves the scene, and of markers, for a scene of
/// `world`'s size.
pub(crate) fn stub_length(world: &World) -> f32 {
    world.bounds.extent().length().max(1.0) * 0.25
}

/// The segments of one recorded tree: each ray from its origin to its hit
/// (to the light sample when lit, to the occluder when blocked; a short
/// stub when it left the scene), and a normal tick at each hit. One ray
/// segment per node of the tree, in its order.
pub(crate) fn ray_segments(tree: &RayTree, stub: f32, side: u8) -> Vec<Segment> {
    filtered_ray_segments(tree, stub, side, &RayFilter::default())
}

/// [`ray_segments`] of the nodes `filter` lets through, each with its
/// share of the pixel (the window fades rays by it).
pub(crate) fn filtered_ray_segments(
    tree: &RayTree,
    stub: f32,
    side: u8,
    filter: &RayFilter,
) -> Vec<Segment> {
    let last_bounce = tree.nodes.iter().map(|n| n.depth).max().unwrap_or(0);
    let shares = ray_shares(tree);
    let mut segments = Vec::with_capacity(tree.nodes.len() * 2);
    for (node, &share) in tree.nodes.iter().zip(&shares) {
        let missed = matches!(node.outcome, Outcome::Background);
        if (filter.hide_misses && missed)
            || share < filter.min_share
            || filter.max_depth.is_some_and(|d| node.depth > d)
        {
            continue;
        }
        let phase = match node.kind {
            RayKind::Shadow => last_bounce + 1,
            _ => node.depth,
        };
        let (end, part) = match &node.outcome {
            Outcome::Surface(s) => (s.point, ray(node.kind)),
            Outcome::Background => (node.origin + node.dir * stub, ray(node.kind)),
            Outcome::Light {
                distance,
                occluder: None,
                ..
            } => (node.origin + node.dir * *distance, ray(node.kind)),
            Outcome::Light {
                occluder: Some(occluder),
                ..
            } => (node.origin + node.dir * occluder.t, Part::BlockedShadow),
        };
        segments.push(Segment {
            ends: [node.origin, end],
            part,
            side,
            phase,
            depth: node.depth,
            share,
        });
        if let Outcome::Surface(s) = &node.outcome {
            segments.push(Segment {
                ends: [s.point, s.point + s.normal * (stub * 0.15)],
                part: Part::Normal,
                side,
                phase,
                depth: node.depth,
                share,
            });
        }
    }
    segments
}

fn ray(kind: RayKind) -> Part {
    Part::Ray { kind: kind.into() }
}

/// The image's four corners on the view plane, clockwise from the top
/// left.
pub(crate) fn image_corners(camera: &Camera) -> [Vec3A; 4] {
    let (w, h) = (camera.width() as f32, camera.height() as f32);
    [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)].map(|(x, y)| camera.view_plane_point(x, y))
}

/// The scene camera: its frustum from the eye through the image's corners,
/// the image plane's outline, and with a lens its disk and the plane in
/// focus.
pub(crate) fn camera_segments(camera: &Camera) -> Vec<Segment> {
    let eye = camera.eye();
    let corners = image_corners(camera);
    let mut segments: Vec<Segment> = corners
        .iter()
        .map(|&c| Segment::still([eye, c], Part::Frustum))
        .collect();
    segments.extend(outline(&corners, Part::ImagePlane));
    if camera.lens_radius() > 0.0 {
        let [right, up, _] = camera.basis();
        segments.extend(circle(eye, right, up, camera.lens_radius(), Part::Lens));
        let focal = corners.map(|c| eye + (c - eye) * camera.focal_ratio());
        segments.extend(outline(&focal, Part::FocalPlane));
    }
    segments
}

/// The lights: a three-axis marker at each, and with soft shadows the
/// area the renderer samples (an `al` light's rectangle; a point light's
/// square of the light size, drawn facing the scene's centre, as the
/// renderer turns it towards each shaded point).
pub(crate) fn light_segments(world: &World, settings: &RenderSettings) -> Vec<Segment> {
    let stub = stub_length(world);
    let centre = world.bounds.centre();
    let mut segments = Vec::new();
    for (index, light) in world.lights.iter().enumerate() {
        let part = Part::Light { index };
        let arm = stub * 0.12;
        for axis in [Vec3A::X, Vec3A::Y, Vec3A::Z] {
            let ends = [light.position - axis * arm, light.position + axis * arm];
            segments.push(Segment::still(ends, part));
        }
        let area = match light.area {
            Some(area) => Some(area),
            None if settings.soft_shadows && settings.light_size > 0.0 => {
                let facing = (centre - light.position).normalize_or(Vec3A::NEG_Y);
                let (u, v) = Vec3::from(facing).any_orthonormal_pair();
                let size = settings.light_size;
                Some((Vec3A::from(u) * size, Vec3A::from(v) * size))
            }
            None => None,
        };
        if settings.soft_shadows
            && let Some((u, v)) = area
        {
            let o = light.position - (u + v) * 0.5;
            segments.extend(outline(&[o, o + u, o + u + v, o + v], part));
        }
    }
    segments
}

/// The structure `index` renders with at `layer`, and the boxes of
/// `visits` (an eye ray's walk) in order, those `step` draws.
pub(crate) fn structure_segments(
    index: &SceneIndex,
    layer: Option<StructureLayer>,
    visits: &[Visit],
    step: VisitStep,
) -> Vec<Segment> {
    let mut segments: Vec<Segment> = layer
        .map(|layer| index.wireframe(layer))
        .unwrap_or_default()
        .into_iter()
        .map(|ends| Segment::still(ends, Part::Structure))
        .collect();
    for (visit, colour) in step.coloured(visits) {
        let part = Part::Visit { colour };
        segments.extend(
            visit
                .edges()
                .into_iter()
                .map(|ends| Segment::still(ends, part)),
        );
    }
    segments
}

/// A closed polygon through `points`.
fn outline(points: &[Vec3A], part: Part) -> impl Iterator<Item = Segment> + '_ {
    (0..points.len())
        .map(move |i| Segment::still([points[i], points[(i + 1) % points.len()]], part))
}

/// A circle of `radius` around `centre` in the plane of `u` and `v`.
fn circle(centre: Vec3A, u: Vec3A, v: Vec3A, radius: f32, part: Part) -> Vec<Segment> {
    const STEPS: usize = 32;
    let at = |i: usize| {
        let a = i as f32 / STEPS as f32 * std::f32::consts::TAU;
        centre + (u * a.cos() + v * a.sin()) * radius
    };
    (0..STEPS)
        .map(|i| Segment::still([at(i), at(i + 1)], part))
        .collect()
}

/// Lights farther than this many times the scene's radius from its centre
/// are left out of the framing: a sun far away would shrink the scene to
/// a dot.
const FRAMED_LIGHT_REACH: f32 = 4.0;

/// Where the observer starts: behind, above and to the side of the scene
/// camera, far enough that the scene's bounds, the camera and the lights
/// near the scene fit in a view `angle` degrees high and `aspect` (height
/// over width) as tall as wide, so that every marker can be grabbed.
pub(crate) fn framing(world: &World, camera: &Camera, angle: f32, aspect: f32) -> CameraPose {
    let eye = camera.eye();
    let scene = world.bounds.grow(eye);
    let reach = (scene.extent().length() * 0.5).max(1e-3) * FRAMED_LIGHT_REACH;
    let bounds = world
        .lights
        .iter()
        .map(|light| light.position)
        .filter(|p| (*p - scene.centre()).length() <= reach)
        .fold(scene, |b, p| b.grow(p));
    let centre = bounds.centre();
    let radius = (bounds.extent().length() * 0.5).max(1e-3);
    let [right, up, forward] = camera.basis();
    let direction = (-forward * 1.0 + up * 0.6 + right * 0.5).normalize();
    let vertical = (angle.clamp(10.0, 170.0) * 0.5).to_radians();
    let horizontal = (vertical.tan() / aspect.max(1e-3)).atan();
    let half = vertical.min(horizontal);
    let distance = radius / half.sin() * 1.05;
    CameraPose {
        from: (centre + direction * distance).into(),
        at: centre.into(),
        up: up.into(),
    }
}

/// The settings the observer renders `scene`'s settings with: from `pose`
/// at `width` x `height`, one sharp sample per pixel, no soft shadows and
/// no refining, traced with a BVH ([`VIEW_ACCEL`]). It shows where rays go,
/// not the finished image, so it renders in a fraction of the scene's time.
pub(crate) fn render_settings(
    scene: &RenderSettings,
    pose: CameraPose,
    width: u32,
    height: u32,
) -> RenderSettings {
    RenderSettings {
        width,
        height,
        camera: Some(pose),
        antialiasing: false,
        depth_of_field: false,
        soft_shadows: false,
        keep_refining: false,
        accel: VIEW_ACCEL,
        ..scene.clone()
    }
}

/// The structure the observer's own view of the scene is traced with,
/// whatever the scene asks for: the view is an illustration, not the
/// experiment (the pixels' rays follow the scene's structure), and a
/// course file's `accel 0` over 100 000 triangles made it take minutes.
pub(crate) const VIEW_ACCEL: AccelKind = AccelKind::Bvh;

/// Which pixels' trees a figure draws beside the pinned one: a row, a
/// column, or a coarse grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum PixelPattern {
    Row(u32),
    Column(u32),
    /// One pixel every `STEP` in both directions.
    Grid(u32),
}

/// Pixels of a row or column the figure samples (evenly spaced).
const LINE_PIXELS: u32 = 32;

/// Most segments a figure draws; the trees of further pixels are left out
/// (and the figure says so).
pub(crate) const MAX_SEGMENTS: usize = 20_000;

impl std::str::FromStr for PixelPattern {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        let bad = || format!("'{text}' is not row:Y, column:X or grid:STEP");
        let (kind, number) = text.split_once(':').ok_or_else(bad)?;
        let number: u32 = number.parse().map_err(|_| bad())?;
        match kind {
            "row" => Ok(PixelPattern::Row(number)),
            "column" => Ok(PixelPattern::Column(number)),
            "grid" if number > 0 => Ok(PixelPattern::Grid(number)),
            "grid" => Err(format!("'{text}': the grid's step must be at least 1")),
            _ => Err(bad()),
        }
    }
}

impl PixelPattern {
    /// The pattern's pixels in a `width` x `height` image, or why it does
    /// not fit (the valid range named).
    pub(crate) fn pixels(self, width: u32, height: u32) -> Result<Vec<(u32, u32)>, String> {
        let spaced = |n: u32| -> Vec<u32> {
            let count = n.min(LINE_PIXELS);
            (0..count).map(|i| (i * n + n / 2) / count).collect()
        };
        match self {
            PixelPattern::Row(y) if y >= height => Err(format!(
                "row {y} is outside the image: rows 0..{} of {width} x {height}",
                height - 1
            )),
            PixelPattern::Column(x) if x >= width => Err(format!(
                "column {x} is outside the image: columns 0..{} of {width} x {height}",
                width - 1
            )),
            PixelPattern::Row(y) => Ok(spaced(width).into_iter().map(|x| (x, y)).collect()),
            PixelPattern::Column(x) => Ok(spaced(height).into_iter().map(|y| (x, y)).collect()),
            PixelPattern::Grid(step) => Ok((step / 2..height)
                .step_by(step as usize)
                .flat_map(|y| {
                    (step / 2..width)
                        .step_by(step as usize)
                        .map(move |x| (x, y))
                })
                .collect()),
        }
    }
}

/// The colour of each kind of ray wherever rays are drawn: over the image
/// and in the observer view.
pub(crate) fn ray_colour(kind: RayKindName) -> [u8; 3] {
    match kind {
        RayKindName::Eye => [255, 255, 255],
        RayKindName::Reflection => [90, 200, 255],
        RayKindName::Refraction => [255, 120, 220],
        RayKindName::Shadow => [255, 220, 60],
    }
}

/// How a part is drawn: its colour, and whether dashed (blocked shadow
/// rays, and side B's rays beside A's in compare mode).
pub(crate) fn style(segment: &Segment, world: &World) -> ([u8; 3], bool) {
    let colour = match segment.part {
        Part::Ray { kind } => ray_colour(kind),
        Part::BlockedShadow => ray_colour(RayKindName::Shadow),
        Part::Normal => [120, 255, 160],
        Part::Frustum => [200, 200, 200],
        Part::ImagePlane => [255, 255, 255],
        Part::Lens => [80, 230, 255],
        Part::FocalPlane => [255, 150, 80],
        Part::Light { index } => world.lights.get(index).map_or([255; 3], |l| {
            let c = l.color / l.color.max_element().max(1e-6);
            [c.x, c.y, c.z].map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8)
        }),
        Part::Structure => [80, 255, 120],
        Part::Visit { colour } => colour.rgb(),
    };
    let dashed = segment.part == Part::BlockedShadow
        || (segment.side == 1 && matches!(segment.part, Part::Ray { .. } | Part::Normal));
    (colour, dashed)
}

/// The scene rendered by `settings` (an observer's: its camera, size and
/// shading), and how far each pixel's eye ray went: what hides a segment
/// drawn into it.
pub(crate) fn render_with_depth(
    world: Arc<World>,
    index: Arc<SceneIndex>,
    settings: RenderSettings,
    threads: Option<usize>,
) -> Result<(Film, DepthMap)> {
    let (width, height) = (settings.width, settings.height);
    let (film, views, _) = render_with_views(world, index, settings, threads)
        .map_err(|e| anyhow!("the observer's render failed: {e}"))?;
    let distances = views.values(View::Distance);
    let depth = DepthMap::new(width, height, distances)
        .ok_or_else(|| anyhow!("the observer's distances do not fit its image"))?;
    Ok((film, depth))
}

#[cfg(test)]
mod tests;
