//! Section 4, acceleration: the course's timing table with a BVH row for
//! each of its rows, as a table and a bar chart; the grid multiplier study;
//! the tests each pixel cost without a structure, with the grid and with
//! the BVH on one scale; each structure's build time and memory.

use anyhow::{Result, bail};
use tracer::accel::AccelKind;
use tracer::render::{HeatScale, View, ViewHeatmap};

use super::html::{escape, figure, image, table, titled_section};
use super::svg::{Bar, Series, YAxis, bar_chart, line_chart};
use super::{Lab, how_measured, ms};
use crate::describe::{millis, si};
use crate::figures::heat_map::{view_image, with_legend};
use crate::figures::study_plot::colour;
use crate::measure::benchmark::Measurement;
use crate::reports::bench_table::yes_no;

/// The timing table's headers; tests find columns by these names.
pub(crate) const TIMING_HEADERS: [&str; 11] = [
    "structure",
    "soft shadows",
    "anti-aliasing",
    "depth of field",
    "samples/px",
    "frame ms",
    "min..max ms",
    "MAD ms",
    "runs",
    "rays",
    "rays/s",
];

/// One row of the timing table, as the course's table words it.
fn timing_row(m: &Measurement) -> (String, Vec<String>) {
    let s = &m.case.settings;
    let aa = if s.antialiasing {
        format!("yes (N = {})", s.samples)
    } else {
        "no".into()
    };
    let dof = match (s.depth_of_field, s.antialiasing) {
        (true, _) => format!("yes ({} px)", m.lens.aperture),
        (false, true) => "no".into(),
        (false, false) => "-".into(),
    };
    (
        m.case.file_stem(),
        vec![
            s.accel.name().into(),
            yes_no(s.soft_shadows),
            aa,
            dof,
            s.samples_per_pixel().to_string(),
            ms(m.median()),
            format!("{}..{}", ms(m.min()), ms(m.max())),
            ms(m.mad()),
            m.times.len().to_string(),
            m.rays().to_string(),
            si(m.rays_per_second()),
        ],
    )
}

/// The bar chart's bars: each row's median frame time in milliseconds,
/// its whisker from the fastest run to the slowest.
fn timing_bars(lab: &Lab) -> Vec<Bar> {
    lab.matrix
        .iter()
        .map(|m| Bar {
            label: m.case.file_stem().replace('_', " "),
            value: millis(m.median()),
            low: millis(m.min()),
            high: millis(m.max()),
            colour: colour(m.case.settings.accel),
        })
        .collect()
}

pub(crate) fn section(lab: &Lab) -> Result<String> {
    let rows: Vec<_> = lab.matrix.iter().map(timing_row).collect();
    let bars = timing_bars(lab);
    let body = format!(
        "<h3>The timing table</h3>\n<p>The course's table (Figure 5.1): brute force (none) and \
         the uniform grid, hard and soft shadows, one sample, anti-aliasing N = {n}, and \
         anti-aliasing with depth of field; with a BVH row for each.</p>\n{table}\
         <p class=\"how\">{how}</p>\n<figure>{chart}<figcaption>Median frame time of each row, \
         the whisker from the fastest to the slowest run.</figcaption></figure>\n{grid}{views}{builds}",
        n = lab.base.samples,
        table = table("timing", &TIMING_HEADERS, &rows),
        how = escape(&how_measured(lab)),
        chart = bar_chart(&bars, "frame time (ms)"),
        grid = grid_study(lab),
        views = tests_per_pixel(lab)?,
        builds = builds(lab),
    );
    Ok(titled_section("acceleration", "4. Acceleration", &body))
}

