//! `workbench compare`: one scene, two settings (or one and a reference
//! image), one A | B | difference PNG and the times and metrics of both
//! sides.

use std::sync::atomic::AtomicBool;

use anyhow::{Context, Result};
use tracer::render::{View, ViewSummary};

use crate::cli::{CompareArgs, MetricsFormat};
use crate::compare_side::{SideSetup, side_from_flags};
use crate::describe::si;
use crate::figures::heat_map;
use crate::image_file::save_png;
use crate::load::Loaded;
use crate::measure::ab::{self, Heatmap, ImageComparison, RenderComparison, SideOptions};
use crate::measure::benchmark::Measurement;
use crate::reports::view_summary;

pub fn run(args: &CompareArgs) -> Result<()> {
    let loaded = Loaded::for_command(&args.scene, &args.settings.set)?;
    let side = |name: &str, flags: &str| {
        side_from_flags(&loaded, name, flags, &args.settings, &args.encoding)
    };
    let a = side("a", &args.a)?;
    super::warn_brute_force(&a.case.settings, &a.world.counts);
    let heatmap = Heatmap::from(args.heatmap);
    if let Some(path) = &args.b_image {
        if args.view.view().is_some() {
            anyhow::bail!(
                "--view compares the views of two renders; it does not work with --b-image"
            );
        }
        return against_image(args, a, path, heatmap);
    }
    let b = side("b", &args.b)?;
    super::warn_brute_force(&b.case.settings, &b.world.counts);
    let mut progress = super::runner_progress(vec!["A".into(), "B".into()], 1);
    let options = SideOptions {
        threads: args.threads,
        views: args.view.view().is_some(),
        b_matches: args.b_matches,
    };
    let comparison = ab::run(
        [&a.world, &b.world],
        a.case,
        b.case,
        options,
        heatmap,
        &AtomicBool::new(false),
        &mut progress,
    );
    let mut comparison = finished(comparison, args)?;
    comparison.labels = with_edits(comparison.labels, (&a.edits, &b.edits));
    let c = &comparison;
    let views = match args.view.view() {
        Some(view) => Some(compare_views(args, view, c)?),
        None => {
            save_png(
                &ab::compose(&c.a.image, &c.b.image, &c.heatmap, heatmap.palette()),
                &args.output,
            )?;
            None
        }
    };
    match args.format {
        MetricsFormat::Text => {
            print!("{}", text(args, c, heatmap));
            if let Some(lines) = &views {
                print!("{}", lines.text);
            }
        }
        MetricsFormat::Json => {
            let mut value = json(args, c);
            if let Some(lines) = views {
                value["view"] = lines.json;
            }
            println!(
                "{}",
                serde_json::to_string_pretty(&value).unwrap_or_default()
            );
        }
    }
    Ok(())
}

/// The sides' labels with their edits: what differs in the settings, then
/// in the scene (`sphere #5 ior 1.33`), when the sides' edits differ.
fn with_edits(labels: (String, String), edits: (&[String], &[String])) -> (String, String) {
    if edits.0 == edits.1 {
        return labels;
    }
    let label = |settings: String, edits: &[String]| match (settings.as_str(), edits) {
        ("same settings", []) => "the scene unedited".into(),
        (_, []) => settings,
        ("same settings", edits) => edits.join(", "),
        (_, edits) => format!("{settings}, {}", edits.join(", ")),
    };
    (label(labels.0, edits.0), label(labels.1, edits.1))
}

/// The comparison, or why there is none: it failed or was cancelled.
fn finished<T>(outcome: Result<Option<T>>, args: &CompareArgs) -> Result<T> {
    outcome
        .with_context(|| format!("cannot compare on {}", args.scene.display()))?
        .context("the comparison was cancelled")
}

/// `--b-image`: A against a reference image.
fn against_image(
    args: &CompareArgs,
    side: SideSetup,
    path: &std::path::Path,
    heatmap: Heatmap,
) -> Result<()> {
    let SideSetup {
        case: a,
        world,
        edits,
    } = side;
    let image = ab::read_reference(path, a.encoding)?;
    let size = (a.settings.width, a.settings.height);
    let reference = ab::fit_reference(image, size, args.fit)
        .with_context(|| format!("cannot compare with {}", path.display()))?;
    let mut progress = super::runner_progress(vec!["A".into()], 1);
    let c = ab::run_against_image(
        &world,
        a,
        reference,
        args.threads,
        heatmap,
        &AtomicBool::new(false),
        &mut progress,
    );
    let c = finished(c, args)?;
    save_png(
        &ab::compose(
            &c.a.image,
            &c.reference.image,
            &c.heatmap,
            heatmap.palette(),
        ),
        &args.output,
    )?;
    let settings = crate::describe::describe(&c.a.case.settings, &world.view);
    let label = [settings]
        .into_iter()
        .chain(edits)
        .collect::<Vec<_>>()
        .join(", ");
    match args.format {
        MetricsFormat::Text => {
            let resized = c
                .reference
                .resized_from
                .map_or_else(String::new, |(w, h)| format!(" (resized from {w}x{h})"));
            print!(
                "{} -> {} (A | image | {})\n{}B: {}{resized}\nMSE {:.3}, PSNR {:.2} dB, FLIP {:.4}\n",
                args.scene.display(),
                args.output.display(),
                heatmap.legend(),
                side_text("A", &label, &c.a),
                path.display(),
                c.metrics.mse,
                c.metrics.psnr,
                c.metrics.flip,
            );
        }
        MetricsFormat::Json => println!("{}", image_json(args, &c, &label, path)),
    }
    Ok(())
}

