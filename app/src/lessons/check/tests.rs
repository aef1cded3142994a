//! Each kind of check, on small scenes whose answers are known by
//! construction, passing when it should and failing when it should.

use std::sync::Arc;

use tracer::accel::AccelKind;
use tracer::render::{AdaptiveSampling, Sampling};
use tracer::scene::{Limits, parse_scene};

use super::quantity::Reads;
use super::*;
use crate::lessons::state::{LessonState, SideState};
use crate::load::{self, Loaded, SceneSource};

/// A triangle at z = 0 facing a camera on the z axis, a light above and
/// in front, and a small sphere on the segment from the triangle's centre
/// to the light: the centre pixel's eye ray hits the triangle (object 0)
/// and its one shadow ray is blocked by the sphere (object 1).
const SHADOWED: &str = "
v
from 0 0 10
at 0 0 0
up 0 1 0
angle 30
hither 0.01
resolution 32 32
l 0 10 5 1 1 1
f 0.8 0.8 0.8 1 0 0 0 0 1 0 1
p 3
-2 -2 0
2 -2 0
0 2 0
f 0.9 0.1 0.1 1 0 0 0 0 1 0 1
s 0 4 2 0.5
";

/// A camera inside a glass sphere, off its centre and looking across it:
/// the eye ray meets the surface from inside at 64 degrees, beyond glass's
/// critical angle of 42: total internal reflection.
const INSIDE_GLASS: &str = "
v
from 0 0 0.9
at 1 0 0.9
up 0 0 1
angle 20
hither 0.001
resolution 9 9
l 0 0 0 1 1 1
f 1 1 1 0 1 1 1 0.1 100 0.9 1.5
s 0 0 0 1
";

fn state_of(p3f: &str) -> LessonState {
    let scene = parse_scene(p3f, None, &Limits::default()).unwrap();
    let world = Arc::new(load::build_with_sky(&scene));
    LessonState::new(scene, world)
}

fn value(of: &str, is: &str) -> Check {
    Check::Value {
        of: Quantity::parse(of).unwrap(),
        is: Expect::parse(is).unwrap(),
        side: Which::A,
    }
}

fn done(check: &Check, state: &LessonState) -> bool {
    evaluate(check, state).is_done()
}

#[test]
fn a_setting_check_reads_the_settings_as_they_are() {
    let mut state = state_of(SHADOWED);
    let check = value("spp", ">= 4");
    state.a.settings.samples = 2;
    let verdict = evaluate(&check, &state);
    assert_eq!(
        verdict,
        Verdict::NotYet("spp is 2, expected >= 4".into()),
        "{verdict:?}"
    );
    state.a.settings.samples = 4;
    assert!(done(&check, &state));
    let accel = value("accel", "grid");
    state.a.settings.accel = AccelKind::Bvh;
    assert!(!done(&accel, &state));
    state.a.settings.accel = AccelKind::Grid;
    assert!(done(&accel, &state));
}

#[test]
fn a_scene_check_reads_the_edited_scene() {
    let mut state = state_of(SHADOWED);
    let check = value("object 1 radius", "0.5");
    assert!(done(&check, &state));
    let ior = value("object 1 ior", "1.33 +- 1%");
    assert!(!done(&ior, &state));
    let edit = |line: &str| crate::lessons::actions::Actions {
        edits: vec![crate::lessons::actions::Located {
            value: line.to_string(),
            line: 1,
            column: 1,
        }],
        ..Default::default()
    };
    state.apply(&edit("object 1 t 0.5"), "test").unwrap();
    state.apply(&edit("object 1 ior 1.33"), "test").unwrap();
    assert!(done(&ior, &state));
    assert!(done(&value("object 0 kind", "triangle"), &state));
    let missing = evaluate(&value("object 7 ior", "1"), &state);
    assert!(missing.reason().contains("no object 7"), "{missing:?}");
}

#[test]
fn the_focus_error_is_the_plane_in_focus_against_an_object() {
    let mut state = state_of(SHADOWED);
    // The sphere's centre is 8 along the view from the eye; the view-plane
    // distance is 10.
    let check = value("focus-error 1", "<= 0.05");
    state.a.settings.lens_override.focal = Some(1.0);
    assert!(!done(&check, &state));
    state.a.settings.lens_override.focal = Some(0.8);
    assert!(done(&check, &state));
}

