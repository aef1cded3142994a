//! Checks: what a step asks the student to achieve, tested on the outcome
//! (the settings and scene as they are, the pinned pixel's recorded ray
//! tree, an answer against a value computed now, a measurement), never on
//! which control was touched. [`evaluate`] is a pure function of a
//! [`LessonState`], so the window and `lesson check` agree.

mod expect;
mod measurement;
mod quantity;

#[cfg(test)]
mod tests;

use anyhow::Result;
use serde::Deserialize;

pub use expect::{Expect, Tolerance, Value};
pub use measurement::{By, Metric};
pub use quantity::Quantity;

use super::state::{LessonState, Which};

/// One check, as a lesson file writes it (`kind = "value"`, ...).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Check {
    /// A value of the state (a setting, the scene, the pinned pixel's ray
    /// tree, the structure) meets an expectation.
    Value {
        of: Quantity,
        is: Expect,
        #[serde(default)]
        side: Which,
    },
    /// The student's answer equals a value the workbench computes when it
    /// checks.
    Answer {
        /// What the window asks.
        question: String,
        of: Quantity,
        /// How close a number must be (`"2%"`, `"0.01"`; default exact).
        tolerance: Option<String>,
        /// The answers to pick from; none for a typed answer.
        #[serde(default)]
        choices: Vec<String>,
        #[serde(default)]
        side: Which,
    },
    /// A rendered measurement meets an expectation.
    Measure {
        metric: Metric,
        is: Expect,
        #[serde(default)]
        by: By,
        /// The grid multipliers a `grid-sweep` tries.
        #[serde(default)]
        values: Vec<f32>,
    },
    /// Every one of these.
    All { checks: Vec<Check> },
}

/// What a check found.
#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    /// It holds; the words say what was seen.
    Done(String),
    /// Not yet, and what is missing.
    NotYet(String),
    /// An answer was given and it is not the right one.
    Wrong(String),
}

impl Verdict {
    pub fn is_done(&self) -> bool {
        matches!(self, Verdict::Done(_))
    }

    /// The words, whatever the verdict.
    pub fn reason(&self) -> &str {
        match self {
            Verdict::Done(r) | Verdict::NotYet(r) | Verdict::Wrong(r) => r,
        }
    }
}

impl Check {
    /// What makes a check well-formed beyond its fields' types: a sweep
    /// has values, a tolerance reads, choices are distinct.
    pub fn validate(&self) -> Result<(), String> {
        match self {
            Check::Value { .. } => Ok(()),
            Check::Answer {
                question,
                tolerance,
                choices,
                ..
            } => {
                if question.trim().is_empty() {
                    return Err("the answer check's `question` is empty".into());
                }
                if let Some(t) = tolerance {
                    Tolerance::parse(t)?;
                }
                let mut seen = Vec::new();
                for choice in choices {
                    let value = Value::parse(choice)
                        .ok_or("a choice is empty: expected the text of each answer")?;
                    if seen.contains(&value) {
                        return Err(format!("the choice `{choice}` is given twice"));
                    }
                    seen.push(value);
                }
                Ok(())
            }
            Check::Measure { metric, values, .. } => match metric {
                Metric::GridSweep if values.is_empty() => Err(
                    "a `grid-sweep` needs `values`: the grid multipliers to try, e.g. [0.5, 1, 2, 4]"
                        .into(),
                ),
                Metric::GridSweep => match values.iter().find(|m| !(**m > 0.0 && m.is_finite())) {
                    Some(m) => Err(format!("a grid multiplier must be above 0, found {m}")),
                    None => Ok(()),
                },
                _ if !values.is_empty() => {
                    Err("only a `grid-sweep` takes `values`".into())
                }
                _ => Ok(()),
            },
            Check::All { checks } if checks.is_empty() => {
                Err("`all` needs at least one check in `checks`".into())
            }
            Check::All { checks } => checks.iter().try_for_each(Check::validate),
        }
    }

    /// The question a step asks, when its check is an answer (or holds one).
    pub fn question(&self) -> Option<(&str, &[String])> {
        match self {
            Check::Answer {
                question, choices, ..
            } => Some((question, choices)),
            Check::All { checks } => checks.iter().find_map(Check::question),
            _ => None,
        }
    }
}

/// Evaluates `check` on `state`. What cannot be read yet (no pixel pinned,
/// no side B) is a [`Verdict::NotYet`] saying so, not an error.
pub fn evaluate(check: &Check, state: &LessonState) -> Verdict {
    match check {
        Check::Value { of, is, side } => {
            let value = match of.read(state, *side) {
                Ok(value) => value,
                Err(why) => return Verdict::NotYet(why),
            };
            let seen = format!("{}{of} is {value}", side_prefix(*side));
            if is.holds(&value) {
                Verdict::Done(seen)
            } else {
                Verdict::NotYet(format!("{seen}, expected {is}"))
            }
        }
        Check::Answer {
            of,
            tolerance,
            choices,
            side,
            ..
        } => evaluate_answer(state, of, tolerance.as_deref(), choices, *side),
        Check::Measure {
            metric,
            is,
            by,
            values,
        } => match measurement::measure(*metric, *by, values, state) {
            Ok(measured) if is.holds(&Value::Number(measured.value)) => {
                Verdict::Done(measured.detail)
            }
            Ok(measured) => Verdict::NotYet(format!("{}, expected {is}", measured.detail)),
            Err(why) => Verdict::NotYet(why),
        },
        Check::All { checks } => {
            let mut seen = Vec::new();
            for check in checks {
                match evaluate(check, state) {
                    Verdict::Done(words) => seen.push(words),
                    not_yet => return not_yet,
                }
            }
            Verdict::Done(seen.join("; "))
        }
    }
}

fn side_prefix(side: Which) -> &'static str {
    match side {
        Which::A => "",
        Which::B => "B's ",
    }
}

/// The answer given against the value computed now. The verdict never
/// says the right value: only whether the answer is it.
fn evaluate_answer(
    state: &LessonState,
    of: &Quantity,
    tolerance: Option<&str>,
    choices: &[String],
    side: Which,
) -> Verdict {
    let Some(given) = state.answer.as_deref().and_then(Value::parse) else {
        return Verdict::NotYet("no answer yet".into());
    };
    if !choices.is_empty()
        && !choices
            .iter()
            .any(|c| Value::parse(c).as_ref() == Some(&given))
    {
        return Verdict::NotYet(format!("pick one of {}", choices.join(", ")));
    }
    let correct = match of.read(state, side) {
        Ok(value) => value,
        Err(why) => return Verdict::NotYet(why),
    };
    let tolerance = tolerance
        .and_then(|t| Tolerance::parse(t).ok())
        .unwrap_or(Tolerance::Absolute(0.0));
    let right = match (&given, &correct) {
        (Value::Number(g), Value::Number(c)) => tolerance.holds(*g, *c),
        (g, c) => g == c,
    };
    if right {
        Verdict::Done(format!("{given} is right"))
    } else {
        Verdict::Wrong(format!("{given} is not right"))
    }
}
