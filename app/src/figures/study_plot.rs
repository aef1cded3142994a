//! A study as a PNG line chart (plotters, bitmap backend): frame time
//! against the parameter, one line per structure, the best point ringed;
//! log-log axes for the level study, and for `spp` a second panel of image
//! error against frame time. The font is egui's embedded one, rasterized in
//! Rust ([`chart_text`]), so drawing needs nothing from the system, nor
//! on the web page from the browser: a study's chart is drawn on a worker
//! there.

use std::ops::Range;

use anyhow::{Result, anyhow};
use image::RgbImage;
use plotters::coord::Shift;
use plotters::coord::combinators::BindKeyPoints;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use tracer::accel::AccelKind;

use super::chart_text::{EmbeddedText, legend};
use crate::measure::study::analysis::{self, Best};
use crate::measure::study::{Param, Point, values};

/// Size of a chart panel in pixels.
pub(crate) const PANEL: (u32, u32) = (800, 500);

/// The colour of a structure's line, the same in the window's chart.
pub(crate) fn colour(accel: AccelKind) -> [u8; 3] {
    match accel {
        AccelKind::None => [214, 69, 65],
        AccelKind::Grid => [52, 120, 198],
        AccelKind::Bvh => [46, 160, 67],
    }
}

/// The font family the charts name (the embedded font draws them all).
const FONT: &str = "sans-serif";

/// What a chart draws on: a pixel buffer, its text drawn by
/// [`EmbeddedText`].
type Chart<'a> = EmbeddedText<BitMapBackend<'a>>;

/// One line of a panel.
struct Curve {
    name: String,
    colour: RGBColor,
    points: Vec<(f64, f64)>,
    /// The best point, ringed, with its label.
    best: Option<((f64, f64), String)>,
}

/// One chart.
struct Panel {
    title: String,
    x_label: String,
    y_label: String,
    /// Start the y axis at 0 (times, errors), or at the data (ray counts
    /// whose changes are small against their size).
    y_from_zero: bool,
    log_x: bool,
    log_y: bool,
    /// Label only whole numbers on x (N, depth, width, ...).
    integer_x: bool,
    /// Where the legend covers the least of the lines.
    legend: SeriesLabelPosition,
    curves: Vec<Curve>,
}

/// The chart of `points` (a study of `param` on `subject`, a name for the
/// title) as an image: one panel, two side by side for `spp`.
pub(crate) fn chart(param: Param, points: &[Point], subject: &str) -> Result<RgbImage> {
    let panels = panels(param, points, subject);
    let (w, h) = (PANEL.0 * panels.len() as u32, PANEL.1);
    let mut buffer = vec![0u8; (w * h * 3) as usize];
    {
        let root =
            EmbeddedText(BitMapBackend::with_buffer(&mut buffer, (w, h))).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let areas = root.split_evenly((1, panels.len()));
        for (panel, area) in panels.iter().zip(&areas) {
            draw_panel(panel, area)?;
        }
        root.present().map_err(drawing)?;
    }
    RgbImage::from_raw(w, h, buffer).ok_or_else(|| anyhow!("the chart has the wrong size"))
}

/// [`chart`] as PNG bytes, for a download or a save dialog's file.
pub(crate) fn chart_png(param: Param, points: &[Point], subject: &str) -> Result<Vec<u8>> {
    let mut png = std::io::Cursor::new(Vec::new());
    chart(param, points, subject)?.write_to(&mut png, image::ImageFormat::Png)?;
    Ok(png.into_inner())
}

/// The name a chart is saved under: `study-PARAM-STEM.png`.
pub(crate) fn chart_file_name(param: Param, subject: &str) -> String {
    format!("study-{param}-{}.png", subject_stem(subject))
}

/// What names a study's files: its subject's file stem (of a scene
/// file, or a generator's name).
pub(crate) fn subject_stem(subject: &str) -> String {
    std::path::Path::new(subject)
        .file_stem()
        .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned())
}

fn drawing(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow!("cannot draw the chart: {e}")
}