#[test]
fn a_ray_tree_check_reads_the_pinned_pixels_tree() {
    let mut state = state_of(SHADOWED);
    let blocked = Check::All {
        checks: vec![
            value("tree eye-kind", "triangle"),
            value("tree blocked-shadow-rays", "1"),
            value("tree blocker 0", "1"),
        ],
    };
    let verdict = evaluate(&blocked, &state);
    assert_eq!(verdict, Verdict::NotYet("no pixel is pinned".into()));
    state.pixel = Some((16, 16));
    let verdict = evaluate(&blocked, &state);
    assert!(verdict.is_done(), "{verdict:?}");
    // A second light straight above the camera: each light has its own
    // shadow ray, and only light 0's is blocked.
    let mut two_lights = state.clone();
    two_lights.a = edited(&state, "light 1 add l 0 0 20");
    assert!(done(&value("tree blocker 1", "none"), &two_lights));
    assert!(done(&value("tree blocker 0", "1"), &two_lights));
    // Move the sphere out of the light's way: lit, blocked by nothing.
    state.a = edited(&state, "object 1 centre 5 -4 2");
    let verdict = evaluate(&blocked, &state);
    // Every failing part is said, not only the first.
    assert_eq!(
        verdict,
        Verdict::NotYet(
            "tree blocked-shadow-rays is 0, expected 1; tree blocker 0 is none, expected 1".into()
        )
    );
    assert!(done(&value("tree blocker 0", "none"), &state));
}

fn edited(state: &LessonState, line: &str) -> SideState {
    let mut copy = state.clone();
    copy.apply(
        &crate::lessons::actions::Actions {
            edits: vec![crate::lessons::actions::Located {
                value: line.into(),
                line: 1,
                column: 1,
            }],
            ..Default::default()
        },
        "test",
    )
    .unwrap();
    copy.a
}

#[test]
fn total_internal_reflection_shows_in_the_tree() {
    let mut state = state_of(INSIDE_GLASS);
    state.pixel = Some((4, 4));
    let tir = value("tree tir", "on");
    assert!(done(&tir, &state), "{:?}", evaluate(&tir, &state));
    assert!(done(&value("tree eye-outside", "off"), &state));
    // Water's critical angle (49 degrees) is still below 64; at ior 1.1 it
    // is 65 degrees and the ray gets out.
    state.a = edited(&state, "object 0 ior 1.1");
    assert!(!done(&tir, &state));
}

#[test]
fn an_answer_is_checked_against_a_value_computed_now() {
    let mut state = state_of(SHADOWED);
    state.pixel = Some((16, 16));
    let check = Check::Answer {
        question: "How many shadow rays does this pixel spawn?".into(),
        of: Quantity::parse("tree shadow-rays").unwrap(),
        tolerance: None,
        choices: vec![],
        side: Which::A,
    };
    assert_eq!(
        evaluate(&check, &state),
        Verdict::NotYet("no answer yet".into())
    );
    state.answer = Some("4".into());
    assert_eq!(
        evaluate(&check, &state),
        Verdict::Wrong("4 is not right".into())
    );
    state.answer = Some(" 1 ".into());
    assert!(done(&check, &state));
    // With soft shadows at N = 3 the same pixel spawns 3 x 3: the right
    // answer follows the state, the lesson never states it.
    state.a.settings.soft_shadows = true;
    state.a.settings.samples = 3;
    assert!(!done(&check, &state));
    state.answer = Some("9".into());
    assert!(done(&check, &state), "{:?}", evaluate(&check, &state));
}

#[test]
fn a_picked_answer_must_be_one_of_the_choices() {
    let mut state = state_of(SHADOWED);
    state.pixel = Some((16, 16));
    let check = Check::Answer {
        question: "Which object blocks the light?".into(),
        of: Quantity::parse("tree blocker 0").unwrap(),
        tolerance: None,
        choices: vec!["0".into(), "1".into(), "none".into()],
        side: Which::A,
    };
    state.answer = Some("2".into());
    assert!(matches!(evaluate(&check, &state), Verdict::NotYet(_)));
    state.answer = Some("none".into());
    assert!(matches!(evaluate(&check, &state), Verdict::Wrong(_)));
    state.answer = Some("1".into());
    assert!(done(&check, &state));
}

