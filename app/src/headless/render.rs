//! `workbench render`: one image, headless, with the scene's own settings
//! and the command line's overrides.

use std::io::IsTerminal;
use std::sync::Arc;
use std::time::Duration;

use anyhow::{Context, Result};
use tracer::accel::{AccelKind, SceneIndex, StructureLayer, Visit};
use tracer::render::{Finished, JobOptions, JobState, RenderJob, RenderSettings, ViewSummary};
use tracer::world::World;

use crate::cli::{RenderArgs, StatsFormat};
use crate::figures::{heat_map, overlay};
use crate::image_file::{is_exr, save_exr, save_png};
use crate::load::Loaded;
use crate::reports::render_stats;
use crate::reports::{ray_tree, view_summary};

pub fn run(args: &RenderArgs) -> Result<()> {
    let loaded = Loaded::for_command(&args.scene, &args.settings.set)?;
    if let Some(path) = &args.save_scene {
        let folder = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => std::path::Path::new("."),
        };
        std::fs::write(path, tracer::scene::write_p3f_in(&loaded.scene, folder))
            .with_context(|| format!("cannot write the scene to {}", path.display()))?;
        eprintln!("wrote {}", path.display());
    }
    let mut settings = RenderSettings::from_scene(&loaded.scene);
    args.settings.apply(&mut settings);
    let encoding = args.encoding.encoding();
    super::warn_brute_force(&settings, &loaded.world.counts);

    let on_pass = match &args.progressive_out {
        Some(dir) => {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create folder {}", dir.display()))?;
            let dir = dir.clone();
            let listener: tracer::render::PassListener = Box::new(move |pass, film, _| {
                let path = dir.join(format!("pass_{pass:04}.png"));
                if let Err(e) = save_png(&film.to_image(encoding), &path) {
                    eprintln!("warning: {e:#}");
                }
            });
            Some(listener)
        }
        None => None,
    };
    if is_exr(&args.output) && (args.view.view().is_some() || args.overlay.is_some()) {
        anyhow::bail!(
            "--view and --overlay draw on a PNG; {} is OpenEXR, which holds the linear film only",
            args.output.display()
        );
    }
    // The overlay's structure, built once: the render reuses it when it
    // traces with the same structure.
    let overlay = args.overlay.map(|layer| {
        let accel = overlay_accel(layer);
        let m = settings.grid_multiplier;
        (
            layer,
            Arc::new(SceneIndex::build(&loaded.world.shapes, accel, m)),
        )
    });
    let job = RenderJob::start(
        loaded.world.clone(),
        overlay.as_ref().map(|(_, index)| index.clone()),
        settings.clone(),
        JobOptions {
            threads: args.threads,
            on_pass,
            views: args.view.view().is_some(),
            // The bytes of the PNG that shows the render itself, made
            // tile by tile by the render threads.
            finished_image: (!is_exr(&args.output) && args.view.view().is_none())
                .then_some(encoding),
            // Nothing reads the film when the image is made tile by tile,
            // unless passes are saved (`on_pass`, which keeps it anyway).
            image_only: true,
            ..JobOptions::default()
        },
    )
    // The message only: the error's source repeats it, and `{:#}` would
    // print it twice.
    .map_err(|e| anyhow::anyhow!("cannot render {}: {e}", args.scene.display()))?;

    if std::io::stderr().is_terminal() {
        show_progress(&job, &settings);
    }
    let Finished {
        film,
        views,
        image: finished,
        stats,
        state,
    } = job.wait_with_image();
    if let JobState::Failed(message) = state {
        anyhow::bail!("rendering {} failed: {message}", args.scene.display());
    }
    let view = args.view.view().zip(views.as_ref()).map(|(view, film)| {
        let values = film.values(view);
        let heat = args.view.heatmap(&[&values]);
        (view, film, ViewSummary::of(&values), heat)
    });
    if is_exr(&args.output) {
        // The linear film, before any clamping or encoding.
        save_exr(&film.to_linear_image(), &args.output)?;
    } else {
        let mut image = match &view {
            Some((v, film, _, heat)) => {
                heat_map::view_image(film, *v, heat).context("the view has no image")?
            }
            None => finished.unwrap_or_else(|| film.to_image(encoding)),
        };
        if let Some((layer, index)) = &overlay {
            let world = &loaded.world;
            let camera = settings
                .render_camera(&world.view)
                .with_context(|| format!("cannot draw the overlay on {}", args.scene.display()))?;
            overlay::draw_wireframe(&mut image, &camera, &index.wireframe(*layer));
            if let Some(pixel) = &args.pixel {
                let visits = eye_visits(args, &loaded.world, index, &settings, pixel)?;
                overlay::draw_visits(&mut image, &camera, &visits);
            }
        }
        match &view {
            Some((v, _, _, heat)) if v.is_scalar() => {
                save_png(&heat_map::with_legend(&image, heat), &args.output)?
            }
            _ => save_png(&image, &args.output)?,
        }
    }
    match args.stats {
        Some(StatsFormat::Json) => {
            let mut json = render_stats::json_value(&stats, &loaded.world.counts);
            if let Some((v, _, summary, heat)) = &view {
                json["view"] = view_summary::summary_json(*v, summary.as_ref(), heat);
            }
            println!(
                "{}",
                serde_json::to_string_pretty(&json).unwrap_or_default()
            );
        }
        None => {
            println!(
                "{} -> {}\n{}",
                args.scene.display(),
                args.output.display(),
                render_stats::summary(&stats, &loaded.world.counts)
            );
            if let Some((v, _, summary, heat)) = &view {
                println!("{}", view_summary::describe(*v, summary.as_ref(), heat));
            }
        }
    }
    Ok(())
}

/// The structure an overlay layer draws.
fn overlay_accel(layer: StructureLayer) -> AccelKind {
    match layer {
        StructureLayer::Grid => AccelKind::Grid,
        _ => AccelKind::Bvh,
    }
}

/// What `--pixel`'s eye ray visited in the overlay's structure `index`
/// (the same rays whatever the structure: only what they visit differs).
fn eye_visits(
    args: &RenderArgs,
    world: &Arc<World>,
    index: &Arc<SceneIndex>,
    settings: &RenderSettings,
    pixel: &[u32],
) -> Result<Vec<Visit>> {
    let [x, y] = pixel[..] else {
        anyhow::bail!("--pixel takes two numbers, X and Y");
    };
    let mut settings = settings.clone();
    settings.accel = index.kind();
    let tree = ray_tree::inspect(world, Some(index.clone()), &settings, (x, y), args.sample)
        .with_context(|| format!("cannot inspect a pixel of {}", args.scene.display()))?;
    Ok(tree.eye_visits)
}

/// A progress bar on stderr, counting eye rays against the target.
fn show_progress(job: &RenderJob, settings: &RenderSettings) {
    let total =
        settings.width as u64 * settings.height as u64 * settings.samples_per_pixel() as u64;
    let bar = indicatif::ProgressBar::new(total);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {wide_bar} {percent}% {msg}",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    while !job.is_finished() {
        let stats = job.stats();
        bar.set_position(stats.counters.eye_rays);
        bar.set_message(format!(
            "pass {}/{}",
            stats.passes_done, stats.passes_target
        ));
        std::thread::sleep(Duration::from_millis(100));
    }
    bar.finish_and_clear();
}
