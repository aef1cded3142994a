//! `lesson explain --find`: the pixels of a step's image where tree figures
//! hold (`tir=yes`, `eye-object=2`), each pixel's tree recorded once on
//! side A, as the window's ray tree and a `tree` check record it.

use std::fmt::Write;
use std::sync::Arc;

use anyhow::{Result, bail};
use tracer::accel::SceneIndex;

use crate::reports::ray_tree;

use super::super::check::{Expect, Quantity};
use super::super::format::Lesson;
use super::{heading, step_state};

/// One condition of `--find`: a tree figure and what it must be.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Condition {
    pub(crate) of: Quantity,
    pub(crate) is: Expect,
}

impl Condition {
    /// `tir=yes`, `tree eye-object=2`, `rays>=6`, `blocker 0=1`: a tree
    /// figure (the `tree ` in front may be left out) and an expectation as
    /// a check's `is` writes it.
    pub(crate) fn parse(text: &str) -> Result<Condition, String> {
        let Some(at) = text.find(['=', '<', '>']) else {
            return Err(format!(
                "`{text}`: expected QUANTITY=VALUE, such as `tir=yes` or `eye-object=2`"
            ));
        };
        let (name, rest) = text.split_at(at);
        let name = name.trim();
        let name = if name.starts_with("tree ") {
            name.to_string()
        } else {
            format!("tree {name}")
        };
        // With `tree ` in front, what parses is a tree figure.
        let of = Quantity::parse(&name).map_err(|e| format!("`{text}`: {e}"))?;
        let rest = rest.strip_prefix('=').unwrap_or(rest);
        let is = Expect::parse(rest).map_err(|e| format!("`{text}`: {e}"))?;
        let reads = of.reads();
        reads
            .accepts(&is)
            .map_err(|e| format!("`{text}`: {of} {e}"))?;
        Ok(Condition { of, is })
    }
}

/// The pixels of step `number`'s image where every condition holds on
/// side A, row by row, and the one nearest their middle to pin. None found
/// is an error, so a script can tell.
pub(crate) fn find(lesson: &Lesson, number: usize, conditions: &[Condition]) -> Result<String> {
    let (step, state) = step_state(lesson, number)?;
    let side = &state.a;
    let settings = &side.settings;
    let index = Arc::new(SceneIndex::build(
        &side.world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    let mut found = Vec::new();
    for y in 0..settings.height {
        for x in 0..settings.width {
            let tree = ray_tree::inspect(&side.world, Some(index.clone()), settings, (x, y), 0)?;
            let holds = conditions.iter().all(|c| {
                (c.of.read_tree(&side.scene, &tree)).is_some_and(|value| c.is.holds(&value))
            });
            if holds {
                found.push((x, y));
            }
        }
    }
    let wanted: Vec<String> = (conditions.iter())
        .map(|c| format!("{} is {}", c.of, c.of.reads().show_expect(&c.is)))
        .collect();
    let wanted = wanted.join(" and ");
    let Some(middle) = nearest_middle(&found) else {
        bail!(
            "step {number}: no pixel of the {}x{} image where {wanted}",
            settings.width,
            settings.height
        );
    };
    let mut out = heading(lesson, number, step);
    let _ = writeln!(
        out,
        ": {} of {} pixels where {wanted} (side A, sample 0, as the step starts):",
        found.len(),
        settings.width * settings.height
    );
    out.push_str(&rows_text(&found));
    let _ = writeln!(
        out,
        "nearest their middle: pixel = [{}, {}]",
        middle.0, middle.1
    );
    Ok(out)
}

/// The pixels one row a line, runs of neighbours as ranges:
/// `row 27: 40-44, 47`.
fn rows_text(pixels: &[(u32, u32)]) -> String {
    let mut out = String::new();
    for row in pixels.chunk_by(|a, b| a.1 == b.1) {
        let runs: Vec<String> = row
            .chunk_by(|a, b| b.0 == a.0 + 1)
            .map(|run| match (run.first(), run.last()) {
                (Some(first), Some(last)) if first != last => format!("{}-{}", first.0, last.0),
                (Some(first), _) => first.0.to_string(),
                _ => String::new(),
            })
            .collect();
        let _ = writeln!(out, "  row {}: {}", row[0].1, runs.join(", "));
    }
    out
}

/// The pixel found nearest the mean of those found: one well inside the
/// region, away from its edges, where a small change of settings keeps it.
fn nearest_middle(pixels: &[(u32, u32)]) -> Option<(u32, u32)> {
    let n = pixels.len() as f64;
    let (sx, sy) = pixels.iter().fold((0.0, 0.0), |(sx, sy), &(x, y)| {
        (sx + f64::from(x), sy + f64::from(y))
    });
    let (mx, my) = (sx / n, sy / n);
    pixels.iter().copied().min_by(|a, b| {
        let d = |&(x, y): &(u32, u32)| (f64::from(x) - mx).powi(2) + (f64::from(y) - my).powi(2);
        d(a).total_cmp(&d(b))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_condition_reads_like_a_check() {
        let c = Condition::parse("tir=yes").unwrap();
        assert_eq!(c.of.to_string(), "tree tir");
        assert_eq!(c.is, Expect::parse("yes").unwrap());
        let c = Condition::parse("tree rays>=6").unwrap();
        assert_eq!(
            (c.of.to_string(), c.is),
            ("tree rays".into(), Expect::AtLeast(6.0))
        );
        let c = Condition::parse("blocker 1=none").unwrap();
        assert_eq!(c.of.to_string(), "tree blocker 1");
    }

    #[test]
    fn a_condition_that_cannot_be_found_is_refused() {
        for (text, says) in [
            ("tir", "expected QUANTITY=VALUE"),
            ("spp=4", "no tree figure `spp`"),
            ("tir=5", "is yes or no"),
            ("refracions=1", "no tree figure `refracions`"),
        ] {
            let e = Condition::parse(text).unwrap_err();
            assert!(e.contains(says), "{text}: {e}");
        }
    }

    #[test]
    fn rows_are_said_as_runs() {
        let pixels = [(40, 27), (41, 27), (42, 27), (47, 27), (3, 28)];
        assert_eq!(rows_text(&pixels), "  row 27: 40-42, 47\n  row 28: 3\n");
        assert_eq!(nearest_middle(&pixels), Some((40, 27)));
        assert_eq!(nearest_middle(&[]), None);
    }
}