/// The bundled ten-sphere flake at 24 x 24: enough objects for structures
/// to matter.
pub(super) fn balls() -> LessonState {
    let loaded = Loaded::read(SceneSource::Bundled("balls_low".into()), &[], &mut |_| {}).unwrap();
    let mut state = LessonState::new(loaded.scene, loaded.world);
    state.a.settings.width = 24;
    state.a.settings.height = 24;
    state
}

/// A speedup of B over A, compared by `by`, expected to be `is`.
fn speedup(is: &str, by: By) -> Check {
    Check::Measure {
        metric: Metric::Speedup,
        is: Expect::parse(is).unwrap(),
        by,
        values: vec![],
    }
}

#[test]
fn a_speedup_is_measured_between_the_sides() {
    let mut state = balls();
    let check = speedup(">= 2", By::Work);
    let verdict = evaluate(&check, &state);
    assert!(verdict.reason().contains("no side B"), "{verdict:?}");
    state.a.settings.accel = AccelKind::None;
    let mut b = state.a.clone();
    state.b = Some(b.clone());
    let same = evaluate(&check, &state);
    assert!(same.reason().contains("B is 1x faster"), "{same:?}");
    b.settings.accel = AccelKind::Bvh;
    state.b = Some(b.clone());
    assert!(done(&check, &state), "{:?}", evaluate(&check, &state));
    state.b = Some(state.a.clone());
    state.a = b;
    let reversed = evaluate(&check, &state);
    assert!(reversed.reason().contains("A is "), "{reversed:?}");
    assert!(
        reversed.reason().contains("x faster (A costs 0."),
        "{reversed:?}"
    );
}

/// The samples a check reads are those the side's render took: N x N
/// everywhere with uniform sampling; with adaptive sampling the minimum in
/// the empty background and more along the triangle's edges.
#[test]
fn the_samples_pixels_took_are_read_from_the_render() {
    let mut state = state_of(SHADOWED);
    state.a.settings.antialiasing = true;
    state.a.settings.samples = 2;
    let read =
        |of: &str, state: &LessonState| Quantity::parse(of).unwrap().read(state, Which::A).unwrap();
    assert_eq!(read("sampling", &state), Value::Word("uniform".into()));
    assert_eq!(read("noise-threshold", &state), Value::Bool(false));
    assert_eq!(read("samples mean", &state), Value::Number(4.0));
    assert_eq!(read("samples max", &state), Value::Number(4.0));
    let verdict = evaluate(&value("pixel samples", "4"), &state);
    assert_eq!(verdict, Verdict::NotYet("no pixel is pinned".into()));

    let adaptive = AdaptiveSampling::for_samples(4, 0.01);
    state.a.settings.sampling = Sampling::Adaptive(adaptive);
    state.pixel = Some((0, 0));
    assert_eq!(read("sampling", &state), Value::Word("adaptive".into()));
    assert_eq!(
        read("noise-threshold", &state),
        Value::Number(0.01f32.into())
    );
    let min = f64::from(adaptive.min_spp);
    assert_eq!(read("pixel samples", &state), Value::Number(min));
    let (Value::Number(mean), Value::Number(max)) =
        (read("samples mean", &state), read("samples max", &state))
    else {
        panic!("sample counts are numbers");
    };
    assert!(min < mean && mean < max, "{min} < {mean} < {max}");
    assert!(max <= f64::from(adaptive.max_spp));

    state.a.settings.width = 16;
    state.pixel = Some((20, 20));
    let verdict = evaluate(&value("pixel samples", ">= 1"), &state);
    assert!(
        verdict.reason().contains("outside the 16x32 image"),
        "{verdict:?}"
    );
}

