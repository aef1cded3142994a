//! The acceleration section read back from its HTML: one lab measured on
//! balls_low at 16 x 16, each table's rows and the chart's bars checked
//! against the measurements they come from.

use std::sync::atomic::AtomicBool;
use std::sync::{Arc, OnceLock};

use tracer::render::{Encoding, RenderSettings};
use tracer::scene::{Limits, parse_scene_file};
use tracer::world::World;

use super::*;
use crate::measure::benchmark::SamplingColumn;
use crate::reports::lab::{Request, measure};

/// balls_low at 16 x 16, two runs a timing, on one thread: measured once
/// for all the tests (about a second).
fn lab() -> &'static Lab {
    static LAB: OnceLock<Lab> = OnceLock::new();
    LAB.get_or_init(|| {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/balls_low.p3f");
        let scene = parse_scene_file(path.as_ref(), &Limits::default()).unwrap();
        let base = RenderSettings {
            width: 16,
            height: 16,
            samples: 2,
            ..RenderSettings::from_scene(&scene)
        };
        let request = Request {
            scene_name: "balls_low".into(),
            world: Arc::new(World::build(&scene)),
            scene: Arc::new(scene),
            base,
            edits: Vec::new(),
            runs: 2,
            threads: Some(1),
            encoding: Encoding::Srgb,
            pixel: None,
            quick: false,
        };
        measure(&request, &AtomicBool::new(false), &mut |_| {})
            .unwrap()
            .expect("nothing cancelled the lab")
    })
}

/// The rows of the table of class `class` in `html`: each row's
/// `data-row` and its cells' text.
fn rows(html: &str, class: &str) -> Vec<(String, Vec<String>)> {
    let start = html
        .find(&format!("<table class=\"{class}\">"))
        .unwrap_or_else(|| panic!("no {class} table"));
    let table = &html[start..start + html[start..].find("</table>").unwrap()];
    table
        .split("<tr data-row=\"")
        .skip(1)
        .map(|row| {
            let (id, rest) = row.split_once('"').unwrap();
            let cells = rest
                .split("<td>")
                .skip(1)
                .map(|cell| cell.split_once("</td>").unwrap().0.to_string())
                .collect();
            (id.to_string(), cells)
        })
        .collect()
}

