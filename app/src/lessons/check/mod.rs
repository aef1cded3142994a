//! Checks: what a step asks the student to achieve, tested on the outcome
//! (the settings and scene as they are, the pinned pixel's recorded ray
//! tree, an answer against a value computed now, a measurement), never on
//! which control was touched. [`evaluate`] is a pure function of a
//! [`LessonState`], so the window and `lesson check` agree.

pub(crate) mod catalogue;
mod expect;
mod measurement;
mod quantity;
pub(crate) mod written;

#[cfg(test)]
mod tests;

pub(crate) use expect::{Expect, Tolerance, Value};
pub(crate) use measurement::{By, Metric, measure};
pub(crate) use quantity::{Part, Quantity};

use super::state::{LessonState, Which};

/// One check, as a lesson file describes it (`kind = "value"`, ...), read
/// by [`written::Reader`].
#[derive(Debug, Clone, PartialEq)]
pub enum Check {
    /// A value of the state (a setting, the scene, the pinned pixel's ray
    /// tree, the structure) meets an expectation.
    Value {
        of: Quantity,
        is: Expect,
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
        choices: Vec<String>,
        side: Which,
    },
    /// A rendered measurement meets an expectation.
    Measure {
        metric: Metric,
        is: Expect,
        by: By,
        /// The grid multipliers a `grid-sweep` tries.
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
    pub(crate) fn reason(&self) -> &str {
        match self {
            Verdict::Done(r) | Verdict::NotYet(r) | Verdict::Wrong(r) => r,
        }
    }
}

impl Check {
    /// What an answer check (or one inside an `all`) grades against, and
    /// on which side: what `lesson check` shows a teacher when a recorded
    /// answer is wrong.
    pub(crate) fn answer_of(&self) -> Option<(&Quantity, Which)> {
        match self {
            Check::Answer { of, side, .. } => Some((of, *side)),
            Check::All { checks } => checks.iter().find_map(Check::answer_of),
            _ => None,
        }
    }

    /// The question a step asks, when its check is an answer (or holds one).
    pub(crate) fn question(&self) -> Option<(&str, &[String])> {
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
            let reads = of.reads();
            let seen = format!("{}{of} is {}", side_prefix(*side), reads.show(&value));
            if is.holds(&value) {
                Verdict::Done(seen)
            } else {
                Verdict::NotYet(format!("{seen}, expected {}", reads.show_expect(is)))
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
            // Every part is said, once: the ones not done, or all of them
            // done ("no pixel is pinned" is said once for all the parts
            // that need one).
            let verdicts: Vec<Verdict> = checks.iter().map(|c| evaluate(c, state)).collect();
            let mut failing: Vec<&str> = Vec::new();
            for verdict in verdicts.iter().filter(|v| !v.is_done()) {
                if !failing.contains(&verdict.reason()) {
                    failing.push(verdict.reason());
                }
            }
            if failing.is_empty() {
                let seen: Vec<&str> = verdicts.iter().map(Verdict::reason).collect();
                Verdict::Done(seen.join("; "))
            } else if verdicts.iter().any(|v| matches!(v, Verdict::Wrong(_))) {
                Verdict::Wrong(failing.join("; "))
            } else {
                Verdict::NotYet(failing.join("; "))
            }
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
    let given = of.reads().show(&given);
    if right {
        Verdict::Done(format!("{given} is right"))
    } else {
        Verdict::Wrong(format!("{given} is not right"))
    }
}
