//! `workbench lesson explain`: the state a step starts from, said for the
//! teacher writing it: the settings, compare mode, the pinned pixel and its
//! ray tree, the step's check as it stands, and every quantity a check can
//! read there with its current value. [`find`] lists the pixels where tree
//! figures hold, to choose one to pin without the window.

mod find;

#[cfg(not(target_family = "wasm"))]
pub(crate) use find::{Condition, find};

use std::fmt::Write;

use anyhow::{Result, bail};

use crate::describe::describe;
use crate::reports::ray_tree;

use super::check::catalogue::{self, LISTED_PARTS};
use super::check::{By, Check, Metric, Verdict, evaluate, measure};
use super::format::{Lesson, LessonStep};
use super::replay::{open_scene, state_at_step};
use super::state::{LessonState, SideState, Which};

/// Step `number` (counted from 1, as `lesson check` prints it) of
/// `lesson`, and the state it starts from: the start, every earlier step
/// set up and solved, its own setup.
pub(crate) fn step_state(lesson: &Lesson, number: usize) -> Result<(&LessonStep, LessonState)> {
    let count = lesson.steps.len();
    let Some(step) = number.checked_sub(1).and_then(|i| lesson.steps.get(i)) else {
        bail!("{} has steps 1 to {count}, no step {number}", lesson.name);
    };
    let (scene, world) = open_scene(lesson)?;
    let state = state_at_step(lesson, &scene, &world, number - 1)?;
    Ok((step, state))
}

/// The lesson and step as `lesson check` names them: `refraction
/// (chapter 6): Refraction` then `step 3/6 The cube traps light`.
fn heading(lesson: &Lesson, number: usize, step: &LessonStep) -> String {
    format!(
        "{} (chapter {}): {}\nstep {number}/{} {}",
        lesson.name,
        lesson.chapter,
        lesson.title,
        lesson.steps.len(),
        step.title
    )
}

/// The explanation of step `number`; `pixel` pins another pixel than the
/// one the step starts with, to see what the check would read there.
pub(crate) fn explain(lesson: &Lesson, number: usize, pixel: Option<(u32, u32)>) -> Result<String> {
    let (step, mut state) = step_state(lesson, number)?;
    let mut out = heading(lesson, number, step);
    let earlier = match number {
        1 => "the lesson's [start]".to_string(),
        2 => "the lesson's [start], step 1 set up and solved".to_string(),
        n => format!(
            "the lesson's [start], steps 1 to {} set up and solved",
            n - 1
        ),
    };
    let _ = writeln!(out, ", as it starts: {earlier}, then its own setup");
    if let Some((x, y)) = pixel {
        let settings = &state.a.settings;
        if x >= settings.width || y >= settings.height {
            bail!(
                "pixel ({x}, {y}) is outside the {}x{} image",
                settings.width,
                settings.height
            );
        }
        state.pixel = Some((x, y));
        let _ = writeln!(out, "(pixel ({x}, {y}) pinned by --pixel)");
    }
    out.push_str(&settings_text(&state));
    let verdict = evaluate(&step.check.value, &state);
    let word = match verdict {
        Verdict::Done(_) => "holds",
        Verdict::NotYet(_) => "not yet",
        Verdict::Wrong(_) => "wrong",
    };
    let _ = writeln!(out, "check: {word}: {}", verdict.reason());
    out.push_str(&tree_text(&state)?);
    out.push_str(&quantities_text(&state, Which::A));
    if state.b.is_some() {
        out.push_str(&quantities_text(&state, Which::B));
    }
    out.push_str(&measures_text(&step.check.value, &state));
    Ok(out)
}