/// The grid multiplier study: frame time and work per ray against m.
fn grid_study(lab: &Lab) -> String {
    let points = &lab.grid.points;
    let series = Series {
        name: "grid".into(),
        colour: colour(AccelKind::Grid),
        points: points.iter().map(|p| (p.value, p.frame_ms())).collect(),
    };
    let tests = Series {
        name: "tests/ray".into(),
        colour: [214, 69, 65],
        points: points
            .iter()
            .map(|p| (p.value, p.measurement.tests_per_ray()))
            .collect(),
    };
    let rows: Vec<(String, Vec<String>)> = points
        .iter()
        .map(|p| {
            let m = &p.measurement;
            let cells = m.index.grid.as_ref().map_or("-".into(), |g| {
                format!("{} x {} x {}", g.cells[0], g.cells[1], g.cells[2])
            });
            (
                format!("m{}", p.value),
                vec![
                    format!("{}", p.value),
                    cells,
                    ms(m.median()),
                    format!("{:.2}", millis(m.index.build_time)),
                    format!("{}B", si(m.index.memory_bytes as f64)),
                    format!("{:.2}", m.tests_per_ray()),
                    format!("{:.2}", m.steps_per_ray()),
                ],
            )
        })
        .collect();
    format!(
        "<h3>The grid multiplier m</h3>\n<p>Cells per axis = trunc(m · dim · s) + 1: more cells \
         mean fewer tests per ray and more cells to walk. One sample per pixel, hard \
         shadows.</p>\n<div class=\"figures\">{}{}</div>\n{}",
        line_chart(
            "Frame time against m",
            "m",
            "ms",
            YAxis::FromZero,
            &[series]
        ),
        line_chart(
            "Tests per ray against m",
            "m",
            "tests/ray",
            YAxis::FromZero,
            &[tests]
        ),
        table(
            "grid",
            &[
                "m",
                "cells",
                "frame ms",
                "build ms",
                "memory",
                "tests/ray",
                "cells/ray"
            ],
            &rows
        )
    )
}

/// The plain frame's tests per pixel for each structure, on one scale.
fn tests_per_pixel(lab: &Lab) -> Result<String> {
    let plain = |accel| {
        lab.views.iter().find(|m| {
            let s = &m.case.settings;
            s.accel == accel && !s.soft_shadows && s.samples_per_pixel() == 1
        })
    };
    let mut films = Vec::new();
    for accel in AccelKind::ALL {
        match plain(accel).and_then(|m| m.views.as_ref().map(|v| (accel, v))) {
            Some(film) => films.push(film),
            None => bail!("the {} frame's views are missing", accel.name()),
        }
    }
    let values: Vec<Vec<Option<f32>>> = films.iter().map(|(_, f)| f.values(View::Tests)).collect();
    let sides: Vec<&[Option<f32>]> = values.iter().map(Vec::as_slice).collect();
    let heat = ViewHeatmap::fit(HeatScale::Max, true, &sides);
    let mut figures = String::new();
    for ((accel, film), values) in films.iter().zip(&values) {
        let Some(map) = view_image(film, View::Tests, &heat) else {
            bail!("the tests view has no image");
        };
        let pixels = values.iter().flatten().count().max(1) as f32;
        let mean = values.iter().flatten().sum::<f32>() / pixels;
        let caption = format!("{}: {mean:.1} tests per pixel on average", accel.name());
        figures += &figure(&image(&with_legend(&map, &heat), &caption, 300)?, &caption);
    }
    Ok(format!(
        "<h3>Tests per pixel</h3>\n<p>Ray-primitive intersection tests of every ray each pixel \
         spawned, one sample per pixel, hard shadows; the three on one logarithmic scale, \
         log(1 + tests), from 0 to the largest ({}).</p>\n<div class=\"figures\">{figures}</div>\n",
        heat.top
    ))
}

/// Each structure's build time and memory, from the matrix's frames.
fn builds(lab: &Lab) -> String {
    let rows: Vec<(String, Vec<String>)> = AccelKind::ALL
        .iter()
        .filter_map(|&accel| lab.matrix.iter().find(|m| m.case.settings.accel == accel))
        .map(|m| {
            let info = &m.index;
            let size = match (&info.grid, info.bvh_nodes) {
                (Some(g), _) => format!(
                    "{} x {} x {} cells, {} references",
                    g.cells[0], g.cells[1], g.cells[2], g.references
                ),
                (None, Some(nodes)) => format!("{nodes} nodes"),
                (None, None) => "-".into(),
            };
            (
                info.kind.name().to_string(),
                vec![
                    info.kind.name().to_string(),
                    format!("{:.3}", millis(info.build_time)),
                    format!("{}B", si(info.memory_bytes as f64)),
                    size,
                ],
            )
        })
        .collect();
    format!(
        "<h3>Building the structures</h3>\n{}<p class=\"how\">Each built once per report, \
         before the frames that use it, and timed once.</p>\n",
        table(
            "builds",
            &["structure", "build ms", "memory", "size"],
            &rows
        ),
    )
}

#[cfg(test)]
mod tests;
