//! Studies measured for real on tiny scenes.

use std::sync::atomic::AtomicBool;

use super::*;
use crate::figures::study_plot;

fn world() -> Arc<World> {
    let text = "v\nfrom 0 -5 1\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0.01\n\
                resolution 12 8\nl 2 -2 4\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\ns 1 1 0 0.5\n";
    let scene = tracer::scene::parse_scene(text, None, &tracer::scene::Limits::default()).unwrap();
    Arc::new(World::build(&scene))
}

fn study(param: Param, values: &str, structures: &[AccelKind]) -> Study {
    Study {
        param,
        values: values::parse(values).unwrap(),
        structures: structures.to_vec(),
        options: RunOptions {
            runs: 2,
            threads: Some(1),
        },
        encoding: Encoding::Linear,
        reference_samples: None,
    }
}

fn scene() -> Subject {
    Subject::Scene {
        world: world(),
        base: RenderSettings {
            width: 12,
            height: 8,
            ..RenderSettings::default()
        },
    }
}

fn never() -> AtomicBool {
    AtomicBool::new(false)
}

#[test]
fn a_grid_m_study_measures_every_point_on_one_grid_each() {
    let study = study(
        Param::GridM,
        "0.5..2:x2",
        &[AccelKind::Grid, AccelKind::Bvh],
    );
    let (now, after) = (never(), never());
    let stop = Stop {
        now: &now,
        after_frame: &after,
    };
    let mut measured = Vec::new();
    let outcome = run(&study, &scene(), stop, &mut |e| {
        if let StudyEvent::Measured { point, result } = e {
            measured.push((point, result.accel(), result.value));
        }
    })
    .unwrap();
    assert!(!outcome.cancelled);
    assert_eq!(
        measured,
        study
            .plan()
            .into_iter()
            .enumerate()
            .map(|(i, (a, v))| (i, a, v))
            .collect::<Vec<_>>()
    );
    let points = &outcome.points;
    assert_eq!(points.len(), 6);
    for p in points {
        assert_eq!(p.measurement.times.len(), 2);
        assert_eq!(p.x, p.value);
        assert_eq!(p.measurement.case.settings.grid_multiplier, p.value as f32);
        assert!(p.error.is_none());
    }
    // Each m has its own grid; the BVH is built once for its three points.
    let grids: Vec<Option<f32>> = points[..3]
        .iter()
        .map(|p| p.measurement.index.grid_multiplier)
        .collect();
    assert_eq!(grids, [Some(0.5), Some(1.0), Some(2.0)]);
    let bvh_build = points[3].measurement.index.build_time;
    assert!(
        points[3..]
            .iter()
            .all(|p| p.measurement.index.build_time == bvh_build)
    );
    // The grid's fastest m is marked; m changes nothing for the BVH.
    let best = analysis::best(Param::GridM, points);
    assert_eq!(best.len(), 1);
    for (i, why) in best {
        assert_eq!(why, analysis::Best::Fastest);
        let p = &points[i];
        assert!(
            points
                .iter()
                .filter(|q| q.accel() == p.accel())
                .all(|q| q.frame_ms() >= p.frame_ms())
        );
    }
}

#[test]
fn the_spp_study_measures_error_against_a_reference() {
    let study = study(Param::Spp, "1..3", &[AccelKind::Bvh]);
    let (now, after) = (never(), never());
    let stop = Stop {
        now: &now,
        after_frame: &after,
    };
    let mut preparing = false;
    let outcome = run(&study, &scene(), stop, &mut |e| {
        preparing |= matches!(e, StudyEvent::Preparing { .. });
    })
    .unwrap();
    assert!(preparing);
    let reference = outcome.reference.as_ref().unwrap();
    assert_eq!(reference.samples, 6);
    let errors: Vec<f64> = outcome
        .points
        .iter()
        .map(|p| p.error.unwrap().mse)
        .collect();
    assert_eq!(errors.len(), 3);
    assert!(errors.iter().all(|&e| e > 0.0), "{errors:?}");
    for p in &outcome.points {
        let s = &p.measurement.case.settings;
        assert!(s.antialiasing);
        assert_eq!(f64::from(s.samples), p.value);
    }
}

