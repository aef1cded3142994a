//! Section 3, stochastic sampling: anti-aliasing, depth of field and soft
//! shadows each off and on (the matrix's BVH frames, so their times are the
//! timing table's), a magnified crop where anti-aliasing changes the most,
//! and the error against samples as charts.

use anyhow::{Result, bail};
use image::RgbImage;
use tracer::accel::AccelKind;

use super::html::{escape, figure, image, table, titled_section};
use super::svg::{Series, YAxis, line_chart};
use super::{Lab, ms};
use crate::describe::millis;
use crate::measure::benchmark::{Measurement, SamplingColumn};
use crate::measure::study::Point;

/// Side of the crop, in pixels of the image, before magnifying.
const CROP: u32 = 24;
/// How many times the crop is magnified.
const ZOOM: u32 = 6;

/// Where `a` and `b` differ the most over a `side` x `side` window: its
/// top-left corner.
fn busiest_window(a: &RgbImage, b: &RgbImage, side: u32) -> (u32, u32) {
    let (w, h) = a.dimensions();
    let difference = |x: u32, y: u32| -> u32 {
        let (p, q) = (a.get_pixel(x, y), b.get_pixel(x, y));
        (0..3).map(|c| u32::from(p[c].abs_diff(q[c]))).sum()
    };
    let mut best = ((0, 0), 0);
    for y in (0..=h.saturating_sub(side)).step_by(2) {
        for x in (0..=w.saturating_sub(side)).step_by(2) {
            let mut total = 0;
            for dy in (0..side.min(h)).step_by(2) {
                for dx in (0..side.min(w)).step_by(2) {
                    total += difference(x + dx, y + dy);
                }
            }
            if total > best.1 {
                best = ((x, y), total);
            }
        }
    }
    best.0
}

fn magnified(image: &RgbImage, (x, y): (u32, u32), side: u32) -> RgbImage {
    let crop = image::imageops::crop_imm(image, x, y, side, side).to_image();
    image::imageops::resize(
        &crop,
        crop.width() * ZOOM,
        crop.height() * ZOOM,
        image::imageops::FilterType::Nearest,
    )
}

fn shown(m: &Measurement, what: &str) -> Result<String> {
    let caption = format!("{what}: {} ms, {} rays", ms(m.median()), m.rays());
    Ok(figure(&image(&m.image, &caption, 300)?, &caption))
}

pub(crate) fn section(lab: &Lab) -> Result<String> {
    let row = |soft, sampling| lab.row(AccelKind::Bvh, soft, sampling);
    let (Some(plain), Some(aa), Some(dof), Some(soft), Some(soft_aa)) = (
        row(false, SamplingColumn::Single),
        row(false, SamplingColumn::Antialiasing),
        row(false, SamplingColumn::AntialiasingDof),
        row(true, SamplingColumn::Single),
        row(true, SamplingColumn::Antialiasing),
    ) else {
        bail!("the timing matrix lacks a BVH row");
    };
    let n = lab.base.samples;
    let side = CROP.min(plain.image.width()).min(plain.image.height());
    let corner = busiest_window(&plain.image, &aa.image, side);
    let crop_caption = |what: &str| {
        format!(
            "{what}, the {side} x {side} pixels at ({}, {}) magnified {ZOOM} times",
            corner.0, corner.1
        )
    };
    let crops = figure(
        &image(
            &magnified(&plain.image, corner, side),
            &crop_caption("without"),
            300,
        )?,
        &crop_caption("Without anti-aliasing"),
    ) + &figure(
        &image(
            &magnified(&aa.image, corner, side),
            &crop_caption("with"),
            300,
        )?,
        &crop_caption(&format!("With anti-aliasing N = {n}")),
    );
    let aperture = dof.lens.aperture;
    let body = format!(
        "<h3>Anti-aliasing</h3>\n<p>Jittered sampling: N x N = {spp} samples per pixel, each \
         at a random point of its stratum.</p>\n<div class=\"figures\">{}{}</div>\n\
         <div class=\"figures\">{crops}</div>\n\
         <h3>Depth of field</h3>\n<p>A thin lens of aperture {aperture} pixels focused at {} \
         times the view-plane distance; each sample takes another point of the lens.</p>\n\
         <div class=\"figures\">{}{}</div>\n\
         <h3>Soft shadows</h3>\n<p>Lights become squares. The course's two modes: without \
         anti-aliasing, N x N shadow rays per light over the square; with anti-aliasing, one \
         shadow ray per sample, the samples averaging them.</p>\n<div class=\"figures\">{}{}{}</div>\n\
         {}",
        shown(plain, "Anti-aliasing off")?,
        shown(aa, &format!("Anti-aliasing N = {n}"))?,
        lab.base.chosen_lens(&lab.request.scene.view).focal,
        shown(aa, "Depth of field off (anti-aliasing on)")?,
        shown(dof, "Depth of field on")?,
        shown(plain, "Hard shadows")?,
        shown(soft, "Soft shadows without anti-aliasing")?,
        shown(soft_aa, "Soft shadows with anti-aliasing")?,
        error_charts(lab) + &adaptive_charts(lab),
        spp = n * n,
    );
    let how = format!(
        "<p class=\"how\">Images and times are the BVH rows of the timing table (section 4): \
         median of {} run(s) on {} thread(s).</p>\n",
        lab.runs, lab.threads
    );
    Ok(titled_section(
        "sampling",
        "3. Stochastic sampling",
        &(body + &how),
    ))
}

