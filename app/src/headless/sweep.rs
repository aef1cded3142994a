//! `workbench sweep`: a parameter study from the command line. Prints the
//! table and what it shows, writes the chart; Ctrl-C stops after the frame
//! under way and still prints what was measured.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result, bail};
use tracer::accel::AccelKind;
use tracer::generate::GeneratorName;
use tracer::render::RenderSettings;
use tracer::scene::Scene;

use crate::cli::{SettingsArgs, SweepArgs};
use crate::figures::study_plot;
use crate::image_file::save_png;
use crate::load::Loaded;
use crate::measure::benchmark::{RunOptions, Stop};
use crate::measure::study::{self, Param, Study, StudyEvent, Subject, values};
use crate::reports::bench_table::Format;
use crate::reports::study_table;

/// What Ctrl-C has asked: the first press stops after the frame under
/// way, the second at once.
#[derive(Default)]
struct Interrupt {
    now: AtomicBool,
    after_frame: AtomicBool,
}

impl Interrupt {
    fn press(&self) {
        if self.after_frame.swap(true, Ordering::Relaxed) {
            self.now.store(true, Ordering::Relaxed);
            eprintln!("\nstopping now");
        } else {
            eprintln!("\nstopping after this frame (Ctrl-C again to stop at once)");
        }
    }
}

/// A sweep's frames start one sample per pixel with hard shadows, as
/// `bench` does, unless the command line asks for more.
fn base_settings(scene: &Scene, overrides: &SettingsArgs) -> RenderSettings {
    let mut settings = RenderSettings::from_scene(scene);
    settings.antialiasing = false;
    settings.depth_of_field = false;
    overrides.apply(&mut settings);
    settings
}

pub fn run(args: &SweepArgs) -> Result<()> {
    let (subject, name, base) = subject(args)?;
    let values_text = args
        .values
        .clone()
        .unwrap_or_else(|| args.param.default_values(&base));
    let values =
        values::parse(&values_text).with_context(|| format!("--values `{values_text}`"))?;
    let structures: Vec<AccelKind> = match &args.structures {
        Some(list) => list.clone(),
        None => args.param.default_structures(base.accel),
    };
    let study = Study {
        param: args.param,
        values,
        structures,
        options: RunOptions {
            runs: args.runs.max(1),
            threads: args.threads,
        },
        encoding: args.encoding.encoding(),
        reference_samples: args.reference_spp,
    };
    study.check(&subject)?;
    if let Subject::Document { world, .. } = &subject
        && study.structures.contains(&AccelKind::None)
    {
        let brute = RenderSettings {
            accel: AccelKind::None,
            ..base.clone()
        };
        super::warn_brute_force_with(
            &brute,
            &world.counts,
            "each point renders so; leave `none` out of --structures to measure in seconds",
        );
    }

    let interrupt = Arc::new(Interrupt::default());
    let handler = interrupt.clone();
    ctrlc::set_handler(move || handler.press()).context("cannot catch Ctrl-C")?;

    let format: Format = args.format.into();
    let header = header(&study, &name, &base, args);
    // The header would break CSV and JSON; it goes to stderr for those.
    match format {
        Format::Text | Format::Markdown => println!("{header}\n"),
        Format::Csv | Format::Json => eprintln!("{header}"),
    }
    let stop = Stop {
        now: &interrupt.now,
        after_frame: &interrupt.after_frame,
    };
    let mut progress = progress(&study);
    let outcome = study::run(&study, &subject, stop, &mut progress)
        .with_context(|| format!("cannot sweep {name}"))?;
    let points = &outcome.points;
    print!("{}", study_table::table(study.param, points, format));
    let summary = study_table::summary(study.param, points);
    if let Some(reference) = &outcome.reference {
        eprintln!(
            "error against a reference of N = {} ({} samples per pixel)",
            reference.samples,
            reference.samples.pow(2)
        );
    }
    let summary = summary.join("\n");
    match format {
        Format::Text | Format::Markdown if !summary.is_empty() => println!("\n{summary}"),
        Format::Text | Format::Markdown => {}
        Format::Csv | Format::Json => eprintln!("{summary}"),
    }
    if let Some(path) = &args.plot
        && !points.is_empty()
    {
        write_plot(study.param, points, &name, path)?;
    }
    if outcome.cancelled {
        bail!(
            "interrupted: {} of {} points measured",
            points.len(),
            study.len()
        );
    }
    Ok(())
}

