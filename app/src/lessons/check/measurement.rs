//! Checks that render: how much faster B is than A, how far apart their
//! images are (FLIP), and whether side A's grid multiplier is near the best
//! of a sweep. They use the measuring code the `compare`, `bench` and
//! `sweep` commands use.

use std::sync::atomic::AtomicBool;

use serde::Deserialize;
use tracer::accel::AccelKind;
use tracer::render::{Encoding, RenderSettings};

use crate::measure::ab::{self, Heatmap, SideOptions};
use crate::measure::benchmark::{self, Case, Measurement, RunOptions};

use super::super::state::{LessonState, SideState};
use super::expect::number;

/// What a measurement compares by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum By {
    /// Ray-primitive tests plus cells or nodes visited in one frame:
    /// exact, the same on every machine and every run.
    #[default]
    Work,
    /// The median frame time of three frames each, the sides
    /// alternated: what the course's timing table measures, noisy on a
    /// shared machine.
    Time,
}

/// Frames per side for a timed measurement.
const TIMED_ROUNDS: usize = 3;

/// What a measurement reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Metric {
    /// A's cost over B's: above 1 when B is faster.
    Speedup,
    /// Mean FLIP error between A's and B's images, 0 to 1.
    Flip,
    /// How many percent side A's grid multiplier costs above the cheapest
    /// of a sweep (10: 10% slower than the best).
    GridSweep,
}

impl By {
    /// The word a lesson writes after `by =`.
    pub(crate) fn name(self) -> &'static str {
        match self {
            By::Work => "work",
            By::Time => "time",
        }
    }
}

impl Metric {
    /// The word a lesson writes after `metric =`.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Metric::Speedup => "speedup",
            Metric::Flip => "flip",
            Metric::GridSweep => "grid-sweep",
        }
    }
}

/// A figure measured, with words saying what it came from.
pub(crate) struct Measured {
    pub(crate) value: f64,
    pub(crate) detail: String,
}

/// Measures `metric` on `state`; `values` are the sweep's multipliers.
pub(crate) fn measure(
    metric: Metric,
    by: By,
    values: &[f32],
    state: &LessonState,
) -> Result<Measured, String> {
    match metric {
        Metric::Speedup => {
            let b = state.side(super::super::state::Which::B)?;
            let (a_cost, b_cost) = match by {
                By::Work => (work(&frame(&state.a)?), work(&frame(b)?)),
                By::Time => timed_pair(&state.a, b)?,
            };
            let value = a_cost / b_cost.max(f64::MIN_POSITIVE);
            Ok(Measured {
                value,
                detail: format!(
                    "A {} and B {}: {}",
                    cost_words(a_cost, by),
                    cost_words(b_cost, by),
                    faster_side(value)
                ),
            })
        }
        Metric::Flip => {
            let b = state.side(super::super::state::Which::B)?;
            let cancel = AtomicBool::new(false);
            let comparison = ab::run(
                [&state.a.world, &b.world],
                case(&state.a, state.a.settings.clone()),
                case(b, b.settings.clone()),
                SideOptions::default(),
                Heatmap::Flip,
                &cancel,
                &mut |_| {},
            )
            .map_err(|e| format!("{e:#}"))?
            .ok_or("the comparison was cancelled")?;
            let value = f64::from(comparison.metrics.flip);
            Ok(Measured {
                value,
                detail: format!("FLIP between A and B is {}", number(value)),
            })
        }
        Metric::GridSweep => grid_sweep(&state.a, by, values),
    }
}

/// A case of `side`'s scene measured once, labelled as the reports label
/// it.
fn case(side: &SideState, settings: RenderSettings) -> Case {
    Case::new(settings, &side.scene.view, Encoding::Linear)
}

/// One frame of `side`.
fn frame(side: &SideState) -> Result<Measurement, String> {
    frames(side, &side.settings, 1)
}

/// `runs` frames of `side` under `settings`.
fn frames(side: &SideState, settings: &RenderSettings, runs: usize) -> Result<Measurement, String> {
    let cancel = AtomicBool::new(false);
    let outcome = benchmark::run(
        &side.world,
        &[case(side, settings.clone())],
        RunOptions {
            runs,
            threads: None,
        },
        &cancel,
        &mut |_| {},
    )
    .map_err(|e| format!("{e:#}"))?;
    outcome
        .measurements
        .into_iter()
        .next()
        .ok_or_else(|| "the render was cancelled".to_string())
}

/// Tests and steps of one frame: the work a structure did.
fn work(m: &Measurement) -> f64 {
    let c = &m.stats.counters;
    (c.intersection_tests + c.nodes_visited) as f64
}

