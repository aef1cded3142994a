//! `bench --to-error`'s findings as text and JSON: the renders tried, the
//! uniform and adaptive sides at the target error, and the verdict.

use tracer::render::RenderSettings;

use crate::measure::to_error::{MeasuredSampling, SMALLEST_THRESHOLD, ToError};

/// How a side is named in the tables.
fn name(settings: &RenderSettings) -> String {
    match settings.adaptive() {
        Some(a) => format!(
            "adaptive T = {} ({}..{} spp)",
            a.noise_threshold, a.min_spp, a.max_spp
        ),
        None => format!("uniform N = {}", settings.samples),
    }
}

/// The renders tried, the two sides and the verdict, as aligned text.
pub(crate) fn text(found: &ToError) -> String {
    let mut out = String::new();
    let target = match found.target_flip {
        Some(flip) => format!(
            "uniform N = {}'s error, MSE {:.3} and FLIP {:.4}",
            found.uniform.settings.samples, found.target_mse, flip
        ),
        None => format!("MSE {:.3}", found.target_mse),
    };
    out.push_str(&format!(
        "reference: uniform N = {} ({} spp, {:.2} s); target: {target}\n\n",
        found.reference_samples,
        found.reference_samples.pow(2),
        found.reference_time.as_secs_f64(),
    ));
    out.push_str(&format!(
        "{:<28} {:>8} {:>8} {:>8} {:>9}  reached\n",
        "tried", "spp", "MSE", "FLIP", "time"
    ));
    for a in &found.attempts {
        out.push_str(&format!(
            "{:<28} {:>8.1} {:>8.3} {:>8.4} {:>8.3}s  {}\n",
            a.label,
            a.spp_mean,
            a.metrics.mse,
            a.metrics.flip,
            a.time.as_secs_f64(),
            if a.reached { "yes" } else { "no" }
        ));
    }
    out.push_str(&format!(
        "\n{:<36} {:>8} {:>7} {:>8} {:>8} {:>12} {:>10}\n",
        "sampling", "spp mean", "spp max", "MSE", "FLIP", "median time", "vs uniform"
    ));
    let uniform = found.uniform.median().as_secs_f64();
    for side in std::iter::once(&found.uniform).chain(&found.adaptive) {
        out.push_str(&format!(
            "{:<36} {:>8.1} {:>7} {:>8.3} {:>8.4} {:>11.3}s {:>9.0}%\n",
            name(&side.settings),
            side.spp_mean,
            side.spp_max,
            side.metrics.mse,
            side.metrics.flip,
            side.median().as_secs_f64(),
            100.0 * side.median().as_secs_f64() / uniform.max(1e-9),
        ));
    }
    let n = found.uniform.settings.samples;
    match (&found.adaptive, found.time_ratio()) {
        (Some(adaptive), Some(ratio)) => out.push_str(&format!(
            "\nadaptive reaches the error of uniform {n} x {n} in {:.0}% of its time \
             ({:.3} s -> {:.3} s, medians of {} alternated runs), with {:.0}% of its samples\n",
            100.0 * ratio,
            uniform,
            adaptive.median().as_secs_f64(),
            adaptive.times.len(),
            100.0 * adaptive.spp_mean / found.uniform.spp_mean.max(1e-9),
        )),
        _ => out.push_str(&format!(
            "\nno adaptive threshold down to {SMALLEST_THRESHOLD} reaches the target\n"
        )),
    }
    out
}

/// Everything measured, as JSON.
pub(crate) fn json(found: &ToError) -> serde_json::Value {
    let side = |s: &MeasuredSampling| {
        serde_json::json!({
            "sampling": name(&s.settings),
            "noise_threshold": s.settings.adaptive().map(|a| a.noise_threshold),
            "samples": s.settings.samples,
            "spp_mean": s.spp_mean,
            "spp_max": s.spp_max,
            "mse": s.metrics.mse,
            "flip": s.metrics.flip,
            "median_seconds": s.median().as_secs_f64(),
            "seconds": s.times.iter().map(|t| t.as_secs_f64()).collect::<Vec<_>>(),
        })
    };
    serde_json::json!({
        "reference_samples": found.reference_samples,
        "reference_seconds": found.reference_time.as_secs_f64(),
        "target_mse": found.target_mse,
        "target_flip": found.target_flip,
        "uniform": side(&found.uniform),
        "adaptive": found.adaptive.as_ref().map(side),
        "time_ratio": found.time_ratio(),
        "attempts": found.attempts.iter().map(|a| serde_json::json!({
            "label": a.label,
            "spp_mean": a.spp_mean,
            "mse": a.metrics.mse,
            "flip": a.metrics.flip,
            "seconds": a.time.as_secs_f64(),
            "reached": a.reached,
        })).collect::<Vec<_>>(),
    })
}