#[test]
fn flip_between_the_sides_is_measured() {
    let mut state = balls();
    let check = Check::Measure {
        metric: Metric::Flip,
        is: Expect::parse("< 0.01").unwrap(),
        by: By::Work,
        values: vec![],
    };
    let mut b = state.a.clone();
    b.settings.accel = AccelKind::Grid;
    state.b = Some(b.clone());
    assert!(done(&check, &state), "the structure changes no pixel");
    b.settings.ambient = 0.6;
    state.b = Some(b);
    assert!(!done(&check, &state));
}

#[test]
fn a_grid_sweep_finds_the_cheapest_multiplier() {
    let mut state = balls();
    let values = vec![0.25, 1.0, 4.0];
    let check = Check::Measure {
        metric: Metric::GridSweep,
        is: Expect::parse("<= 0").unwrap(),
        by: By::Work,
        values: values.clone(),
    };
    let passing: Vec<f32> = values
        .iter()
        .copied()
        .filter(|&m| {
            state.a.settings.grid_multiplier = m;
            done(&check, &state)
        })
        .collect();
    assert_eq!(
        passing.len(),
        1,
        "exactly one of {values:?} is the cheapest"
    );
}

/// A check written as a lesson writes it, read: the check, or every
/// mistake with the column of its token (the check on line 1).
fn read(check: &str) -> Result<Check, Vec<(usize, String)>> {
    #[derive(serde::Deserialize)]
    struct Line {
        check: toml::Spanned<written::WrittenCheck>,
    }
    let text = format!("check = {check}");
    let line: Line = toml::from_str(&text).map_err(|e| vec![(0, e.to_string())])?;
    let mut reader = written::Reader::new(&text);
    let check = reader.check(line.check);
    match check {
        Some(check) if reader.mistakes.is_empty() => Ok(check),
        _ => Err(reader
            .mistakes
            .into_iter()
            .map(|(span, why)| (span.start + 1, why))
            .collect()),
    }
}