fn millis(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

#[test]
fn the_timing_table_has_the_matrix_rows_in_the_courses_words() {
    let lab = lab();
    let rows = rows(&section(lab).unwrap(), "timing");
    assert_eq!(rows.len(), lab.matrix.len());
    assert_eq!(
        rows.len(),
        18,
        "none, grid and BVH, each in 6 configurations"
    );
    for ((id, cells), m) in rows.iter().zip(&lab.matrix) {
        let s = &m.case.settings;
        assert_eq!(id, &m.case.file_stem());
        assert_eq!(cells.len(), TIMING_HEADERS.len(), "{id}");
        assert_eq!(cells[0], s.accel.name(), "{id}");
        let soft = if s.soft_shadows { "yes" } else { "no" };
        assert_eq!(cells[1], soft, "{id}");
        let (aa, dof) = match (s.antialiasing, s.depth_of_field) {
            (false, _) => ("no".to_string(), "-".to_string()),
            (true, false) => ("yes (N = 2)".into(), "no".into()),
            (true, true) => (
                "yes (N = 2)".into(),
                format!("yes ({} px)", m.lens.aperture),
            ),
        };
        assert_eq!((&cells[2], &cells[3]), (&aa, &dof), "{id}");
        let spp = if s.antialiasing { "4" } else { "1" };
        assert_eq!(cells[4], spp, "{id}");
        assert_eq!(cells[5], format!("{:.1}", millis(m.median())), "{id}");
        assert_eq!(cells[8], "2", "{id}: runs");
        assert_eq!(cells[9], m.rays().to_string(), "{id}");
    }
}

#[test]
fn each_bar_is_a_rows_median_with_a_whisker_from_its_fastest_to_slowest_run() {
    let lab = lab();
    let bars = timing_bars(lab);
    assert_eq!(bars.len(), lab.matrix.len());
    for (bar, m) in bars.iter().zip(&lab.matrix) {
        assert_eq!(bar.label, m.case.file_stem().replace('_', " "));
        assert_eq!(bar.value, millis(m.median()), "{}", bar.label);
        assert_eq!(bar.low, millis(m.min()), "{}", bar.label);
        assert_eq!(bar.high, millis(m.max()), "{}", bar.label);
        assert!(bar.low <= bar.value && bar.value <= bar.high);
        // A frame of 16 x 16 pixels takes well under a second.
        assert!(bar.high < 1000.0, "{}: {} ms", bar.label, bar.high);
    }
}

#[test]
fn the_grid_study_has_a_row_per_multiplier_with_its_cells() {
    let lab = lab();
    let points = &lab.grid.points;
    assert!(points.len() >= 2, "{} multipliers", points.len());
    let rows = rows(&section(lab).unwrap(), "grid");
    assert_eq!(rows.len(), points.len());
    for ((id, cells), point) in rows.iter().zip(points) {
        let m = &point.measurement;
        assert_eq!(id, &format!("m{}", point.value));
        assert_eq!(cells[0], format!("{}", point.value));
        let grid = m
            .index
            .grid
            .as_ref()
            .expect("a grid study's frames use the grid");
        let [x, y, z] = grid.cells;
        assert_eq!(cells[1], format!("{x} x {y} x {z}"));
        assert_eq!(cells[5], format!("{:.2}", m.tests_per_ray()));
    }
    // More cells per axis as m grows.
    let first = &rows[0].1[1];
    let last = &rows[rows.len() - 1].1[1];
    assert_ne!(first, last);
}

/// The caption's mean tests per pixel of each structure's plain frame: one
/// sample per pixel, hard shadows, no lens.
#[test]
fn tests_per_pixel_are_the_plain_frames_means() {
    let lab = lab();
    let html = section(lab).unwrap();
    for accel in AccelKind::ALL {
        let plain: Vec<_> = lab
            .views
            .iter()
            .filter(|m| {
                let s = &m.case.settings;
                s.accel == accel && !s.soft_shadows && !s.antialiasing && !s.depth_of_field
            })
            .collect();
        assert_eq!(plain.len(), 1, "{}", accel.name());
        let values = plain[0].views.as_ref().unwrap().values(View::Tests);
        let tests: Vec<f32> = values.into_iter().flatten().collect();
        assert_eq!(tests.len(), 16 * 16, "{}", accel.name());
        let mean = tests.iter().sum::<f32>() / tests.len() as f32;
        let caption = format!("{}: {mean:.1} tests per pixel on average", accel.name());
        assert!(html.contains(&caption), "{caption}");
    }
    // The BVH's soft-shadowed frame costs more: picking it would change
    // the BVH's caption above. (The views of the frames with more samples
    // are means per sample.)
    let bvh_tests = |soft: bool, spp: u32| {
        let m = lab
            .views
            .iter()
            .find(|m| {
                let s = &m.case.settings;
                s.accel == AccelKind::Bvh
                    && s.soft_shadows == soft
                    && s.samples_per_pixel() == spp
                    && !s.depth_of_field
            })
            .unwrap();
        let values = m.views.as_ref().unwrap().values(View::Tests);
        values.into_iter().flatten().sum::<f32>()
    };
    assert!(bvh_tests(true, 1) > bvh_tests(false, 1));
}

#[test]
fn each_structure_is_built_once_and_its_size_is_said() {
    let lab = lab();
    let rows = rows(&section(lab).unwrap(), "builds");
    let names: Vec<&str> = rows.iter().map(|(id, _)| id.as_str()).collect();
    let expected: Vec<&str> = AccelKind::ALL.iter().map(|a| a.name()).collect();
    assert_eq!(names, expected);
    for (id, cells) in &rows {
        assert_eq!(&cells[0], id);
    }
    let size = |accel: AccelKind| {
        let at = AccelKind::ALL.iter().position(|&a| a == accel).unwrap();
        rows[at].1[3].as_str()
    };
    let built = |accel: AccelKind| {
        let frame = lab.row(accel, false, SamplingColumn::Single).unwrap();
        &frame.index
    };
    assert_eq!(size(AccelKind::None), "-");
    let g = built(AccelKind::Grid).grid.as_ref().unwrap();
    let [x, y, z] = g.cells;
    assert_eq!(
        size(AccelKind::Grid),
        format!("{x} x {y} x {z} cells, {} references", g.references)
    );
    let nodes = built(AccelKind::Bvh).bvh_nodes.unwrap();
    assert!(nodes > 0);
    assert_eq!(size(AccelKind::Bvh), format!("{nodes} nodes"));
}

#[test]
fn the_section_holds_the_table_chart_study_views_and_builds() {
    let html = section(lab()).unwrap();
    assert!(html.starts_with("<section id=\"acceleration\">"));
    for part in [
        "<h3>The timing table</h3>",
        "<svg",
        "<h3>The grid multiplier m</h3>",
        "<h3>Tests per pixel</h3>",
        "<h3>Building the structures</h3>",
    ] {
        assert!(html.contains(part), "{part}");
    }
}
