//! The observer figure as a PNG (`workbench observe`): the observer's
//! render, the scene camera's image on its image plane, and the figure's
//! segments over them, solid where the observer sees them and faint where
//! a surface hides them.

use std::sync::Arc;

use anyhow::Result;
use glam::{Vec2, Vec3A};
use image::{Rgb, RgbImage};
use tracer::accel::SceneIndex;
use tracer::camera::Camera;
use tracer::render::{Encoding, RenderSettings, render};
use tracer::world::World;

use super::{Part, Segment, VIEW_ACCEL, render_with_depth, style};
use crate::figures::overlay::line_pixels;
use crate::figures::projection::{DepthMap, Projector};

/// How much of a hidden segment's colour shows through what hides it.
const HIDDEN_ALPHA: f32 = 0.3;
/// How much of the scene camera's image shows on its image plane.
const PLANE_ALPHA: f32 = 0.7;
/// Pieces a segment is cut into to find where it is hidden.
const PIECES: usize = 24;

/// One drawn piece of a segment, for the JSON report.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Piece {
    /// Which segment of the figure it belongs to.
    pub(crate) segment: usize,
    pub(crate) ends: [Vec3A; 2],
    pub(crate) hidden: bool,
}

/// A camera and the settings it renders with.
pub(crate) type Viewer<'a> = (&'a RenderSettings, &'a Camera);

/// The whole figure: `world` rendered from the observer (its settings from
/// [`super::render_settings`]), the scene's own render painted on its image
/// plane, and `segments` drawn over both; with the pieces drawn.
pub(crate) fn figure(
    world: &Arc<World>,
    index: Arc<SceneIndex>,
    (scene_settings, scene_camera): Viewer,
    (observer_settings, observer_camera): Viewer,
    segments: &[Segment],
    encoding: Encoding,
    threads: Option<usize>,
) -> Result<(RgbImage, Vec<Piece>)> {
    // The figure is an illustration, not the experiment: traced with the
    // view's BVH whatever structure the scene asks for.
    let index = if index.matches(VIEW_ACCEL, scene_settings.grid_multiplier) {
        index
    } else {
        Arc::new(SceneIndex::build(
            &world.shapes,
            VIEW_ACCEL,
            scene_settings.grid_multiplier,
        ))
    };
    let (film, depth) = render_with_depth(
        world.clone(),
        index.clone(),
        observer_settings.clone(),
        threads,
    )?;
    let mut image = film.to_image(encoding);
    let image_settings = RenderSettings {
        accel: VIEW_ACCEL,
        ..scene_settings.clone()
    };
    let (scene_film, _) = render(world.clone(), index, image_settings, threads)?;
    let scene_image = scene_film.to_image(encoding);
    paint_image_plane(
        &mut image,
        observer_camera,
        &depth,
        scene_camera,
        &scene_image,
    );
    let projector = Projector::new(observer_camera);
    let pieces = draw_segments(&mut image, &projector, &depth, segments, world);
    Ok((image, pieces))
}

/// Paints `render` (the scene camera's image) onto its image plane as the
/// observer sees it: each observer pixel whose ray meets the plane inside
/// the image, in front of the surface it sees, takes the image's pixel.
pub(crate) fn paint_image_plane(
    figure: &mut RgbImage,
    observer: &Camera,
    depth: &DepthMap,
    scene_camera: &Camera,
    render: &RgbImage,
) {
    let [right, up, forward] = scene_camera.basis();
    let (w, h) = (scene_camera.width() as f32, scene_camera.height() as f32);
    let origin = scene_camera.view_plane_point(0.0, 0.0);
    let across = scene_camera.view_plane_point(w, 0.0) - origin;
    let down = scene_camera.view_plane_point(0.0, h) - origin;
    let eye = observer.eye();
    for y in 0..figure.height() {
        for x in 0..figure.width() {
            let through = observer.view_plane_point(x as f32 + 0.5, y as f32 + 0.5);
            let dir = (through - eye).normalize();
            let facing = dir.dot(forward);
            if facing.abs() < 1e-6 {
                continue;
            }
            let t = (origin - eye).dot(forward) / facing;
            if t <= 0.0 || depth.nearer_than(x, y, t) {
                continue;
            }
            let p = eye + dir * t - origin;
            let (u, v) = (p.dot(right) / across.length(), p.dot(-up) / down.length());
            if !(0.0..1.0).contains(&u) || !(0.0..1.0).contains(&v) {
                continue;
            }
            let source = render.get_pixel(
                ((u * render.width() as f32) as u32).min(render.width() - 1),
                ((v * render.height() as f32) as u32).min(render.height() - 1),
            );
            let target = figure.get_pixel_mut(x, y);
            *target = blend(*target, source.0, PLANE_ALPHA);
        }
    }
}

/// Draws `segments` onto `figure` through `projector`: solid where visible,
/// faint where `depth` says a surface hides them. Returns the pieces drawn.
pub(crate) fn draw_segments(
    figure: &mut RgbImage,
    projector: &Projector<'_>,
    depth: &DepthMap,
    segments: &[Segment],
    world: &World,
) -> Vec<Piece> {
    let mut pieces = Vec::new();
    for (index, segment) in segments.iter().enumerate() {
        let Some(ends) = projector.clip(segment.ends[0], segment.ends[1]) else {
            continue;
        };
        let (colour, dashed) = style(segment, world);
        let thick = matches!(segment.part, Part::Ray { .. } | Part::BlockedShadow);
        for (ends, hidden) in depth.split(projector, ends, PIECES) {
            pieces.push(Piece {
                segment: index,
                ends,
                hidden,
            });
            let Some([a, b]) = projector.segment(ends[0], ends[1]) else {
                continue;
            };
            let alpha = if hidden { HIDDEN_ALPHA } else { 1.0 };
            line(figure, a, b, colour, alpha, dashed);
            if thick {
                // Rays two pixels wide, so they read on a busy render.
                let across = (b - a).perp().normalize_or_zero();
                line(figure, a + across, b + across, colour, alpha, dashed);
            }
        }
    }
    pieces
}

/// A line of `colour` at `alpha` over what is there, dashed in 6-pixel
/// strokes when asked.
fn line(figure: &mut RgbImage, a: Vec2, b: Vec2, colour: [u8; 3], alpha: f32, dashed: bool) {
    let pixels = line_pixels(a, b, figure.width(), figure.height());
    for (i, (x, y)) in pixels.into_iter().enumerate() {
        if dashed && (i / 6) % 2 == 1 {
            continue;
        }
        let target = figure.get_pixel_mut(x, y);
        *target = blend(*target, colour, alpha);
    }
}

fn blend(under: Rgb<u8>, over: [u8; 3], alpha: f32) -> Rgb<u8> {
    Rgb([0, 1, 2].map(|c| {
        (f32::from(under.0[c]) * (1.0 - alpha) + f32::from(over[c]) * alpha).round() as u8
    }))
}