#[test]
fn malformed_checks_are_refused_at_their_token() {
    let sweep = read(r#"{ kind = "measure", metric = "grid-sweep", is = "<= 20" }"#);
    assert!(sweep.unwrap_err()[0].1.contains("needs `values`"));
    let twice = read(r#"{ kind = "answer", question = "?", of = "lights", choices = ["1", 1.0] }"#);
    assert_eq!(twice.unwrap_err()[0].0, 75);
    let typo = read(r#"{ kind = "value", of = "tree refracions", is = 2 }"#);
    let mistakes = typo.unwrap_err();
    assert_eq!(mistakes[0].0, 32, "{mistakes:?}");
    assert!(mistakes[0].1.contains("shadow-rays"), "{mistakes:?}");
    assert!(Quantity::parse("material 0 radius").is_err());
}

#[test]
fn an_expectation_must_be_able_to_match_what_is_read() {
    let words = read(r#"{ kind = "value", of = "tree depth", is = "at least 5" }"#);
    let mistakes = words.unwrap_err();
    assert_eq!(mistakes[0].0, 51, "{mistakes:?}");
    assert!(
        mistakes[0].1.contains("`tree depth` is a number") && mistakes[0].1.contains("`>= 5`"),
        "{mistakes:?}"
    );
    let yes_no = read(r#"{ kind = "value", of = "tree tir", is = "grid" }"#);
    assert!(yes_no.unwrap_err()[0].1.contains("is yes or no"));
    let word = read(r#"{ kind = "value", of = "accel", is = "octree" }"#);
    assert!(word.unwrap_err()[0].1.contains("one of none, grid, bvh"));
    assert!(read(r#"{ kind = "value", of = "tree tir", is = "yes" }"#).is_ok());
    assert!(read(r#"{ kind = "value", of = "tree depth", is = ">= 5" }"#).is_ok());
    assert!(read(r#"{ kind = "value", of = "noise-threshold", is = "off" }"#).is_ok());
}

#[test]
fn every_mistake_of_a_check_is_reported() {
    let check = r#"{ kind = "all", checks = [
        { kind = "value", of = "tree refracions", is = 1 },
        { kind = "value", of = "spp", is = "many", metric = "flip" },
        { kind = "measure", metric = "speed" },
    ] }"#;
    let mistakes = read(check).unwrap_err();
    let words: Vec<&str> = mistakes.iter().map(|(_, why)| why.as_str()).collect();
    assert_eq!(mistakes.len(), 5, "{words:#?}");
    assert!(
        words[0].contains("no tree figure `refracions`"),
        "{words:#?}"
    );
    assert!(words[1].contains("takes no `metric`"), "{words:#?}");
    assert!(words[2].contains("`spp` is a number"), "{words:#?}");
    assert!(words[3].contains("needs `is`"), "{words:#?}");
    assert!(words[4].contains("no metric `speed`"), "{words:#?}");
}

/// The parts of the scene a check line names, each with the text at its
/// place.
fn references_in(text: &str) -> Vec<(quantity::Part, &str)> {
    #[derive(serde::Deserialize)]
    struct Line {
        check: toml::Spanned<written::WrittenCheck>,
    }
    let line: Line = toml::from_str(text).unwrap();
    let mut reader = written::Reader::new(text);
    assert!(reader.check(line.check).is_some());
    (reader.references.iter())
        .map(|r| (r.part, &text[r.span.clone()]))
        .collect()
}

#[test]
fn numbers_naming_the_scene_are_kept_with_their_place() {
    let text = r#"check = { kind = "value", of = "tree blocker 12", is = 3 }"#;
    assert_eq!(
        references_in(text),
        [
            (quantity::Part::Light(12), "12"),
            (quantity::Part::Object(3), "3")
        ]
    );
    // In triple quotes the places start after the three quotes.
    let text = r#"check = { kind = "value", of = '''tree blocker 12''', is = "none" }"#;
    assert_eq!(references_in(text), [(quantity::Part::Light(12), "12")]);
}

/// Timed measurements read frame times (never compared with a bound here:
/// timings vary with the machine's load).
#[test]
fn a_timed_speedup_reads_frame_times() {
    let mut state = balls();
    state.b = Some(state.a.clone());
    let check = speedup("> 0", By::Time);
    let verdict = evaluate(&check, &state);
    assert!(verdict.is_done(), "{verdict:?}");
    assert!(
        verdict.reason().starts_with("A ") && verdict.reason().contains(" ms and B "),
        "{verdict:?}"
    );
}

#[test]
fn an_answer_check_names_its_question_and_quantity_even_inside_all() {
    let answer = Check::Answer {
        question: "Which object blocks the light?".into(),
        of: Quantity::parse("tree blocker 0").unwrap(),
        tolerance: None,
        choices: vec!["0".into(), "1".into()],
        side: Which::B,
    };
    let choices = ["0".to_string(), "1".to_string()];
    let asked = Some(("Which object blocks the light?", &choices[..]));
    let of = Quantity::parse("tree blocker 0").unwrap();
    assert_eq!(answer.question(), asked);
    assert_eq!(answer.answer_of(), Some((&of, Which::B)));
    let all = Check::All {
        checks: vec![value("spp", ">= 4"), answer],
    };
    assert_eq!(all.question(), asked);
    assert_eq!(all.answer_of(), Some((&of, Which::B)));
    let plain = value("spp", ">= 4");
    assert_eq!(plain.question(), None);
    assert_eq!(plain.answer_of(), None);
}

#[test]
fn a_check_of_side_b_says_so() {
    let mut state = state_of(SHADOWED);
    let check = Check::Value {
        of: Quantity::parse("spp").unwrap(),
        is: Expect::parse(">= 4").unwrap(),
        side: Which::B,
    };
    let missing = evaluate(&check, &state);
    assert_eq!(
        missing,
        Verdict::NotYet("compare mode is off: there is no side B".into())
    );
    let mut b = state.a.clone();
    b.settings.samples = 2;
    state.b = Some(b);
    assert_eq!(
        evaluate(&check, &state),
        Verdict::NotYet("B's spp is 2, expected >= 4".into())
    );
    state.a.settings.samples = 2;
    assert_eq!(
        evaluate(&value("spp", ">= 4"), &state),
        Verdict::NotYet("spp is 2, expected >= 4".into())
    );
}

/// A side that cannot render is said, never timed.
#[test]
fn a_timed_speedup_of_a_side_that_cannot_render_is_not_yet() {
    let mut state = balls();
    let mut b = state.a.clone();
    b.settings.width = 0;
    state.b = Some(b);
    let check = speedup("> 0", By::Time);
    let verdict = evaluate(&check, &state);
    assert!(
        matches!(&verdict, Verdict::NotYet(why) if why.contains("width")),
        "{verdict:?}"
    );
}

#[test]
fn each_quantity_reads_its_kind_of_value() {
    let reads = |of: &str| Quantity::parse(of).unwrap().reads();
    for switch in ["aa", "soft-shadows", "dof"] {
        assert_eq!(reads(switch), Reads::OnOff, "{switch}");
    }
    assert_eq!(reads("sampling"), Reads::Word(vec!["uniform", "adaptive"]));
    let kinds = [
        "sphere", "plane", "triangle", "polygon", "patch", "box", "cone", "mesh",
    ];
    assert_eq!(reads("object 2 kind"), Reads::Word(kinds.to_vec()));
    let eye_kinds = [&kinds[..], &["none"]].concat();
    assert_eq!(reads("tree eye-kind"), Reads::Word(eye_kinds));
    let views = tracer::render::View::ALL.iter().map(|v| v.name()).collect();
    assert_eq!(reads("view"), Reads::Word(views));
    assert_eq!(reads("spp"), Reads::Number);
}

#[test]
fn a_quantity_names_the_part_of_the_scene_it_reads() {
    let part = |of: &str| Quantity::parse(of).unwrap().part();
    assert_eq!(part("object 3 kd"), Some((Part::Object(3), 1)));
    assert_eq!(part("focus-error 2"), Some((Part::Object(2), 1)));
    assert_eq!(part("material 4 ior"), Some((Part::Material(4), 1)));
    assert_eq!(part("tree blocker 1"), Some((Part::Light(1), 2)));
    assert_eq!(part("spp"), None);
}

#[test]
fn the_camera_distance_is_from_the_eye_to_the_point_looked_at() {
    let state = state_of(INSIDE_GLASS);
    let read = Quantity::parse("camera distance")
        .unwrap()
        .read(&state, Which::A);
    assert_eq!(read, Ok(Value::Number(1.0)));
}

#[test]
fn the_grid_is_read_cell_by_axis_and_in_all() {
    let state = balls();
    let read = |of: &str| match Quantity::parse(of).unwrap().read(&state, Which::A) {
        Ok(Value::Number(n)) => n,
        other => panic!("{of}: {other:?}"),
    };
    let axes = [read("grid nx"), read("grid ny"), read("grid nz")];
    assert!(axes.iter().all(|&n| n >= 2.0), "{axes:?}");
    assert_eq!(read("grid cells"), axes.iter().product::<f64>());
}

/// With no structure the eye ray tests every shape and walks nothing.
#[test]
fn the_eye_rays_walk_is_read_at_the_pinned_pixel() {
    let mut state = state_of(SHADOWED);
    state.pixel = Some((16, 16));
    state.a.settings.accel = AccelKind::None;
    let read = |of: &str| Quantity::parse(of).unwrap().read(&state, Which::A);
    let shapes = read("brute-force tests").unwrap();
    assert_eq!(read("eye tests"), Ok(shapes));
    assert_eq!(read("eye steps"), Ok(Value::Number(0.0)));
}

#[test]
fn an_expectation_fits_the_kind_of_value_it_is_checked_against() {
    let accepts = |reads: Reads, is: &str| reads.accepts(&Expect::parse(is).unwrap()).is_ok();
    assert!(Reads::Number.is_numeric() && Reads::NumberOrOff.is_numeric());
    assert!(!Reads::OnOff.is_numeric() && !Reads::ObjectOrNone.is_numeric());
    let accel = Quantity::parse("accel").unwrap().reads();
    assert!(accepts(accel.clone(), "grid"));
    assert!(!accepts(accel, "kd-tree"));
    assert!(!accepts(Reads::Word(vec!["grid"]), "4"));
    assert!(accepts(Reads::ObjectOrNone, "1") && accepts(Reads::ObjectOrNone, "none"));
    for never in ["1.5", "-1", "sphere"] {
        assert!(!accepts(Reads::ObjectOrNone, never), "{never}");
    }
    assert_eq!(Reads::YesNo.show(&Value::Bool(true)), "yes");
    assert_eq!(Reads::YesNo.show(&Value::Bool(false)), "no");
    assert_eq!(Reads::OnOff.show(&Value::Bool(false)), "off");
}

/// SHADOWED looking at a point 5 from the eye, with a box 12 along the
/// view from the eye (its centre at z = -2) and a square behind it.
#[test]
fn a_box_is_focused_on_its_centre_and_a_square_is_a_polygon() {
    let view = SHADOWED.replace("at 0 0 0", "at 0 0 5");
    let scene = format!("{view}box -1 -1 -3 1 1 -1\np 4\n-1 -1 -5\n1 -1 -5\n1 1 -5\n-1 1 -5\n");
    let mut state = state_of(&scene);
    state.a.settings.lens_override.focal = Some(1.0);
    let read = |of: &str| Quantity::parse(of).unwrap().read(&state, Which::A);
    let Ok(Value::Number(error)) = read("focus-error 2") else {
        panic!("{:?}", read("focus-error 2"));
    };
    // The plane in focus at 5, the box's centre at 12.
    assert!((error - 7.0 / 12.0).abs() < 1e-6, "{error}");
    assert_eq!(read("object 3 kind"), Ok(Value::Word("polygon".into())));
    assert_eq!(read("object 0 kind"), Ok(Value::Word("triangle".into())));
}

/// The centre pixel's rays all hit (the triangle, the light); a corner
/// pixel's eye ray meets nothing.
#[test]
fn the_misses_are_the_rays_that_met_nothing() {
    let mut state = state_of(SHADOWED);
    let misses = Quantity::parse("tree misses").unwrap();
    state.pixel = Some((16, 16));
    assert_eq!(misses.read(&state, Which::A), Ok(Value::Number(0.0)));
    state.pixel = Some((0, 0));
    assert_eq!(misses.read(&state, Which::A), Ok(Value::Number(1.0)));
}

#[test]
fn measure_and_answer_checks_read_as_written() {
    let sweep =
        read(r#"{ kind = "measure", metric = "grid-sweep", is = "<= 20", values = [1, 2.5] }"#);
    assert_eq!(
        sweep,
        Ok(Check::Measure {
            metric: Metric::GridSweep,
            is: Expect::AtMost(20.0),
            by: By::Work,
            values: vec![1.0, 2.5],
        })
    );
    let answer = read(
        r#"{ kind = "answer", question = "How many?", of = "lights", tolerance = "1", side = "b" }"#,
    );
    assert_eq!(
        answer,
        Ok(Check::Answer {
            question: "How many?".into(),
            of: Quantity::Lights,
            tolerance: Some("1".into()),
            choices: vec![],
            side: Which::B,
        })
    );
    // A tolerance on a value that is not a number can never apply.
    let word = read(r#"{ kind = "answer", question = "Which?", of = "accel", tolerance = "1" }"#);
    let mistakes = word.unwrap_err();
    assert!(
        mistakes[0].1.contains("a tolerance needs a number to read"),
        "{mistakes:?}"
    );
}

#[test]
fn only_a_grid_sweep_takes_values_and_each_above_0() {
    let sweep = |values: &str| {
        read(&format!(
            r#"{{ kind = "measure", metric = "grid-sweep", is = "<= 20", values = {values} }}"#
        ))
    };
    for bad in ["[0]", "[1, -1]", "[inf]", "[nan]"] {
        let mistakes = sweep(bad).unwrap_err();
        assert!(
            mistakes[0].1.contains("must be above 0"),
            "{bad}: {mistakes:?}"
        );
    }
    let flip = read(r#"{ kind = "measure", metric = "flip", is = "< 0.1", values = [1] }"#);
    assert!(
        flip.unwrap_err()[0]
            .1
            .contains("only a `grid-sweep` takes `values`")
    );
    assert!(read(r#"{ kind = "measure", metric = "flip", is = "< 0.1" }"#).is_ok());
}
