//! Section 5, statistics in pbrt's manner: for each configuration of the
//! timing table, rays by kind, shadow rays blocked, the deepest bounce, and
//! for each structure the tests and nodes (or cells) per ray.

use std::fmt::Write as _;

use tracer::accel::AccelKind;

use super::Lab;
use super::html::{escape, titled_section};
use crate::measure::benchmark::{Measurement, SamplingColumn};

fn percent(part: f64, whole: f64) -> String {
    if whole > 0.0 {
        format!("{:.1}%", 100.0 * part / whole)
    } else {
        "-".into()
    }
}

/// One configuration's block.
fn block(lab: &Lab, soft: bool, sampling: SamplingColumn) -> Option<String> {
    let bvh = lab.row(AccelKind::Bvh, soft, sampling)?;
    let views = lab
        .views
        .iter()
        .find(|m| same_configuration(m, bvh))
        .and_then(|m| m.views.as_ref())?
        .totals();
    let c = &bvh.stats.counters;
    let total = c.total_rays() as f64;
    let mut out = String::new();
    let line = |out: &mut String, name: &str, value: String| {
        let _ = writeln!(out, "    {name:<40}{value:>16}");
    };
    let _ = writeln!(out, "{}", bvh.case.label.replacen("BVH, ", "", 1));
    line(&mut out, "Rays", c.total_rays().to_string());
    for (kind, n) in [
        ("eye", c.eye_rays),
        ("shadow", c.shadow_rays),
        ("reflection", c.reflection_rays),
        ("refraction", c.refraction_rays),
    ] {
        line(
            &mut out,
            &format!("  {kind}"),
            format!("{n} ({})", percent(n as f64, total)),
        );
    }
    line(
        &mut out,
        "Shadow rays blocked",
        format!(
            "{} ({})",
            views.blocked,
            percent(views.blocked, views.shadow_rays)
        ),
    );
    line(&mut out, "Deepest bounce", views.deepest.to_string());
    line(
        &mut out,
        "Shadow rays blocked by the cached occluder",
        c.shadow_cache_hits.to_string(),
    );
    for accel in AccelKind::ALL {
        if let Some(m) = lab.row(accel, soft, sampling) {
            line(
                &mut out,
                &format!("Intersection tests per ray, {}", accel.name()),
                format!("{:.2}", m.tests_per_ray()),
            );
            if accel != AccelKind::None {
                let what = if accel == AccelKind::Grid {
                    "cells"
                } else {
                    "nodes"
                };
                line(
                    &mut out,
                    &format!("{what} per ray, {}", accel.name()),
                    format!("{:.2}", m.steps_per_ray()),
                );
            }
        }
    }
    Some(out)
}

fn same_configuration(a: &Measurement, b: &Measurement) -> bool {
    let (s, t) = (&a.case.settings, &b.case.settings);
    s.accel == t.accel
        && s.soft_shadows == t.soft_shadows
        && SamplingColumn::of(s) == SamplingColumn::of(t)
}

pub(crate) fn section(lab: &Lab) -> String {
    let mut text = String::new();
    for soft in [false, true] {
        for sampling in [
            SamplingColumn::Single,
            SamplingColumn::Antialiasing,
            SamplingColumn::AntialiasingDof,
        ] {
            match block(lab, soft, sampling) {
                Some(b) => text += &(b + "\n"),
                None => text += "(a configuration was not measured)\n\n",
            }
        }
    }
    let body = format!(
        "<p>Exact counts of one frame of each configuration of the timing table. The rays, \
         blocked shadow rays and bounces are the same with every structure (they trace the same \
         rays); the work per ray is each structure's.</p>\n<pre>{}</pre>\n\
         <p class=\"how\">Counts from one frame of each configuration ({} x {}); blocked shadow \
         rays and bounces from a frame measured with per-pixel views over the BVH.</p>\n",
        escape(&text),
        lab.base.width,
        lab.base.height
    );
    titled_section("statistics", "5. Statistics", &body)
}