/// A noise-threshold study given the spp study's reference renders none
/// and measures what it would have measured against its own: the same
/// image. A reference of another N is refused.
#[test]
fn a_reference_is_reused_as_if_rendered_again() {
    let (now, after) = (never(), never());
    let stop = || Stop {
        now: &now,
        after_frame: &after,
    };
    let spp = run(
        &study(Param::Spp, "1..3", &[AccelKind::Bvh]),
        &scene(),
        stop(),
        &mut |_| {},
    )
    .unwrap();
    let reference = spp.reference.clone().unwrap();
    let adaptive = Study {
        reference_samples: Some(reference.samples),
        ..study(Param::NoiseThreshold, "0.01..0.04:x2", &[AccelKind::Bvh])
    };
    let own = run(&adaptive, &scene(), stop(), &mut |_| {}).unwrap();
    let mut preparing = false;
    let reused = run_with_reference(&adaptive, &scene(), reference.clone(), stop(), &mut |e| {
        preparing |= matches!(e, StudyEvent::Preparing { .. });
    })
    .unwrap();
    assert!(!preparing, "nothing rendered before the points");
    let errors =
        |o: &StudyOutcome| -> Vec<f64> { o.points.iter().map(|p| p.error.unwrap().mse).collect() };
    assert_eq!(errors(&reused), errors(&own));
    assert_eq!(errors(&reused).len(), 3);

    let other = ReferenceRender {
        samples: reference.samples + 1,
        ..reference
    };
    let refused = run_with_reference(&adaptive, &scene(), other, stop(), &mut |_| {}).unwrap_err();
    assert!(
        refused.to_string().contains("takes a reference of N = 6"),
        "{refused}"
    );
}

#[test]
fn the_level_study_generates_each_level_once_and_counts_primitives() {
    let study = study(Param::Level, "0..1", &[AccelKind::None, AccelKind::Bvh]);
    let subject = Subject::Generated {
        generator: GeneratorName::Balls,
        seed: 0,
        settings: Box::new(|scene| RenderSettings {
            width: 16,
            height: 16,
            ..RenderSettings::from_scene(scene)
        }),
    };
    let (now, after) = (never(), never());
    let stop = Stop {
        now: &now,
        after_frame: &after,
    };
    let mut generated = 0;
    let outcome = run(&study, &subject, stop, &mut |e| {
        if let StudyEvent::Preparing { what, .. } = e {
            assert!(what.contains("balls level"), "{what}");
            generated += 1;
        }
    })
    .unwrap();
    assert_eq!(generated, 2);
    let points = &outcome.points;
    assert_eq!(points.len(), 4);
    // Level 0 is one sphere, level 1 ten (plus whatever floor the scene has).
    assert!(points[0].primitives < points[2].primitives);
    assert_eq!(points[0].primitives, points[1].primitives);
    assert_eq!(points[2].x, points[2].primitives as f64);
    // Brute force tests every primitive for every ray it traces.
    assert!(points[2].measurement.tests_per_ray() > points[0].measurement.tests_per_ray());
    assert!(analysis::slope(points, AccelKind::None).is_some());
}

#[test]
fn stopping_after_the_frame_keeps_that_frame() {
    let study = study(Param::Depth, "1..4", &[AccelKind::Bvh]);
    let (now, after) = (never(), never());
    let stop = Stop {
        now: &now,
        after_frame: &after,
    };
    let outcome = run(&study, &scene(), stop, &mut |e| {
        if let StudyEvent::Rendering { .. } = e {
            after.store(true, Ordering::Relaxed);
        }
    })
    .unwrap();
    assert!(outcome.cancelled);
    assert_eq!(outcome.points.len(), 1);
    assert_eq!(outcome.points[0].measurement.times.len(), 1);
    // Stopping at once keeps nothing of the frame under way.
    let (now, after) = (AtomicBool::new(true), never());
    let stopped = run(
        &study,
        &scene(),
        Stop {
            now: &now,
            after_frame: &after,
        },
        &mut |_| {},
    )
    .unwrap();
    assert!(stopped.cancelled && stopped.points.is_empty());
}

