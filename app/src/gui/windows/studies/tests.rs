//! The Studies window without a window: applying points, starting
//! without a scene, exporting.

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use tracer::accel::AccelKind;
use tracer::generate::GeneratorName;
use tracer::render::{Encoding, RenderSettings};
use tracer::world::World;

use super::*;
use crate::figures::study_plot;
use crate::measure::benchmark::{RunOptions, Stop};
use crate::measure::study::{self, Param, Study, Subject};

#[test]
fn a_point_sets_its_structure_and_value_in_the_controls() {
    let mut controls = Controls::default();
    let point = |param, value| Applied {
        param,
        value,
        accel: AccelKind::Grid,
        generator: None,
    };
    point(Param::Spp, 3.0).apply_to(&mut controls, 200);
    assert!(controls.render.antialiasing && controls.render.samples == 3);
    assert_eq!(controls.render.accel, AccelKind::Grid);
    point(Param::Resolution, 50.0).apply_to(&mut controls, 200);
    assert_eq!(controls.resolution_scale, 0.25);
    point(Param::Aperture, 0.0).apply_to(&mut controls, 200);
    assert!(!controls.render.depth_of_field);
    // A scale that no whole width gives exactly survives other points.
    controls.resolution_scale = 0.3719;
    point(Param::GridM, 2.5).apply_to(&mut controls, 200);
    assert_eq!(controls.render.grid_multiplier, 2.5);
    assert_eq!(controls.resolution_scale, 0.3719);
    assert_eq!(point(Param::GridM, 2.0).scene_file().unwrap(), None);
}

#[test]
fn a_level_point_opens_its_generated_scene_with_its_structure() {
    let point = Applied {
        param: Param::Level,
        value: 1.0,
        accel: AccelKind::None,
        generator: Some(GeneratorName::Balls),
    };
    let path = point.scene_file().unwrap().unwrap();
    let scene = tracer::scene::parse_scene_file(&path, &tracer::scene::Limits::default()).unwrap();
    assert_eq!(scene.accel, Some(0));
    assert_eq!(World::build(&scene).counts.primitives, 12);
    // Kept only when the test fails, to be inspected.
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn the_level_study_needs_no_open_scene_the_others_say_so() {
    let mut window = StudiesWindow {
        values: "1".into(),
        runs: 1,
        ..StudiesWindow::default()
    };
    let controls = Controls {
        resolution_scale: 0.05,
        ..Controls::default()
    };
    let base = RenderSettings::default();
    window.start(None, &base, &controls, "", || {});
    assert!(!window.is_running());
    assert!(window.message().unwrap().contains("open a scene first"));

    window.param = Param::Level;
    window.start(None, &base, &controls, "", || {});
    assert!(window.is_running(), "{:?}", window.message());
    window.stop();
}

#[test]
fn the_export_writes_the_tables_and_the_chart() {
    let text = "v\nfrom 0 -5 1\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0.01\n\
                resolution 8 8\nl 2 -2 4\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";
    let scene = tracer::scene::parse_scene(text, None, &tracer::scene::Limits::default()).unwrap();
    let subject = Subject::Scene {
        world: Arc::new(World::build(&scene)),
        base: RenderSettings::from_scene(&scene),
    };
    let study = Study {
        param: Param::Depth,
        values: vec![1.0, 2.0],
        structures: vec![AccelKind::Bvh],
        options: RunOptions {
            runs: 1,
            threads: Some(1),
        },
        encoding: Encoding::Srgb,
        reference_samples: None,
    };
    let never = AtomicBool::new(false);
    let stop = Stop {
        now: &never,
        after_frame: &never,
    };
    let outcome = study::run(&study, &subject, stop, &mut |_| {}).unwrap();
    let dir = tracer::scratch::Scratch::new("study-export");
    let written = write_export(&dir, Param::Depth, &outcome.points, "tiny.p3f").unwrap();
    assert_eq!(written, dir.join("study-depth-tiny"));
    let csv = std::fs::read_to_string(written.join("table.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3);
    assert!(
        std::fs::read_to_string(written.join("table.md"))
            .unwrap()
            .contains("| bvh | 1 |")
    );
    let chart = image::open(written.join("chart.png")).unwrap();
    assert_eq!((chart.width(), chart.height()), study_plot::PANEL);
}
