//! `workbench bench`: build each acceleration structure over a scene and
//! time frames with it, so the structures compare on the same work.

use std::sync::Arc;
use std::time::Duration;

use anyhow::{Context, Result};
use tracer::accel::{AccelKind, SceneIndex};
use tracer::render::{RenderSettings, render};

use crate::cli::BenchArgs;
use crate::load::load_scene;
use crate::report::si;

/// One structure's measurements.
struct Row {
    kind: AccelKind,
    build: Duration,
    memory: usize,
    frame_median: Duration,
    frame_min: Duration,
    frame_max: Duration,
    rays: u64,
    tests_per_ray: f64,
    nodes_per_ray: f64,
}

pub fn run(args: &BenchArgs) -> Result<()> {
    let loaded = load_scene(&args.scene)?;
    let mut settings = RenderSettings::from_scene(&loaded.scene);
    // A benchmark frame is one sample per pixel with hard shadows unless
    // the command line asks for more.
    settings.antialiasing = false;
    settings.depth_of_field = false;
    args.settings.apply(&mut settings);
    let runs = args.runs.max(1);
    println!(
        "{}: {}x{}, {} samples/pixel, soft shadows {}, depth {}, {} run(s) per structure, {} thread(s)",
        args.scene.display(),
        settings.width,
        settings.height,
        settings.samples_per_pixel(),
        if settings.soft_shadows { "on" } else { "off" },
        settings.max_depth,
        runs,
        args.threads.map_or_else(
            || rayon::current_num_threads().to_string(),
            |t| t.to_string()
        ),
    );
    let kinds: Vec<AccelKind> = match &args.structures {
        Some(list) => list.iter().map(|&a| a.into()).collect(),
        None => vec![AccelKind::None, AccelKind::Grid, AccelKind::Bvh],
    };
    let mut rows = Vec::new();
    for kind in kinds {
        let index = Arc::new(SceneIndex::build(
            &loaded.world.shapes,
            kind,
            settings.grid_multiplier,
        ));
        let settings = RenderSettings {
            accel: kind,
            ..settings.clone()
        };
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..runs {
            let (_, stats) = render(
                loaded.world.clone(),
                index.clone(),
                settings.clone(),
                args.threads,
            )
            .with_context(|| format!("cannot render {}", args.scene.display()))?;
            times.push(stats.render_time);
            last = Some(stats);
        }
        let stats = last.context("no run")?;
        times.sort_unstable();
        let rays = stats.counters.total_rays();
        rows.push(Row {
            kind,
            build: index.build_time(),
            memory: index.info().memory_bytes,
            frame_median: times[times.len() / 2],
            frame_min: times[0],
            frame_max: times[times.len() - 1],
            rays,
            tests_per_ray: stats.counters.intersection_tests as f64 / rays.max(1) as f64,
            nodes_per_ray: stats.counters.nodes_visited as f64 / rays.max(1) as f64,
        });
    }
    print_table(&rows);
    Ok(())
}

fn print_table(rows: &[Row]) {
    println!(
        "{:<6} {:>10} {:>10} {:>12} {:>17} {:>9} {:>11} {:>11} {:>11}",
        "accel",
        "build ms",
        "memory",
        "frame ms",
        "min..max ms",
        "rays",
        "rays/s",
        "tests/ray",
        "nodes/ray"
    );
    for r in rows {
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        println!(
            "{:<6} {:>10.2} {:>10} {:>12.1} {:>17} {:>9} {:>11} {:>11.2} {:>11.2}",
            format!("{:?}", r.kind).to_lowercase(),
            ms(r.build),
            format!("{}B", si(r.memory as f64)),
            ms(r.frame_median),
            format!("{:.1}..{:.1}", ms(r.frame_min), ms(r.frame_max)),
            si(r.rays as f64),
            si(r.rays as f64 / r.frame_median.as_secs_f64().max(1e-9)),
            r.tests_per_ray,
            r.nodes_per_ray,
        );
    }
}
