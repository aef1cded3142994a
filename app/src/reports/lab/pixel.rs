//! Section 6, one pixel explained: a pixel with a reflection and a blocked
//! shadow ray (or the one asked for), its ray tree in words and the
//! observer figure of its rays flying through the scene.

use std::sync::Arc;

use anyhow::{Result, anyhow, bail};
use image::RgbImage;
use tracer::render::{Outcome, RayKind, RayTree, RenderSettings};

use super::html::{escape, figure, image, titled_section};
use super::{Lab, Request};
use crate::figures::observer::{self, draw};
use crate::measure::benchmark::Structures;
use crate::reports::ray_tree;

/// Size of the observer figure in pixels.
const FIGURE: (u32, u32) = (640, 480);
/// Candidate pixels tried along each axis when the report chooses.
const CANDIDATES: u32 = 32;

/// The pixel, its tree and its figure.
pub(crate) struct PixelExplained {
    pub(crate) pixel: (u32, u32),
    /// Whether the report chose it (else the user gave it).
    pub(crate) chosen: bool,
    pub(crate) tree: RayTree,
    pub(crate) figure: RgbImage,
}

/// Whether a pixel has both a reflection and a blocked shadow ray, one of
/// them, and how many rays: compared in that order.
type Interest = (bool, bool, usize);

/// What makes a pixel worth explaining: a reflection, a blocked shadow ray,
/// then more rays.
fn interest(tree: &RayTree) -> Interest {
    let reflects = tree.nodes.iter().any(|n| n.kind == RayKind::Reflection);
    let blocked = tree.nodes.iter().any(|n| {
        matches!(
            n.outcome,
            Outcome::Light {
                occluder: Some(_),
                ..
            }
        )
    });
    (reflects && blocked, reflects || blocked, tree.nodes.len())
}

/// Chooses (or checks) the pixel under `settings` and draws its figure.
pub(crate) fn explain(
    request: &Request,
    settings: &RenderSettings,
    structures: &mut Structures,
) -> Result<PixelExplained> {
    let world = &request.world;
    let (w, h) = (settings.width, settings.height);
    let index = structures.get(world, settings.accel, settings.grid_multiplier);
    let (pixel, chosen) = match request.pixel {
        Some((x, y)) if x < w && y < h => ((x, y), false),
        Some((x, y)) => bail!(
            "--pixel {x} {y} is outside the {w} x {h} image measured: x in 0..{}, y in 0..{}",
            w - 1,
            h - 1
        ),
        None => {
            let step_x = (w / CANDIDATES).max(1);
            let step_y = (h / CANDIDATES).max(1);
            let mut best: Option<(Interest, (u32, u32))> = None;
            for y in (step_y / 2..h).step_by(step_y as usize) {
                for x in (step_x / 2..w).step_by(step_x as usize) {
                    let tree = ray_tree::inspect(world, Some(index.clone()), settings, (x, y), 0)?;
                    let score = interest(&tree);
                    if best.is_none_or(|(b, _)| score > b) {
                        best = Some((score, (x, y)));
                    }
                }
            }
            (best.map_or((w / 2, h / 2), |(_, p)| p), true)
        }
    };
    let tree = ray_tree::inspect(world, Some(index.clone()), settings, pixel, 0)?;
    let scene_camera = settings.render_camera(&world.view)?;
    let aspect = FIGURE.1 as f32 / FIGURE.0 as f32;
    let pose = tracer::camera::CameraPose {
        up: scene_camera.basis()[1].into(),
        ..observer::framing(world, &scene_camera, world.view.angle, aspect)
    };
    let observer_settings = observer::render_settings(settings, pose, FIGURE.0, FIGURE.1);
    let observer_camera = observer_settings
        .render_camera(&world.view)
        .map_err(|e| anyhow!("the observer camera: {e}"))?;
    let mut segments = observer::camera_segments(&scene_camera);
    segments.extend(observer::light_segments(world, settings));
    segments.extend(observer::ray_segments(
        &tree,
        observer::stub_length(world),
        0,
    ));
    let (figure, _) = draw::figure(
        world,
        Arc::clone(&index),
        (settings, &scene_camera),
        (&observer_settings, &observer_camera),
        &segments,
        request.encoding,
        request.threads,
    )?;
    Ok(PixelExplained {
        pixel,
        chosen,
        tree,
        figure,
    })
}

pub(crate) fn section(lab: &Lab) -> Result<String> {
    let p = &lab.pixel;
    let (x, y) = p.pixel;
    let why = if p.chosen {
        let (both, either, _) = interest(&p.tree);
        match (both, either) {
            (true, _) => "chosen by the report: it has a reflection and a blocked shadow ray",
            (false, true) => {
                "chosen by the report: no pixel tried has both a reflection and a blocked shadow \
                 ray; this one has one of them"
            }
            _ => {
                "chosen by the report: no pixel tried reflects or is shadowed; this one spawns \
                  the most rays"
            }
        }
    } else {
        "given with --pixel"
    };
    let caption = format!(
        "The rays of pixel ({x}, {y}) seen from outside: eye white, reflection blue, refraction \
         pink, shadow rays yellow (dashed to the occluder when blocked); the scene camera's image \
         on its image plane."
    );
    let body = format!(
        "<p>Pixel ({x}, {y}), {why}. Sample 0, BVH, one sample per pixel, hard shadows, depth \
         {}.</p>\n{}<pre>{}</pre>\n",
        lab.base.max_depth,
        figure(&image(&p.figure, &caption, 640)?, &caption),
        escape(&ray_tree::text(&p.tree))
    );
    Ok(titled_section("pixel", "6. One pixel explained", &body))
}
