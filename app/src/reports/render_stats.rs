//! Human and machine-readable reports of a render's statistics.

use tracer::stats::{RenderStats, SceneCounts};

use crate::describe::si;

/// Objects by kind, e.g. "91 spheres, 2 polygons".
pub(crate) fn describe_objects(counts: &SceneCounts) -> String {
    if counts.objects_by_kind.is_empty() {
        return "no objects".to_string();
    }
    counts
        .objects_by_kind
        .iter()
        .map(|(kind, n)| format!("{n} {kind}{}", if *n == 1 { "" } else { "s" }))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Samples per pixel, mean and max: an adaptive render's own, else one
/// per pass in every pixel.
fn samples_per_pixel(stats: &RenderStats) -> (f64, u32) {
    match &stats.adaptive {
        Some(a) => (a.mean_spp(), a.max_spp),
        None => (f64::from(stats.passes_done), stats.passes_done),
    }
}

/// How far the samples are, in a few words: "4 / 16 spp" (uniform: passes
/// of one sample a pixel against N x N), "pass 7 / 11, 36.0 spp mean"
/// (adaptive: its passes double the active pixels' samples, so the pass
/// count is not the samples).
pub(crate) fn sample_progress(stats: &RenderStats) -> String {
    match &stats.adaptive {
        Some(a) => format!(
            "pass {} / {}, {:.1} spp mean",
            stats.passes_done,
            stats.passes_target,
            a.mean_spp()
        ),
        None => format!("{} / {} spp", stats.passes_done, stats.passes_target),
    }
}

/// The few lines `workbench render` prints after a render.
pub(crate) fn summary(stats: &RenderStats, counts: &SceneCounts) -> String {
    let mut text = counts_summary(stats, counts);
    if let Some(a) = &stats.adaptive {
        let (mean, max) = samples_per_pixel(stats);
        text.push_str(&format!(
            "\nadaptive: {mean:.1} samples per pixel on average, {max} at most; \
             {:.1}% of pixels still active; estimated error {:.4} (RMS, display units)",
            100.0 * a.active_share(),
            a.error,
        ));
    }
    text
}

fn counts_summary(stats: &RenderStats, counts: &SceneCounts) -> String {
    let c = &stats.counters;
    format!(
        "{}x{}, {} objects ({}), {} primitives, {} lights\n\
         {} pass(es), {:.3} s render, {:.3} s acceleration build\n\
         {} rays: {} eye, {} shadow, {} reflection, {} refraction; {} rays/s\n\
         {} intersection tests ({:.1} per ray)",
        stats.width,
        stats.height,
        counts.objects(),
        describe_objects(counts),
        counts.primitives,
        counts.lights,
        stats.passes_done,
        stats.render_time.as_secs_f64(),
        stats.build_time.as_secs_f64(),
        si(c.total_rays() as f64),
        si(c.eye_rays as f64),
        si(c.shadow_rays as f64),
        si(c.reflection_rays as f64),
        si(c.refraction_rays as f64),
        si(stats.rays_per_second()),
        si(c.intersection_tests as f64),
        c.intersection_tests as f64 / c.total_rays().max(1) as f64,
    )
}

/// The statistics as one JSON object, for commands that add their own
/// fields.
pub(crate) fn json_value(stats: &RenderStats, counts: &SceneCounts) -> serde_json::Value {
    let c = &stats.counters;
    let (spp_mean, spp_max) = samples_per_pixel(stats);
    let adaptive = stats.adaptive.map(|a| {
        serde_json::json!({
            "active_pixels": a.active_pixels,
            "active_share": a.active_share(),
            "error_estimate": finite(a.error),
        })
    });
    let objects: serde_json::Map<String, serde_json::Value> = counts
        .objects_by_kind
        .iter()
        .map(|(k, n)| (k.to_string(), (*n).into()))
        .collect();
    serde_json::json!({
        "width": stats.width,
        "height": stats.height,
        "passes_done": stats.passes_done,
        "passes_target": stats.passes_target,
        "render_seconds": stats.render_time.as_secs_f64(),
        "build_seconds": stats.build_time.as_secs_f64(),
        "pass_seconds": stats.pass_times.iter().map(|d| d.as_secs_f64()).collect::<Vec<_>>(),
        "samples_per_pixel": { "mean": spp_mean, "max": spp_max },
        "adaptive": adaptive,
        "rays": {
            "total": c.total_rays(),
            "eye": c.eye_rays,
            "shadow": c.shadow_rays,
            "reflection": c.reflection_rays,
            "refraction": c.refraction_rays,
        },
        "rays_per_second": stats.rays_per_second(),
        "intersection_tests": c.intersection_tests,
        "hits": c.hits,
        "nodes_visited": c.nodes_visited,
        "shadow_cache_hits": c.shadow_cache_hits,
        "scene": {
            "objects": objects,
            "primitives": counts.primitives,
            "triangles": counts.triangles,
            "lights": counts.lights,
        },
    })
}

/// A number JSON can hold: `null` for infinities and NaN.
fn finite(v: f32) -> Option<f32> {
    v.is_finite().then_some(v)
}