/// The scene or generator to study, its name, and the settings points
/// start from (for a generator, those of its first level).
fn subject(args: &SweepArgs) -> Result<(Subject, String, RenderSettings)> {
    if args.param != Param::Level {
        if args.generator.is_some() {
            bail!("--generator is for --param level; other parameters sweep a scene file");
        }
        let Some(path) = &args.scene else {
            bail!("give a scene file to sweep {} on", args.param);
        };
        let loaded = Loaded::for_command(path, &args.settings.set)?;
        let base = base_settings(&loaded.scene, &args.settings);
        let name = path.display().to_string();
        let subject = Subject::Document {
            scene: Arc::new(loaded.scene),
            world: loaded.world,
            base: base.clone(),
        };
        return Ok((subject, name, base));
    }
    if !args.settings.set.is_empty() {
        bail!("--set edits a scene file; the level study generates its scenes");
    }
    if let Some(scene) = &args.scene {
        bail!(
            "the level study generates its scenes: give --generator instead of {}",
            scene.display()
        );
    }
    let Some(generator) = &args.generator else {
        bail!("--param level needs --generator (e.g. balls)");
    };
    let generator: GeneratorName = generator.parse()?;
    let overrides = args.settings.clone();
    let subject = Subject::Generated {
        generator,
        seed: 0,
        settings: Box::new(move |scene| base_settings(scene, &overrides)),
    };
    let mut base = RenderSettings::default();
    args.settings.apply(&mut base);
    Ok((subject, generator.to_string(), base))
}

fn header(study: &Study, name: &str, base: &RenderSettings, args: &SweepArgs) -> String {
    let structures: Vec<&str> = study.structures.iter().map(|a| a.name()).collect();
    let values: Vec<String> = study.values.iter().map(|&v| values::format(v)).collect();
    let size = if study.param == Param::Level {
        String::new()
    } else {
        format!("{}x{}, ", base.width, base.height)
    };
    format!(
        "{name}: {} = {} for {}; {size}{} run(s) per point, {} thread(s)",
        study.param,
        values.join(", "),
        structures.join(", "),
        study.options.runs,
        args.threads.map_or_else(
            || rayon::current_num_threads().to_string(),
            |t| t.to_string()
        ),
    )
}

/// A progress bar fed by the study's events.
fn progress(study: &Study) -> impl FnMut(StudyEvent) + use<> {
    let runs = study.options.runs.max(1);
    let plan = study.plan();
    let param = study.param;
    let bar = super::progress_bar(plan.len() * runs);
    move |event| match event {
        StudyEvent::Preparing { what, .. } => bar.set_message(what.to_string()),
        StudyEvent::Rendering {
            point,
            run,
            fraction,
        } => {
            let done = (point * runs + run) as f64 + f64::from(fraction);
            bar.set_position((done * super::STEPS as f64) as u64);
            let (accel, value) = plan[point];
            bar.set_message(format!(
                "{}/{} {} {param} = {} (run {}/{runs})",
                point + 1,
                plan.len(),
                accel.name(),
                values::format(value),
                run + 1
            ));
        }
        StudyEvent::Measured { point, .. } if point + 1 == plan.len() => bar.finish_and_clear(),
        StudyEvent::Measured { .. } => {}
    }
}

fn write_plot(param: Param, points: &[study::Point], name: &str, path: &Path) -> Result<()> {
    let title = Path::new(name)
        .file_stem()
        .map_or_else(|| name.to_string(), |s| s.to_string_lossy().into_owned());
    let image = study_plot::chart(param, points, &title)?;
    save_png(&image, path)?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