fn panels(param: Param, points: &[Point], subject: &str) -> Vec<Panel> {
    let best = analysis::best(param, points);
    let accels = analysis::structures(points);
    let best_of = |accel: AccelKind, at: &dyn Fn(&Point) -> (f64, f64)| {
        best.iter()
            .map(|&(i, why)| (&points[i], why))
            .find(|(p, _)| p.accel() == accel)
            .map(|(p, why)| {
                let label = match why {
                    Best::Fastest => format!("fastest: {} = {}", param, values::format(p.value)),
                    Best::Knee => format!("knee: N = {}", values::format(p.value)),
                };
                (at(p), label)
            })
    };
    let (log_x, log_y) = log_axes(param, points);
    let mut time = Panel {
        title: format!("{subject}: frame time vs {param}"),
        x_label: param.axis().to_string(),
        y_label: "frame time (ms, median)".into(),
        y_from_zero: true,
        log_x,
        log_y,
        integer_x: param.is_integer() && param != Param::Level,
        // Frame time rises with most parameters; grid-m's dips then rises.
        legend: if param == Param::GridM {
            SeriesLabelPosition::UpperMiddle
        } else {
            SeriesLabelPosition::UpperLeft
        },
        curves: accels
            .iter()
            .map(|&accel| {
                let name = match analysis::slope(points, accel).filter(|_| param == Param::Level) {
                    Some(s) => format!("{} (slope {s:.2})", accel.name()),
                    None => accel.name().to_string(),
                };
                Curve {
                    name,
                    colour: rgb(accel),
                    points: analysis::series(points, accel)
                        .iter()
                        .map(|p| (p.x, p.frame_ms()))
                        .collect(),
                    best: best_of(accel, &|p| (p.x, p.frame_ms())).filter(|_| param != Param::Spp),
                }
            })
            .collect(),
    };
    if param == Param::Level {
        time.title = format!("{subject}: frame time vs scene size (log-log)");
    }
    let mut panels = vec![time];
    if let (Param::Material { .. }, Some(&accel)) = (param, accels.first()) {
        panels.push(rays_by_kind(param, points, accel));
    }
    if points.iter().any(|p| p.error.is_some()) {
        let mse = |p: &Point| p.error.map_or(f64::NAN, |e| e.mse);
        let errors: Vec<f64> = points.iter().map(mse).collect();
        panels.push(Panel {
            title: "image error vs frame time".into(),
            x_label: "frame time (ms, median)".into(),
            y_label: "MSE against the reference".into(),
            y_from_zero: true,
            log_x: false,
            log_y: errors.iter().all(|&e| e > 0.0),
            integer_x: false,
            legend: SeriesLabelPosition::UpperRight,
            curves: accels
                .iter()
                .map(|&accel| {
                    let mut curve: Vec<(f64, f64)> = analysis::series(points, accel)
                        .iter()
                        .map(|p| (p.frame_ms(), mse(p)))
                        .filter(|(_, e)| e.is_finite())
                        .collect();
                    curve.sort_by(|a, b| a.0.total_cmp(&b.0));
                    Curve {
                        name: accel.name().to_string(),
                        colour: rgb(accel),
                        points: curve,
                        best: best_of(accel, &|p| (p.frame_ms(), mse(p))),
                    }
                })
                .collect(),
        });
    }
    panels
}

/// Reflection and refraction rays a pixel against a material parameter
/// (the same for every structure: `accel`'s): where glass loses its
/// refraction rays to total internal reflection, the refraction curve
/// falls.
fn rays_by_kind(param: Param, points: &[Point], accel: AccelKind) -> Panel {
    let series = analysis::series(points, accel);
    let curve = |name: &str, colour: RGBColor, count: fn(&Point) -> u64| Curve {
        name: name.into(),
        colour,
        points: series
            .iter()
            .map(|p| {
                let s = &p.measurement.case.settings;
                let pixels = f64::from(s.width) * f64::from(s.height);
                (p.x, count(p) as f64 / pixels.max(1.0))
            })
            .collect(),
        best: None,
    };
    Panel {
        title: format!("rays by kind vs {param}"),
        x_label: param.axis().to_string(),
        y_label: "rays a pixel".into(),
        y_from_zero: false,
        log_x: false,
        log_y: false,
        integer_x: false,
        legend: SeriesLabelPosition::MiddleRight,
        curves: vec![
            curve("reflection", RGBColor(120, 120, 120), |p| {
                p.measurement.stats.counters.reflection_rays
            }),
            curve("refraction", RGBColor(52, 120, 198), |p| {
                p.measurement.stats.counters.refraction_rays
            }),
        ],
    }
}

