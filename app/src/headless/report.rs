//! `workbench report`: the lab report of a scene as one HTML page, with a
//! progress bar; Ctrl-C stops and writes nothing.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use tracer::render::RenderSettings;

use crate::cli::{ReportArgs, SettingsArgs};
use crate::load::Loaded;
use crate::measure::benchmark::MATRIX_SAMPLES;
use crate::reports::lab::{self, Request};

/// The settings flags a report refuses: it measures every structure, with
/// and without shadows, soft shadows, anti-aliasing and depth of field,
/// sampling uniformly as the course did, so these would change nothing.
fn refused(settings: &SettingsArgs) -> Option<&'static str> {
    [
        ("--accel", settings.accel.is_some()),
        ("--aa", settings.aa),
        ("--no-aa", settings.no_aa),
        ("--soft-shadows", settings.soft_shadows),
        ("--no-shadows", settings.no_shadows),
        ("--dof", settings.dof),
        ("--sampling", settings.sampling.is_some()),
        ("--noise-threshold", settings.noise_threshold.is_some()),
        ("--min-spp", settings.min_spp.is_some()),
        ("--max-spp", settings.max_spp.is_some()),
    ]
    .into_iter()
    .find_map(|(flag, given)| given.then_some(flag))
}

pub fn run(args: &ReportArgs) -> Result<()> {
    let start = Instant::now();
    if let Some(flag) = refused(&args.settings) {
        bail!(
            "report does not take {flag}: it measures every structure, with and without \
             shadows, soft shadows, anti-aliasing and depth of field, sampling uniformly \
             (--spp sets N, --aperture and --focal the lens)"
        );
    }
    let loaded = Loaded::for_command(&args.scene, &args.settings.set)?;
    let mut base = RenderSettings::from_scene(&loaded.scene);
    args.settings.apply(&mut base);
    // The course measured its table with N = 4, not the scene's own N.
    if args.settings.spp.is_none() {
        base.samples = MATRIX_SAMPLES;
    }
    base.validate()?;
    let pixel = match args.pixel.as_deref() {
        None => None,
        Some(&[x, y]) => Some((x, y)),
        Some(_) => bail!("--pixel takes two numbers, X and Y"),
    };
    let request = Request {
        scene_name: args.scene.display().to_string(),
        scene: Arc::new(loaded.scene),
        world: loaded.world,
        base,
        edits: args.settings.set.clone(),
        runs: args.runs.max(1),
        threads: args.threads,
        encoding: args.encoding.encoding(),
        pixel,
        quick: args.quick,
    };

    let cancel = Arc::new(AtomicBool::new(false));
    let handler = cancel.clone();
    ctrlc::set_handler(move || {
        handler.store(true, Ordering::Relaxed);
        eprintln!("\nstopping: nothing will be written");
    })
    .context("cannot catch Ctrl-C")?;
    let (measured, runs) = request.measured();
    println!(
        "{}: {}x{}, N = {}, {runs} run(s) per time, {} thread(s){}",
        request.scene_name,
        measured.width,
        measured.height,
        measured.samples,
        request.threads_used(),
        if request.quick { ", quick" } else { "" }
    );

    let bar = super::progress_bar(1);
    let steps = super::STEPS as f32;
    let lab = lab::measure(&request, &cancel, &mut |p| {
        bar.set_position((p.fraction * steps) as u64);
        bar.set_message(p.doing.clone());
    })
    .with_context(|| format!("cannot measure {}", args.scene.display()))?;
    bar.finish_and_clear();
    let Some(lab) = lab else {
        bail!("interrupted: {} was not written", args.output.display());
    };
    let page = lab::page(&lab)?;
    if let Some(path) = &args.json {
        lab::write_atomically(path, &lab::matrix_json(&lab))?;
    }
    lab::write_atomically(&args.output, &page)?;
    println!(
        "wrote {} ({} KB) in {:.1} s",
        args.output.display(),
        page.len().div_ceil(1024),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
