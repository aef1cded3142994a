//! A view's numbers in words and JSON: its mean, median, 99th percentile
//! and maximum with their unit, and the heat map's scale. Shared by
//! `render --view` and `compare --view`.

use tracer::render::{View, ViewHeatmap, ViewSummary};

use crate::figures::heat_map::format_number;

/// The summary line of a view: its numbers and what they count.
pub(crate) fn describe(view: View, summary: Option<&ViewSummary>, heat: &ViewHeatmap) -> String {
    match summary {
        None if !view.is_scalar() => format!("view {}: colours, no numbers", view.name()),
        None => format!("view {}: no pixel has a value", view.name()),
        Some(s) => format!(
            "view {}: mean {}, median {}, p99 {}, max {} ({}); scale 0..{}{}",
            view.name(),
            format_number(s.mean),
            format_number(s.median),
            format_number(s.p99),
            format_number(s.max),
            view.unit(),
            format_number(heat.top),
            if heat.log { " (log)" } else { "" },
        ),
    }
}

/// The summary as JSON (null numbers when no pixel has a value).
pub(crate) fn summary_json(
    view: View,
    summary: Option<&ViewSummary>,
    heat: &ViewHeatmap,
) -> serde_json::Value {
    let number = |f: fn(&ViewSummary) -> f32| summary.map(f);
    serde_json::json!({
        "name": view.name(),
        "unit": view.unit(),
        "pixels_with_value": summary.map_or(0, |s| s.pixels),
        "mean": number(|s| s.mean),
        "median": number(|s| s.median),
        "p99": number(|s| s.p99),
        "max": number(|s| s.max),
        "scale_top": view.is_scalar().then_some(heat.top),
        "log": heat.log,
    })
}
