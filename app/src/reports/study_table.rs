//! A study as a table (aligned text, Markdown, CSV, JSON) with one row per
//! (structure, value), and a summary in words of what it shows.

use crate::describe::{millis, si};
use crate::measure::study::analysis::{self, Best};
use crate::measure::study::{Knob, Param, Point, values};
use crate::reports::bench_table::{self, Format};

/// Samples per pixel a point's frame took, on average and at most.
fn spp(p: &Point) -> (f64, u32) {
    let stats = &p.measurement.stats;
    match &stats.adaptive {
        Some(a) => (a.mean_spp(), a.max_spp),
        None => (f64::from(stats.passes_done), stats.passes_done),
    }
}

/// The headers and the readable cells of every row, as the text table
/// has them (the window's table shows the same).
pub(crate) fn rows(param: Param, points: &[Point]) -> (Vec<String>, Vec<Vec<String>>) {
    cells(param, points, false)
}

/// The headers and the (pretty or raw) cells of every row.
fn cells(param: Param, points: &[Point], raw: bool) -> (Vec<String>, Vec<Vec<String>>) {
    let best = analysis::best(param, points);
    let with_error = points.iter().any(|p| p.error.is_some());
    let mut headers = vec!["accel".to_string(), param.to_string()];
    if param == Param::Level {
        headers.push("primitives".into());
    }
    // A material changes which rays are spawned: show how many of each.
    let by_kind = matches!(param, Param::Material { .. });
    headers.extend(
        [
            "build ms",
            "frame ms",
            "min..max ms",
            "runs",
            "rays",
            "rays/s",
            "tests/ray",
            "steps/ray",
        ]
        .map(String::from),
    );
    if by_kind {
        headers.extend(["reflection rays", "refraction rays"].map(String::from));
    }
    // Adaptive sampling decides the samples: show how many it took.
    let adaptive = param == Param::NoiseThreshold;
    if adaptive {
        headers.extend(["spp mean", "spp max"].map(String::from));
    }
    if with_error {
        headers.extend(["MSE", "PSNR dB", "FLIP"].map(String::from));
    }
    if !best.is_empty() {
        headers.push("best".into());
    }
    let rows = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let m = &p.measurement;
            let (digits, ratio) = if raw { (3, 4) } else { (1, 2) };
            let mut row = vec![p.accel().name().to_string(), values::format(p.value)];
            if param == Param::Level {
                row.push(p.primitives.to_string());
            }
            row.extend([
                format!("{:.digits$}", millis(m.index.build_time)),
                format!("{:.digits$}", millis(m.median())),
                format!("{:.digits$}..{:.digits$}", millis(m.min()), millis(m.max())),
                m.times.len().to_string(),
                if raw {
                    m.rays().to_string()
                } else {
                    si(m.rays() as f64)
                },
                if raw {
                    format!("{:.0}", m.rays_per_second())
                } else {
                    si(m.rays_per_second())
                },
                format!("{:.ratio$}", m.tests_per_ray()),
                format!("{:.ratio$}", m.steps_per_ray()),
            ]);
            if by_kind {
                let counters = &m.stats.counters;
                row.extend(
                    [counters.reflection_rays, counters.refraction_rays]
                        .map(|n| if raw { n.to_string() } else { si(n as f64) }),
                );
            }
            if adaptive {
                let (mean, max) = spp(p);
                row.extend([format!("{mean:.ratio$}"), max.to_string()]);
            }
            if with_error {
                row.extend(match p.error {
                    Some(e) => [
                        format!("{:.ratio$}", e.mse),
                        format!("{:.ratio$}", e.psnr),
                        format!("{:.4}", e.flip),
                    ],
                    None => ["", "", ""].map(String::from),
                });
            }
            if !best.is_empty() {
                row.push(match best.iter().find(|(b, _)| *b == i) {
                    Some((_, Best::Fastest)) => "fastest".into(),
                    Some((_, Best::Knee)) => "knee".into(),
                    None => String::new(),
                });
            }
            row
        })
        .collect();
    (headers, rows)
}

/// The points in `format`, in measuring order.
pub(crate) fn table(param: Param, points: &[Point], format: Format) -> String {
    match format {
        Format::Text => {
            let (headers, rows) = cells(param, points, false);
            bench_table::text(&headers, &rows)
        }
        Format::Markdown => {
            let (headers, rows) = cells(param, points, false);
            bench_table::markdown(&headers, &rows)
        }
        Format::Csv => {
            let (headers, rows) = cells(param, points, true);
            bench_table::csv(&headers, &rows)
        }
        Format::Json => json(param, points),
    }
}

/// Every point with its numbers, times in seconds.
fn json(param: Param, points: &[Point]) -> String {
    let best = analysis::best(param, points);
    let rows: Vec<serde_json::Value> = points
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let m = &p.measurement;
            m.with_timing_json(serde_json::json!({
                "accel": p.accel().name(),
                "param": param.to_string(),
                "reflection_rays": m.stats.counters.reflection_rays,
                "refraction_rays": m.stats.counters.refraction_rays,
                "value": p.value,
                "x": p.x,
                "primitives": p.primitives,
                "width": m.case.settings.width,
                "height": m.case.settings.height,
                "samples_per_pixel": m.case.settings.samples_per_pixel(),
                "spp_mean": spp(p).0,
                "spp_max": spp(p).1,
                "tests_per_ray": m.tests_per_ray(),
                "steps_per_ray": m.steps_per_ray(),
                "mse": p.error.map(|e| e.mse),
                "psnr": p.error.map(|e| e.psnr).filter(|v| v.is_finite()),
                "flip": p.error.map(|e| e.flip),
                "best": best.iter().any(|(b, _)| *b == i),
            }))
        })
        .collect();
    serde_json::to_string_pretty(&rows).unwrap_or_default() + "\n"
}

/// One line per structure saying what the study found: the best value
/// (with its time), or for the level study the log-log slope.
pub(crate) fn summary(param: Param, points: &[Point]) -> Vec<String> {
    if param == Param::Level {
        return analysis::structures(points)
            .into_iter()
            .filter_map(|accel| {
                analysis::slope(points, accel).map(|s| {
                    format!(
                        "{}: frame time grows as primitives^{s:.2} (log-log slope)",
                        accel.name()
                    )
                })
            })
            .collect();
    }
    if let Param::Material {
        field: Knob::Ior, ..
    } = param
    {
        return analysis::steepest_fall(points, |p| p.measurement.stats.counters.refraction_rays)
            .map(|(from, to)| {
                let per_pixel = |p: &Point| {
                    let s = &p.measurement.case.settings;
                    let pixels = u64::from(s.width) * u64::from(s.height);
                    p.measurement.stats.counters.refraction_rays as f64 / pixels.max(1) as f64
                };
                format!(
                    "refraction rays fall most between {param} = {} and {} ({:.3} -> {:.3} a \
                     pixel): where total internal reflection sets in, on glass",
                    values::format(from.value),
                    values::format(to.value),
                    per_pixel(from),
                    per_pixel(to)
                )
            })
            .into_iter()
            .collect();
    }
    if let Param::Material { .. } = param {
        return Vec::new();
    }
    analysis::best(param, points)
        .into_iter()
        .map(|(i, why)| {
            let p = &points[i];
            let what = match why {
                Best::Fastest => "fastest",
                Best::Knee => "knee of error vs time",
            };
            format!(
                "{}: {what} at {} = {} ({:.1} ms)",
                p.accel().name(),
                param,
                values::format(p.value),
                p.frame_ms()
            )
        })
        .collect()
}
