//! `workbench observe`: the observer figure, the scene seen from outside
//! with its camera, lights and a pixel's rays, as a PNG (for a report or a
//! slide) and optionally every drawn segment as JSON (for scripts).

use std::sync::Arc;

use anyhow::{Context, Result, anyhow, bail};
use glam::Vec3;
use serde_json::json;
use tracer::accel::{AccelKind, SceneIndex, StructureLayer};
use tracer::camera::CameraPose;
use tracer::render::{RayTree, RenderSettings};

use crate::cli::{MetricsFormat, ObserveArgs};
use crate::figures::observer::draw::{Piece, figure};
use crate::figures::observer::{self, MAX_SEGMENTS, Part, Segment};
use crate::figures::overlay::VisitStep;
use crate::image_file::save_png;
use crate::load::Loaded;
use crate::reports::ray_tree;

pub fn run(args: &ObserveArgs) -> Result<()> {
    let loaded = Loaded::for_command(&args.scene, &args.settings.set)?;
    let world = loaded.world.clone();
    let mut settings = RenderSettings::from_scene(&loaded.scene);
    args.settings.apply(&mut settings);
    settings.validate()?;
    let (width, height) = (settings.width, settings.height);
    let pixel = match args.pixel[..] {
        [x, y] if x < width && y < height => (x, y),
        [x, y] => bail!(
            "--pixel {x} {y} is outside the {width} x {height} image: x in 0..{}, y in 0..{}",
            width - 1,
            height - 1
        ),
        _ => bail!("--pixel takes two numbers, X and Y"),
    };
    let mut pixels = vec![pixel];
    if let Some(pattern) = args.pixels {
        let more = pattern
            .pixels(width, height)
            .map_err(|e| anyhow!("--pixels: {e}"))?;
        pixels.extend(more.into_iter().filter(|p| *p != pixel));
    }
    let pose = observer_pose(args, &world, &settings)?;
    let [figure_width, figure_height] = args.size[..] else {
        bail!("--size takes two numbers, W and H");
    };
    let observer_settings = observer::render_settings(&settings, pose, figure_width, figure_height);
    observer_settings
        .validate()
        .map_err(|e| anyhow!("--size {figure_width} {figure_height}: {e}"))?;
    let observer_camera = observer_settings
        .render_camera(&world.view)
        .map_err(|e| anyhow!("the observer camera (--from, --at, --up): {e}"))?;
    let scene_camera = settings.render_camera(&world.view)?;

    super::warn_brute_force_with(
        &settings,
        &world.counts,
        "the figure and its image plane are traced with a BVH, the pixels' rays as the \
         scene says (add `--accel bvh` to trace those with it too)",
    );
    let stage = super::stage_spinner();
    stage.set_message("building the scene's structure");
    let index = Arc::new(SceneIndex::build(
        &world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    stage.set_message("recording the pixels' rays");
    let mut trees = Vec::new();
    let mut segments = observer::camera_segments(&scene_camera);
    segments.extend(observer::light_segments(&world, &settings));
    let stub = observer::stub_length(&world);
    let mut left_out = 0;
    for &p in &pixels {
        let tree = ray_tree::inspect(&world, Some(index.clone()), &settings, p, args.sample)
            .map_err(|e| anyhow!("cannot record pixel ({}, {}): {e}", p.0, p.1))?;
        let rays = observer::ray_segments(&tree, stub, 0);
        if segments.len() + rays.len() > MAX_SEGMENTS && !trees.is_empty() {
            left_out += 1;
            continue;
        }
        segments.extend(rays);
        trees.push(tree);
    }
    if let Some(layer) = args.overlay {
        let visits = trees.first().map_or(&[][..], |t| &t.eye_visits[..]);
        let layer = structure_layer(layer, index.kind())?;
        segments.extend(observer::structure_segments(
            &index,
            Some(layer),
            visits,
            VisitStep::All,
        ));
    }

    // The figure and its image plane are traced with a BVH whatever the
    // scene's structure (`draw::figure`): the same image, in seconds.
    stage.set_message("tracing the figure and the image on its plane");
    let (figure, pieces) = figure(
        &world,
        index,
        (&settings, &scene_camera),
        (&observer_settings, &observer_camera),
        &segments,
        args.encoding.encoding(),
        args.threads,
    )?;
    stage.finish_and_clear();
    save_png(&figure, &args.output)?;

    match args.format {
        MetricsFormat::Text => print!(
            "{}",
            summary(args, &trees, &segments, &pieces, pose, left_out)
        ),
        MetricsFormat::Json => println!(
            "{}",
            serde_json::to_string_pretty(&report(&trees, &segments, &pieces, pose))
                .context("cannot write the JSON")?
        ),
    }
    Ok(())
}

/// The observer's pose: `--from`/`--at` (and `--up`), checked, or framed
/// on the scene.
fn observer_pose(
    args: &ObserveArgs,
    world: &tracer::world::World,
    settings: &RenderSettings,
) -> Result<CameraPose> {
    let aspect = args.size[1] as f32 / args.size[0].max(1) as f32;
    let scene_camera = settings.render_camera(&world.view)?;
    let vector = |v: &Option<Vec<f32>>| v.as_ref().map(|v| Vec3::new(v[0], v[1], v[2]));
    let up = vector(&args.up).unwrap_or_else(|| scene_camera.basis()[1].into());
    let pose = match (vector(&args.from), vector(&args.at)) {
        (Some(from), Some(at)) => {
            if (from - at).length() < 1e-6 {
                bail!(
                    "--from {from} and --at {at} are the same point: the observer must look \
                     somewhere"
                );
            }
            if (at - from)
                .normalize()
                .cross(up.normalize_or_zero())
                .length()
                < 1e-4
            {
                bail!(
                    "--up {up} is along the observer's view from {from} to {at}: give an up \
                     across it"
                );
            }
            CameraPose { from, at, up }
        }
        _ => CameraPose {
            up,
            ..observer::framing(world, &scene_camera, world.view.angle, aspect)
        },
    };
    Ok(pose)
}

/// `--overlay`'s layer for the structure the render uses.
fn structure_layer(layer: StructureLayer, kind: AccelKind) -> Result<StructureLayer> {
    let fits = matches!(
        (layer, kind),
        (StructureLayer::Grid, AccelKind::Grid)
            | (
                StructureLayer::BvhDepth(_) | StructureLayer::BvhLeaves,
                AccelKind::Bvh
            )
    );
    if fits {
        Ok(layer)
    } else {
        bail!(
            "--overlay shows the structure the render uses, here {}: add --accel {}",
            kind.name(),
            match layer {
                StructureLayer::Grid => "grid",
                _ => "bvh",
            }
        )
    }
}

/// What the figure shows, for a person.
fn summary(
    args: &ObserveArgs,
    trees: &[RayTree],
    segments: &[Segment],
    pieces: &[Piece],
    pose: CameraPose,
    left_out: usize,
) -> String {
    let rays: usize = trees.iter().map(|t| t.nodes.len()).sum();
    let hidden = pieces.iter().filter(|p| p.hidden).count();
    let mut text = format!(
        "{} -> {} ({} x {} from {} looking at {})\n{} pixel(s), {rays} rays; {} segments \
         drawn in {} pieces, {hidden} of them hidden behind surfaces\n",
        args.scene.display(),
        args.output.display(),
        args.size[0],
        args.size[1],
        pose.from,
        pose.at,
        trees.len(),
        segments.len(),
        pieces.len()
    );
    if left_out > 0 {
        text += &format!(
            "{left_out} more pixel(s) left out: the figure draws at most {MAX_SEGMENTS} segments\n"
        );
    }
    text
}

/// Every drawn piece with what it is, for scripts.
fn report(
    trees: &[RayTree],
    segments: &[Segment],
    pieces: &[Piece],
    pose: CameraPose,
) -> serde_json::Value {
    let triple = |v: glam::Vec3A| [v.x, v.y, v.z];
    let pieces: Vec<serde_json::Value> = pieces
        .iter()
        .map(|piece| {
            let segment = &segments[piece.segment];
            let mut entry = serde_json::to_value(segment.part).unwrap_or_default();
            if let Some(object) = entry.as_object_mut() {
                object.insert("segment".into(), json!(piece.segment));
                object.insert("side".into(), json!(segment.side));
                object.insert("phase".into(), json!(segment.phase));
                if matches!(segment.part, Part::Ray { .. } | Part::BlockedShadow) {
                    object.insert("depth".into(), json!(segment.depth));
                }
                object.insert("from".into(), json!(triple(piece.ends[0])));
                object.insert("to".into(), json!(triple(piece.ends[1])));
                object.insert("hidden".into(), json!(piece.hidden));
            }
            entry
        })
        .collect();
    json!({
        "observer": {
            "from": [pose.from.x, pose.from.y, pose.from.z],
            "at": [pose.at.x, pose.at.y, pose.at.z],
            "up": [pose.up.x, pose.up.y, pose.up.z],
        },
        "pixels": trees.iter().map(|t| json!({"x": t.x, "y": t.y, "rays": t.nodes.len()})).collect::<Vec<_>>(),
        "segments": pieces,
    })
}