/// The sides' settings, the pinned pixel, the layout.
fn settings_text(state: &LessonState) -> String {
    let side = |s: &SideState| {
        let r = &s.settings;
        format!(
            "{}; {} x {}, depth {}",
            describe(r, &s.scene.view),
            r.width,
            r.height,
            r.max_depth
        )
    };
    let mut out = format!("side A: {}\n", side(&state.a));
    match &state.b {
        Some(b) => {
            let _ = writeln!(out, "side B (compare mode): {}", side(b));
        }
        None => out.push_str("compare mode: off\n"),
    }
    match state.pixel {
        Some((x, y)) => {
            let _ = writeln!(out, "pinned pixel: ({x}, {y})");
        }
        None => out.push_str("pinned pixel: none (--find lists pixels to pin)\n"),
    }
    let view = state.layout.view.map_or("shaded", |v| v.name());
    let observer = if state.layout.observer {
        "open"
    } else {
        "closed"
    };
    let _ = writeln!(out, "view: {view}; observer: {observer}");
    out
}

/// The pinned pixel's ray tree on side A, sample 0, as `inspect --pixel`
/// prints it without the structure's visits.
fn tree_text(state: &LessonState) -> Result<String> {
    let Some(pixel) = state.pixel else {
        return Ok(String::new());
    };
    let tree = ray_tree::inspect(&state.a.world, None, &state.a.settings, pixel, 0)?;
    let mut out = String::from("ray tree of the pinned pixel (side A, sample 0):\n");
    for line in ray_tree::nodes_text(&tree).lines() {
        let _ = writeln!(out, "  {line}");
    }
    Ok(out)
}

/// Every quantity a check can read on side `which`, one per line with its
/// value in the format's words, or why it cannot be read.
fn quantities_text(state: &LessonState, which: Which) -> String {
    let Ok(side) = state.side(which) else {
        return String::new();
    };
    let scene = &side.scene;
    let mut out = match which {
        Which::A => String::from("what a check can read here (side A):\n"),
        Which::B => String::from("what a check can read on side B (with side = \"b\"):\n"),
    };
    let mut list = catalogue::without_pixel(scene);
    if state.pixel.is_some() {
        list.extend(catalogue::at_pixel(scene));
    }
    for quantity in list {
        let value = match quantity.read(state, which) {
            Ok(value) => quantity.reads().show(&value),
            Err(why) => format!("({why})"),
        };
        let _ = writeln!(out, "  {:<26} {value}", quantity.to_string());
    }
    let parts = scene.objects.len().max(scene.materials.len());
    if parts > LISTED_PARTS {
        let _ = writeln!(
            out,
            "  (objects and materials from {LISTED_PARTS} on read the same way; \
             the scene has {} objects, {} materials)",
            scene.objects.len(),
            scene.materials.len()
        );
    }
    if state.pixel.is_none() {
        out.push_str("  (tree ..., eye ... and pixel samples read a pinned pixel)\n");
    }
    out
}

/// The measurements a `measure` check would take here: the step's own,
/// and in compare mode the speedup and FLIP by work.
fn measures_text(check: &Check, state: &LessonState) -> String {
    let mut wanted: Vec<(Metric, By, Vec<f32>)> = Vec::new();
    collect_measures(check, &mut wanted);
    if state.b.is_some() {
        for metric in [Metric::Speedup, Metric::Flip] {
            if !wanted.iter().any(|(m, _, _)| *m == metric) {
                wanted.push((metric, By::Work, Vec::new()));
            }
        }
    }
    if wanted.is_empty() {
        return String::new();
    }
    let mut out = String::from("what a measure check would take here:\n");
    for (metric, by, values) in wanted {
        let measured =
            measure(metric, by, &values, state).map_or_else(|why| format!("({why})"), |m| m.detail);
        let _ = writeln!(
            out,
            "  {:<26} {measured}",
            format!("{} by {}", metric.name(), by.name())
        );
    }
    out
}

/// The measurements `check` takes, with how and over which values.
fn collect_measures(check: &Check, into: &mut Vec<(Metric, By, Vec<f32>)>) {
    match check {
        Check::Measure {
            metric, by, values, ..
        } => into.push((*metric, *by, values.clone())),
        Check::All { checks } => checks.iter().for_each(|c| collect_measures(c, into)),
        Check::Value { .. } | Check::Answer { .. } => {}
    }
}
