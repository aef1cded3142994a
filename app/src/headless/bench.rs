//! `workbench bench`: time frames of a scene, one row per acceleration
//! structure or the course's whole timing matrix, as a table or JSON.

use std::sync::atomic::AtomicBool;

use anyhow::{Context, Result, bail};
use tracer::accel::AccelKind;
use tracer::render::RenderSettings;

use crate::cli::{BenchArgs, TableFormat};
use crate::image_file::save_png;
use crate::load::Loaded;
use crate::measure::benchmark::{self, Measurement, RunOptions};
use crate::measure::ray_cast::{self, RayBenchOptions};
use crate::measure::to_error::{self, ToErrorPlan};
use crate::reports::{
    self,
    bench_table::{Columns, Format, table},
};

pub fn run(args: &BenchArgs) -> Result<()> {
    let loaded = Loaded::for_command(&args.scene, &args.settings.set)?;
    let mut settings = benchmark::frame_settings(&loaded.scene);
    if args.to_error {
        // The target is the error of the report's N unless --spp says.
        settings.samples = benchmark::MATRIX_SAMPLES;
    }
    args.settings.apply(&mut settings);
    if args.rays {
        return rays(args, &loaded, &settings);
    }
    if args.to_error {
        return to_error(args, &loaded, settings);
    }
    let encoding = args.encoding.encoding();
    let accels: Vec<AccelKind> = match (&args.structures, args.settings.accel) {
        (Some(list), None) => list.clone(),
        (None, Some(accel)) => vec![accel],
        (None, None) => AccelKind::ALL.to_vec(),
        (Some(_), Some(_)) => {
            bail!("--accel and --structures both choose what to time: give one of them")
        }
    };
    let (cases, layout) = if args.matrix {
        if args.settings.spp.is_none() {
            settings.samples = benchmark::MATRIX_SAMPLES;
        }
        (
            benchmark::matrix(&settings, &loaded.scene.view, &accels, encoding),
            Columns::Matrix,
        )
    } else {
        (
            benchmark::structures(&settings, &accels, encoding),
            Columns::Structures,
        )
    };
    let runs = args.runs.max(1);
    let format: Format = args.format.into();
    // The header would break CSV and JSON; it goes to stderr for those.
    let header = format!(
        "{}: {}x{}, N = {}, depth {}, {} run(s) per row, {} thread(s)",
        args.scene.display(),
        settings.width,
        settings.height,
        settings.samples,
        settings.max_depth,
        runs,
        args.threads.map_or_else(
            || rayon::current_num_threads().to_string(),
            |t| t.to_string()
        ),
    );
    match format {
        Format::Text | Format::Markdown => println!("{header}\n"),
        Format::Csv | Format::Json => eprintln!("{header}"),
    }
    if let Some(dir) = &args.images {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create folder {}", dir.display()))?;
    }
    let labels = cases.iter().map(|c| c.label.clone()).collect();
    let mut progress = super::runner_progress(labels, runs);
    let outcome = benchmark::run(
        &loaded.world,
        &cases,
        RunOptions {
            runs,
            threads: args.threads,
        },
        &AtomicBool::new(false),
        &mut progress,
    )
    .with_context(|| format!("cannot benchmark {}", args.scene.display()))?;
    if let Some(dir) = &args.images {
        for m in &outcome.measurements {
            save_image(m, dir, args.thumbnail)?;
        }
    }
    print!("{}", table(&outcome.measurements, layout, format));
    Ok(())
}

/// `bench --rays`: one structure's eye and shadow rays, as text or JSON.
fn rays(args: &BenchArgs, loaded: &Loaded, settings: &RenderSettings) -> Result<()> {
    let accel = match args.structures.as_deref() {
        None => AccelKind::Bvh,
        Some([one]) => *one,
        Some(_) => bail!("--rays measures one structure: give one to --structure"),
    };
    let camera = settings
        .render_camera(&loaded.world.view)
        .with_context(|| format!("cannot set up the camera of {}", args.scene.display()))?;
    let options = RayBenchOptions {
        accel,
        grid_multiplier: settings.grid_multiplier,
        runs: args.runs,
        threads: args.threads,
    };
    let bench = ray_cast::run(&loaded.world, &camera, &options)
        .with_context(|| format!("cannot cast the rays of {}", args.scene.display()))?;
    let scene = args.scene.display().to_string();
    match args.format {
        TableFormat::Text => print!("{}", bench.text(&scene)),
        TableFormat::Json => println!("{}", bench.json(&scene)),
        TableFormat::Md | TableFormat::Csv => bail!("--rays prints text or json"),
    }
    Ok(())
}

/// `bench --to-error`: the time uniform and adaptive sampling take to
/// reach one error, as text or JSON.
fn to_error(args: &BenchArgs, loaded: &Loaded, mut settings: RenderSettings) -> Result<()> {
    if args.structures.as_ref().is_some_and(|s| s.len() > 1) {
        bail!("--to-error measures one structure: give one to --structure");
    }
    if let Some([accel]) = args.structures.as_deref() {
        settings.accel = *accel;
    }
    if !matches!(args.format, TableFormat::Text | TableFormat::Json) {
        bail!("--to-error prints text or json");
    }
    // The reference and both sides anti-alias whatever the flags say: the
    // header describes what is measured.
    settings.antialiasing = true;
    let plan = ToErrorPlan {
        reference_samples: args
            .reference_spp
            .unwrap_or_else(|| to_error::default_reference_samples(settings.samples)),
        target_mse: args.target_mse,
        noise_threshold: args.settings.noise_threshold,
        runs: args.runs.max(1),
        threads: args.threads,
        encoding: args.encoding.encoding(),
        base: settings,
    };
    let header = format!(
        "{}: {}x{}, {}, {} timed run(s) per side, {} thread(s)",
        args.scene.display(),
        plan.base.width,
        plan.base.height,
        crate::describe::describe(&plan.base, &loaded.scene.view),
        plan.runs,
        args.threads.map_or_else(
            || rayon::current_num_threads().to_string(),
            |t| t.to_string()
        ),
    );
    eprintln!("{header}");
    let measured = to_error::measure(&loaded.world, &plan, &mut |attempt| {
        eprintln!(
            "  {}: {:.1} spp, MSE {:.3}, FLIP {:.4}, {:.3} s",
            attempt.label,
            attempt.spp_mean,
            attempt.metrics.mse,
            attempt.metrics.flip,
            attempt.time.as_secs_f64()
        )
    })
    .with_context(|| format!("cannot measure {}", args.scene.display()))?;
    match args.format {
        TableFormat::Json => println!(
            "{}",
            serde_json::to_string_pretty(&reports::to_error::json(&measured)).unwrap_or_default()
        ),
        _ => print!("{header}\n{}", reports::to_error::text(&measured)),
    }
    Ok(())
}

/// Writes a row's image as `DIR/<stem>.png`, scaled down to `thumbnail`.
fn save_image(m: &Measurement, dir: &std::path::Path, thumbnail: Option<u32>) -> Result<()> {
    let path = dir.join(format!("{}.png", m.case.file_stem()));
    match thumbnail {
        Some(side) if side < m.image.width().max(m.image.height()) => {
            let scale = f64::from(side) / f64::from(m.image.width().max(m.image.height()));
            let size = |v: u32| ((f64::from(v) * scale).round() as u32).max(1);
            let small =
                image::imageops::thumbnail(&m.image, size(m.image.width()), size(m.image.height()));
            save_png(&small, &path)
        }
        _ => save_png(&m.image, &path),
    }
}