/// The `noise-threshold` study beside the `spp` study: PSNR against frame
/// time for both, against the same reference, and the adaptive points as
/// a table. Where the adaptive curve lies above the uniform one, it
/// reaches an error in less time.
fn adaptive_charts(lab: &Lab) -> String {
    let Some(reference) = &lab.samples.reference else {
        return String::new();
    };
    let series = |name: &str, colour, points: &[Point]| Series {
        name: name.to_string(),
        colour,
        points: points
            .iter()
            .filter_map(|p| Some((millis(p.measurement.median()), p.error?.psnr)))
            .filter(|(_, y)| y.is_finite())
            .collect(),
    };
    let points = &lab.adaptive.points;
    if points.is_empty() {
        return String::new();
    }
    let chart = line_chart(
        "PSNR against frame time",
        "frame ms",
        "PSNR dB",
        YAxis::Fitted,
        &[
            series("uniform N x N", [52, 120, 198], &lab.samples.points),
            series("adaptive", [214, 96, 40], points),
        ],
    );
    let knobs = points
        .first()
        .and_then(|p| p.measurement.case.settings.adaptive());
    let rows: Vec<(String, Vec<String>)> = points
        .iter()
        .map(|p| {
            let spp = p.measurement.stats.adaptive;
            let mut cells = vec![
                format!("{}", p.value),
                spp.map_or("-".into(), |a| format!("{:.1}", a.mean_spp())),
                spp.map_or("-".into(), |a| a.max_spp.to_string()),
            ];
            cells.extend(timed_error_cells(p));
            (format!("t{}", p.value), cells)
        })
        .collect();
    format!(
        "<h3>Adaptive sampling</h3>\n<p>Not in the course: each pixel takes samples until its \
         estimated error (its last pass's mean against its earlier samples', pooled with its \
         neighbours') is below a noise threshold, from {} up to {} samples, so flat areas stop \
         early and edges, penumbrae and lens blur refine. Against the same reference as \
         uniform N x N above; where its curve lies above uniform's, it reaches an error in \
         less time.</p>\n<div class=\"figures\">{chart}</div>\n{}<p class=\"how\">{}</p>\n",
        knobs.map_or(0, |a| a.min_spp),
        knobs.map_or(0, |a| a.max_spp),
        table(
            "adaptive",
            &[
                "threshold",
                "samples/px",
                "most/px",
                "frame ms",
                "MSE",
                "PSNR dB",
                "FLIP"
            ],
            &rows
        ),
        escape(&format!(
            "Reference: N = {} ({} samples per pixel). Frame times: median of {} run(s) on {} \
             thread(s), the same as the uniform points'.",
            reference.samples,
            reference.samples.pow(2),
            lab.runs,
            lab.threads
        ))
    )
}

/// A study point's frame time, MSE, PSNR and FLIP as table cells ("-"
/// for an error not measured).
fn timed_error_cells(p: &Point) -> [String; 4] {
    let metric = |f: &dyn Fn(&crate::measure::ab::Metrics) -> String| {
        p.error.as_ref().map_or("-".to_string(), f)
    };
    [
        ms(p.measurement.median()),
        metric(&|m| format!("{:.2}", m.mse)),
        metric(&|m| format!("{:.2}", m.psnr)),
        metric(&|m| format!("{:.4}", m.flip)),
    ]
}

/// The `spp` study: MSE, PSNR and FLIP against the reference, as charts
/// and a table.
fn error_charts(lab: &Lab) -> String {
    let points = &lab.samples.points;
    let Some(reference) = &lab.samples.reference else {
        return String::new();
    };
    let series = |name: &str, value: &dyn Fn(&crate::measure::ab::Metrics) -> f64| Series {
        name: name.to_string(),
        colour: [52, 120, 198],
        points: points
            .iter()
            .filter_map(|p| Some((p.value, value(p.error.as_ref()?))))
            .filter(|(_, y)| y.is_finite())
            .collect(),
    };
    let charts = [
        line_chart(
            "MSE (8-bit units)",
            "N",
            "MSE",
            YAxis::FromZero,
            &[series("MSE", &|m| m.mse)],
        ),
        line_chart(
            "PSNR (dB)",
            "N",
            "dB",
            YAxis::Fitted,
            &[series("PSNR", &|m| m.psnr)],
        ),
        line_chart(
            "FLIP",
            "N",
            "mean FLIP",
            YAxis::FromZero,
            &[series("FLIP", &|m| f64::from(m.flip))],
        ),
    ]
    .concat();
    let rows: Vec<(String, Vec<String>)> = points
        .iter()
        .map(|p| {
            let mut cells = vec![
                format!("{}", p.value),
                format!("{}", (p.value * p.value) as u64),
            ];
            cells.extend(timed_error_cells(p));
            (format!("n{}", p.value), cells)
        })
        .collect();
    format!(
        "<h3>Error against samples</h3>\n<p>Each N against a reference of N = {} ({} samples \
         per pixel), anti-aliasing on, BVH.</p>\n<div class=\"figures\">{charts}</div>\n{}\
         <p class=\"how\">{}</p>\n",
        reference.samples,
        reference.samples.pow(2),
        table(
            "errors",
            &["N", "samples/px", "frame ms", "MSE", "PSNR dB", "FLIP"],
            &rows
        ),
        escape(&format!(
            "Frame times: median of {} run(s) on {} thread(s); errors of the last frame (every \
             frame is the same image).",
            lab.runs, lab.threads
        ))
    )
}