/// Which side is faster, A's cost over B's being `ratio`: a student
/// reads "A is 2.7x faster", not "B is 0.37x faster".
fn faster_side(ratio: f64) -> String {
    if ratio >= 1.0 {
        format!("B is {}x faster", number(ratio))
    } else {
        format!(
            "A is {}x faster (A costs {} of B)",
            number(1.0 / ratio.max(f64::MIN_POSITIVE)),
            number(ratio)
        )
    }
}

fn cost_words(cost: f64, by: By) -> String {
    match by {
        By::Work => format!("{} tests and steps", number(cost)),
        By::Time => format!("{} ms", number((cost * 1e3).round())),
    }
}

/// Median frame times of A and B, their frames alternated so a change of
/// load on the machine falls on both.
fn timed_pair(a: &SideState, b: &SideState) -> Result<(f64, f64), String> {
    let mut times = [Vec::new(), Vec::new()];
    for _ in 0..TIMED_ROUNDS {
        for (i, side) in [a, b].into_iter().enumerate() {
            times[i].push(frame(side)?.median().as_secs_f64());
        }
    }
    Ok((median(&mut times[0]), median(&mut times[1])))
}

fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(0.0)
}

/// Side A's multiplier against each of `values`, with a grid: the cost of
/// A's over the cheapest, minus one.
fn grid_sweep(side: &SideState, by: By, values: &[f32]) -> Result<Measured, String> {
    let cost_at = |m: f32| -> Result<f64, String> {
        let mut settings = side.settings.clone();
        settings.accel = AccelKind::Grid;
        settings.grid_multiplier = m;
        let measured = frames(
            side,
            &settings,
            if by == By::Time { TIMED_ROUNDS } else { 1 },
        )?;
        Ok(match by {
            By::Work => work(&measured),
            By::Time => measured.median().as_secs_f64(),
        })
    };
    let chosen_m = side.settings.grid_multiplier;
    let chosen = cost_at(chosen_m)?;
    let mut best = (chosen_m, chosen);
    for &m in values {
        let cost = cost_at(m)?;
        if cost < best.1 {
            best = (m, cost);
        }
    }
    let value = (chosen / best.1.max(f64::MIN_POSITIVE) - 1.0) * 100.0;
    Ok(Measured {
        value,
        detail: format!(
            "m = {} costs {}; the sweep's best, m = {}, costs {} ({}% more)",
            number(f64::from(chosen_m)),
            cost_words(chosen, by),
            number(f64::from(best.0)),
            cost_words(best.1, by),
            number(value.round())
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::super::tests::balls;
    use super::*;

    #[test]
    fn each_metric_and_comparison_is_named_by_the_word_a_lesson_writes() {
        for by in [By::Work, By::Time] {
            let read: By = serde_json::from_str(&format!("\"{}\"", by.name())).unwrap();
            assert_eq!(read, by);
        }
        for metric in [Metric::Speedup, Metric::Flip, Metric::GridSweep] {
            let read: Metric = serde_json::from_str(&format!("\"{}\"", metric.name())).unwrap();
            assert_eq!(read, metric);
        }
    }

    #[test]
    fn the_median_is_the_middle_value_or_the_upper_of_two() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), 3.0);
        assert_eq!(median(&mut []), 0.0);
    }

    /// A's multiplier's cost in tests and steps.
    fn cost_at(side: &SideState, m: f32) -> f64 {
        let mut settings = side.settings.clone();
        settings.accel = AccelKind::Grid;
        settings.grid_multiplier = m;
        work(&frames(side, &settings, 1).unwrap())
    }

    #[test]
    fn a_grid_sweep_gives_how_many_percent_the_chosen_costs_above_the_best() {
        let mut state = balls();
        state.a.settings.grid_multiplier = 0.25;
        let (chosen, best) = (cost_at(&state.a, 0.25), cost_at(&state.a, 4.0));
        assert!(best < chosen, "{best} {chosen}");
        let swept = grid_sweep(&state.a, By::Work, &[4.0]).unwrap();
        assert_eq!(swept.value, (chosen / best - 1.0) * 100.0);
        assert!(
            swept.detail.starts_with(&format!(
                "m = 0.25 costs {} tests and steps; the sweep's best, m = 4, costs {} ",
                number(chosen),
                number(best)
            )),
            "{}",
            swept.detail
        );
        // Nothing cheaper: the chosen is the best, 0% more.
        assert_eq!(grid_sweep(&state.a, By::Work, &[]).unwrap().value, 0.0);
        // A multiplier that costs the same keeps the one chosen as best.
        let same = 0.2501;
        assert_eq!(cost_at(&state.a, same), chosen);
        let tie = grid_sweep(&state.a, By::Work, &[same]).unwrap();
        assert!(tie.detail.contains("best, m = 0.25,"), "{}", tie.detail);
    }
}