/// One side's time and work in two lines.
fn side_text(name: &str, label: &str, m: &Measurement) -> String {
    format!(
        "{name}: {label}\n   {:.3} s, {}x{}, {} samples/pixel ({:.1} taken), {} rays, {} rays/s\n",
        m.median().as_secs_f64(),
        m.case.settings.width,
        m.case.settings.height,
        m.case.settings.samples_per_pixel(),
        mean_spp(m),
        si(m.rays() as f64),
        si(m.rays_per_second()),
    )
}

/// Samples per pixel a side took, on average: its settings' for uniform
/// sampling, fewer where adaptive sampling stopped early.
fn mean_spp(m: &Measurement) -> f64 {
    let pixels = u64::from(m.stats.width) * u64::from(m.stats.height);
    m.stats.samples_taken() as f64 / pixels.max(1) as f64
}

/// One side's time and work as JSON.
fn side_json(label: &str, m: &Measurement) -> serde_json::Value {
    serde_json::json!({
        "label": label,
        "seconds": m.median().as_secs_f64(),
        "width": m.case.settings.width,
        "height": m.case.settings.height,
        "samples_per_pixel": m.case.settings.samples_per_pixel(),
        "samples_taken": m.stats.samples_taken(),
        "rays": m.rays(),
        "rays_per_second": m.rays_per_second(),
    })
}

/// The render against the image as one JSON object.
fn image_json(
    args: &CompareArgs,
    c: &ImageComparison,
    label: &str,
    path: &std::path::Path,
) -> String {
    let value = serde_json::json!({
        "scene": args.scene.display().to_string(),
        "output": args.output.display().to_string(),
        "a": side_json(label, &c.a),
        "b": {
            "image": path.display().to_string(),
            "resized_from": c.reference.resized_from,
        },
        "mse": c.metrics.mse,
        "psnr": c.metrics.psnr,
        "flip": c.metrics.flip,
    });
    serde_json::to_string_pretty(&value).unwrap_or_default()
}

/// The view's summary of both sides, as text and JSON.
struct ViewReport {
    text: String,
    json: serde_json::Value,
}

/// Writes `view` of both sides (measured in the comparison's own frames)
/// as A | B | difference on a shared scale, and reports both sides' numbers.
fn compare_views(args: &CompareArgs, view: View, c: &RenderComparison) -> Result<ViewReport> {
    let (Some(fa), Some(fb)) = (&c.a.views, &c.b.views) else {
        anyhow::bail!("the renders measured no views");
    };
    let (va, vb) = (fa.values(view), fb.values(view));
    let heat = args.view.heatmap(&[&va, &vb]);
    let (image, difference) = heat_map::compose_sides(fa, fb, view, &heat)?;
    save_png(&image, &args.output)?;
    let (sa, sb) = (ViewSummary::of(&va), ViewSummary::of(&vb));
    let number = heat_map::format_number;
    let difference_line = difference.map_or_else(String::new, |d| {
        format!(
            "A - B: mean A / mean B {}, mean |A - B| {}, max |A - B| {} ({})\n",
            number(d.ratio),
            number(d.mean_abs_difference),
            number(d.max_abs_difference),
            view.unit()
        )
    });
    Ok(ViewReport {
        text: format!(
            "A {}\nB {}\n{difference_line}",
            view_summary::describe(view, sa.as_ref(), &heat),
            view_summary::describe(view, sb.as_ref(), &heat)
        ),
        json: serde_json::json!({
            "a": view_summary::summary_json(view, sa.as_ref(), &heat),
            "b": view_summary::summary_json(view, sb.as_ref(), &heat),
            "difference": difference.map(|d| serde_json::json!({
                "pixels": d.pixels,
                "mean_a": d.mean_a,
                "mean_b": d.mean_b,
                "ratio": d.ratio.is_finite().then_some(d.ratio),
                "mean_abs_difference": d.mean_abs_difference,
                "max_abs_difference": d.max_abs_difference,
            })),
        }),
    })
}

fn text(args: &CompareArgs, c: &RenderComparison, heatmap: Heatmap) -> String {
    let side = side_text;
    let ratio = c.time_ratio();
    let speed = if ratio >= 1.0 {
        format!("B is {ratio:.2}x faster")
    } else {
        format!("A is {:.2}x faster", 1.0 / ratio.max(1e-9))
    };
    format!(
        "{} -> {} (A | B | {})\n{}{}time A/B: {ratio:.3} ({speed})\nMSE {:.3}, PSNR {:.2} dB, FLIP {:.4}\n",
        args.scene.display(),
        args.output.display(),
        match args.view.view() {
            Some(view) => format!(
                "{0} | {0} on one scale | A - B (red: A larger, blue: B larger)",
                view.name()
            ),
            None => heatmap.legend(),
        },
        side("A", &c.labels.0, &c.a),
        side("B", &c.labels.1, &c.b),
        c.metrics.mse,
        c.metrics.psnr,
        c.metrics.flip,
    )
}

/// The times and metrics as one JSON object; PSNR is null for identical
/// images (infinite).
fn json(args: &CompareArgs, c: &RenderComparison) -> serde_json::Value {
    let side = side_json;
    serde_json::json!({
        "scene": args.scene.display().to_string(),
        "output": args.output.display().to_string(),
        "a": side(&c.labels.0, &c.a),
        "b": side(&c.labels.1, &c.b),
        "time_ratio_a_over_b": c.time_ratio(),
        "mse": c.metrics.mse,
        "psnr": c.metrics.psnr,
        "flip": c.metrics.flip,
    })
}
