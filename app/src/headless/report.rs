//! `workbench report`: the lab report of a scene as one HTML page, with a
//! progress bar; Ctrl-C stops and writes nothing.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use tracer::render::RenderSettings;

use crate::cli::ReportArgs;
use crate::load::Loaded;
use crate::measure::benchmark::MATRIX_SAMPLES;
use crate::reports::lab::{self, Request};

pub fn run(args: &ReportArgs) -> Result<()> {
    let start = Instant::now();
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