#[test]
fn bad_studies_are_refused_before_rendering() {
    let (now, after) = (never(), never());
    let stop = Stop {
        now: &now,
        after_frame: &after,
    };
    let error = |study: Study, subject: Subject| {
        run(&study, &subject, stop, &mut |_| {
            panic!("nothing should render")
        })
        .unwrap_err()
        .to_string()
    };
    assert!(error(study(Param::Spp, "0.5", &[AccelKind::Bvh]), scene()).contains("whole numbers"));
    assert!(error(study(Param::Spp, "0..2", &[AccelKind::Bvh]), scene()).contains("out of range"));
    assert!(error(study(Param::GridM, "0..2", &[AccelKind::Grid]), scene()).contains("above 0"));
    assert!(error(study(Param::Depth, "1", &[]), scene()).contains("no structures"));
    assert!(error(study(Param::Level, "1", &[AccelKind::Bvh]), scene()).contains("generator"));
    let balls = || Subject::Generated {
        generator: GeneratorName::Balls,
        seed: 0,
        settings: Box::new(RenderSettings::from_scene),
    };
    assert!(
        error(study(Param::Level, "1..9", &[AccelKind::Bvh]), balls()).contains("levels 0..=5")
    );
    assert!(error(study(Param::Depth, "1", &[AccelKind::Bvh]), balls()).contains("scene file"));
}

#[test]
fn parameters_turn_their_feature_on() {
    let mut s = RenderSettings {
        width: 200,
        height: 100,
        ..RenderSettings::default()
    };
    Param::Resolution.apply(&mut s, 64.0);
    assert_eq!((s.width, s.height), (64, 32));
    Param::LightSize.apply(&mut s, 0.5);
    assert!(s.soft_shadows && s.light_size == 0.5);
    Param::Aperture.apply(&mut s, 0.0);
    assert!(!s.depth_of_field);
    Param::Aperture.apply(&mut s, 4.0);
    assert!(s.depth_of_field && s.lens_override.aperture == Some(4.0));
    assert_eq!("Grid-M".parse::<Param>(), Ok(Param::GridM));
    assert!(
        "speed"
            .parse::<Param>()
            .unwrap_err()
            .contains("grid-m, spp")
    );
    for param in Param::ALL {
        let values = values::parse(&param.default_values(&s)).unwrap();
        assert!(values.iter().all(|&v| param.check(v).is_ok()), "{param}");
    }
}

#[test]
fn the_chart_is_drawn_with_a_panel_per_view() {
    let study = study(Param::Spp, "1..3", &[AccelKind::Grid, AccelKind::Bvh]);
    let (now, after) = (never(), never());
    let stop = Stop {
        now: &now,
        after_frame: &after,
    };
    let outcome = run(&study, &scene(), stop, &mut |_| {}).unwrap();
    let image = study_plot::chart(Param::Spp, &outcome.points, "tiny").unwrap();
    assert_eq!(
        image.dimensions(),
        (2 * study_plot::PANEL.0, study_plot::PANEL.1)
    );
    // Lines in each structure's colour were drawn.
    for accel in [AccelKind::Grid, AccelKind::Bvh] {
        let colour = image::Rgb(study_plot::colour(accel));
        assert!(image.pixels().any(|p| *p == colour), "{accel:?}");
    }
    let mut timed_only = outcome.points[..1].to_vec();
    timed_only[0].error = None;
    let single = study_plot::chart(Param::Depth, &timed_only, "tiny").unwrap();
    assert_eq!(single.dimensions(), study_plot::PANEL);
}