/// Whether the frame time chart has a log x and a log y axis: both for
/// the level study (scaling is a power law), x alone when the values span
/// a factor of 8 or more (a doubling sweep).
pub(crate) fn log_axes(param: Param, points: &[Point]) -> (bool, bool) {
    if param == Param::Level {
        return (true, true);
    }
    let low = points.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
    let high = points.iter().map(|p| p.x).fold(0.0, f64::max);
    (low > 0.0 && high / low >= 8.0, false)
}

fn rgb(accel: AccelKind) -> RGBColor {
    let [r, g, b] = colour(accel);
    RGBColor(r, g, b)
}

/// The range of `values`, padded; for a log axis, positive.
fn range(values: impl Iterator<Item = f64>, log: bool, from_zero: bool) -> Range<f64> {
    let (low, high) = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    if !low.is_finite() {
        return if log { 0.1..10.0 } else { 0.0..1.0 };
    }
    if log {
        return low / 1.25..high * 1.25;
    }
    let pad = ((high - low) * 0.05).max(high.abs() * 0.05).max(1e-6);
    let low = if from_zero && low >= 0.0 {
        0.0
    } else {
        low - pad
    };
    low..high + pad
}

/// A tick label: a few significant digits, no trailing zeros.
fn tick(v: &f64) -> String {
    let digits = match v.abs() {
        a if a >= 100.0 => 0,
        a if a >= 10.0 => 1,
        a if a >= 1.0 => 2,
        _ => 3,
    };
    values::format(format!("{v:.digits$}").parse().unwrap_or(*v))
}

fn draw_panel(panel: &Panel, area: &DrawingArea<Chart, Shift>) -> Result<()> {
    let all = || panel.curves.iter().flat_map(|c| c.points.iter());
    let x = range(all().map(|p| p.0), panel.log_x, false);
    let y = range(all().map(|p| p.1), panel.log_y, panel.y_from_zero);
    match (panel.log_x, panel.log_y) {
        (true, true) => draw_axes(panel, area, x.log_scale(), y.log_scale()),
        // A doubling sweep: ticks at the values swept, which the default
        // ticks of a log axis miss below 1.
        (true, false) => {
            let mut ticks: Vec<f64> = all().map(|p| p.0).collect();
            ticks.sort_by(f64::total_cmp);
            ticks.dedup();
            draw_axes(panel, area, x.log_scale().with_key_points(ticks), y)
        }
        (false, true) => draw_axes(panel, area, x, y.log_scale()),
        (false, false) => draw_axes(panel, area, x, y),
    }
}

fn draw_axes<X, Y>(panel: &Panel, area: &DrawingArea<Chart, Shift>, x: X, y: Y) -> Result<()>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, (FONT, 20))
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(64)
        .build_cartesian_2d(x, y)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .x_label_formatter(&|v| {
            if panel.integer_x && v.fract() != 0.0 {
                String::new()
            } else {
                tick(v)
            }
        })
        .y_label_formatter(&tick)
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(drawing)?;
    for (k, curve) in panel.curves.iter().enumerate() {
        let colour = curve.colour;
        chart
            .draw_series(LineSeries::new(
                curve.points.iter().copied(),
                colour.stroke_width(2),
            ))
            .map_err(drawing)?;
        chart
            .draw_series(
                curve
                    .points
                    .iter()
                    .map(|&p| Circle::new(p, 4, colour.filled())),
            )
            .map_err(drawing)?;
        if let Some((at, label)) = &curve.best {
            // A ring around the point, its label up and to the right (one
            // line per structure, so labels of one value do not overlap).
            let marker = EmptyElement::at(*at)
                + Circle::new((0, 0), 9, colour.stroke_width(2))
                + Text::new(
                    format!("{}: {label}", curve.name),
                    (10, -24 - 18 * k as i32),
                    (FONT, 15).into_font().color(&colour),
                );
            chart.draw_series([marker]).map_err(drawing)?;
        }
    }
    let lines: Vec<(&str, RGBColor)> = (panel.curves.iter())
        .map(|c| (c.name.as_str(), c.colour))
        .collect();
    legend(
        &chart.plotting_area().strip_coord_spec(),
        &lines,
        &panel.legend,
        &(FONT, 15).into_text_style(area),
        (WHITE.mix(0.85).filled(), BLACK.into()),
    )
    .map_err(drawing)?;
    Ok(())
}
