//! A check as a lesson file writes it: every key's value kept with its
//! place in the file, so that each mistake is reported at its own token
//! and every mistake of a check at once, and the numbers that name
//! something of the scene (objects, materials, lights) kept to be checked
//! against the scene when the lesson opens.

use std::ops::Range;

use serde::Deserialize;
use serde::de::IntoDeserializer;
use toml::Spanned;

use super::expect::{Expect, RawExpect, Tolerance, Value};
use super::measurement::{By, Metric};
use super::quantity::{Part, Quantity, Reads};
use super::{Check, Which};

/// A mistake at a byte range of the lesson file.
pub(crate) type Mistake = (Range<usize>, String);

/// A number in a check naming a part of the scene, with the side it is
/// read on and where it is written.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Reference {
    pub(crate) part: Part,
    pub(crate) side: Which,
    pub(crate) span: Range<usize>,
}

/// An answer or a choice as a teacher writes it: `3`, `1.5`, `true`,
/// `"sphere"`.
#[derive(Deserialize)]
#[serde(untagged)]
pub(crate) enum WrittenValue {
    Integer(i64),
    Float(f64),
    Bool(bool),
    Text(String),
}

impl WrittenValue {
    /// The text a student would type for it.
    pub(crate) fn into_text(self) -> String {
        match self {
            WrittenValue::Integer(i) => i.to_string(),
            WrittenValue::Float(f) => f.to_string(),
            WrittenValue::Bool(b) => b.to_string(),
            WrittenValue::Text(t) => t,
        }
    }
}

/// One check's table, every key optional here so that what is missing or
/// misplaced is said in the format's words.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct WrittenCheck {
    kind: Spanned<String>,
    of: Option<Spanned<String>>,
    is: Option<Spanned<RawExpect>>,
    side: Option<Spanned<String>>,
    question: Option<Spanned<String>>,
    tolerance: Option<Spanned<String>>,
    choices: Option<Spanned<Vec<Spanned<WrittenValue>>>>,
    metric: Option<Spanned<String>>,
    by: Option<Spanned<String>>,
    values: Option<Spanned<Vec<f32>>>,
    checks: Option<Spanned<Vec<Spanned<WrittenCheck>>>>,
}

/// The kinds of check and the keys each takes beside `kind`.
const KINDS: [(&str, &[&str]); 4] = [
    ("value", &["of", "is", "side"]),
    (
        "answer",
        &["question", "of", "tolerance", "choices", "side"],
    ),
    ("measure", &["metric", "is", "by", "values"]),
    ("all", &["checks"]),
];

/// Reads a check, collecting its mistakes and the scene parts it names.
pub(crate) struct Reader<'a> {
    /// The lesson file's text, to find a word inside a quoted value.
    text: &'a str,
    pub(crate) mistakes: Vec<Mistake>,
    pub(crate) references: Vec<Reference>,
}

impl<'a> Reader<'a> {
    pub(crate) fn new(text: &'a str) -> Self {
        Reader {
            text,
            mistakes: Vec::new(),
            references: Vec::new(),
        }
    }

    /// The check `written` describes, or `None` after recording why not.
    pub(crate) fn check(&mut self, written: Spanned<WrittenCheck>) -> Option<Check> {
        let table = written.span();
        let mut w = written.into_inner();
        let kind = w.kind.get_ref().as_str();
        let Some(&(kind, takes)) = KINDS.iter().find(|(k, _)| *k == kind) else {
            let kinds: Vec<&str> = KINDS.iter().map(|(k, _)| *k).collect();
            let why = format!(
                "no check kind `{kind}`; expected one of {}",
                kinds.join(", ")
            );
            self.mistakes.push((w.kind.span(), why));
            return None;
        };
        let given = [
            ("of", w.of.as_ref().map(Spanned::span)),
            ("is", w.is.as_ref().map(Spanned::span)),
            ("side", w.side.as_ref().map(Spanned::span)),
            ("question", w.question.as_ref().map(Spanned::span)),
            ("tolerance", w.tolerance.as_ref().map(Spanned::span)),
            ("choices", w.choices.as_ref().map(Spanned::span)),
            ("metric", w.metric.as_ref().map(Spanned::span)),
            ("by", w.by.as_ref().map(Spanned::span)),
            ("values", w.values.as_ref().map(Spanned::span)),
            ("checks", w.checks.as_ref().map(Spanned::span)),
        ];
        let before = self.mistakes.len();
        for (key, span) in given {
            if let Some(span) = span.filter(|_| !takes.contains(&key)) {
                let why = format!(
                    "a `{kind}` check takes no `{key}`; its keys are `{}`",
                    takes.join("`, `")
                );
                self.mistakes.push((span, why));
            }
        }
        let side = self.side(w.side.take());
        let check = match kind {
            "value" => {
                let of = self.required(w.of, kind, "of", &table);
                let is = self.required(w.is, kind, "is", &table);
                let of = of.and_then(|of| self.quantity(of, side));
                // Without a quantity there is nothing to check `is` against.
                let is = match (is, &of) {
                    (Some(is), Some(of)) => self.expect(is, Some(of), side),
                    (Some(is), None) => self.expect(is, None, side),
                    (None, _) => None,
                };
                match (of, is) {
                    (Some(of), Some(is)) => Some(Check::Value { of, is, side }),
                    _ => None,
                }
            }
            "answer" => self.answer(w, side, &table),
            "measure" => {
                let metric = self.required(w.metric, kind, "metric", &table);
                let is = self.required(w.is, kind, "is", &table);
                let metric = metric.and_then(|m| self.named::<Metric>(m, "metric"));
                let by =
                    w.by.map_or(Some(By::default()), |b| self.named::<By>(b, "`by`"));
                let is = is.and_then(|is| {
                    let span = is.span();
                    let expect = self.expect(is, None, side)?;
                    Reads::Number
                        .accepts(&expect)
                        .map_err(|why| self.mistakes.push((span, format!("a measurement {why}"))))
                        .ok()
                        .map(|()| expect)
                });
                let values = self.sweep_values(w.values, metric);
                match (metric, by, is, values) {
                    (Some(metric), Some(by), Some(is), Some(values)) => Some(Check::Measure {
                        metric,
                        is,
                        by,
                        values,
                    }),
                    _ => None,
                }
            }
            _ => {
                let checks = self.required(w.checks, kind, "checks", &table)?;
                if checks.get_ref().is_empty() {
                    let why = "`all` needs at least one check in `checks`".to_string();
                    self.mistakes.push((checks.span(), why));
                    return None;
                }
                let parts: Vec<Option<Check>> = (checks.into_inner().into_iter())
                    .map(|c| self.check(c))
                    .collect();
                parts
                    .into_iter()
                    .collect::<Option<Vec<_>>>()
                    .map(|checks| Check::All { checks })
            }
        };
        check.filter(|_| self.mistakes.len() == before)
    }

    fn answer(&mut self, w: WrittenCheck, side: Which, table: &Range<usize>) -> Option<Check> {
        let question = self.required(w.question, "answer", "question", table);
        let of = self.required(w.of, "answer", "of", table);
        let question = question.and_then(|q| {
            let span = q.span();
            let text = q.into_inner();
            if text.trim().is_empty() {
                self.mistakes
                    .push((span, "the `question` is empty".to_string()));
                return None;
            }
            Some(text)
        });
        let of = of.and_then(|of| self.quantity(of, side));
        let reads = of.as_ref().map(Quantity::reads);
        let tolerance = match w.tolerance {
            Some(t) => {
                let span = t.span();
                let checked = match (Tolerance::parse(t.get_ref()), &reads) {
                    (Err(why), _) => Err(why),
                    (Ok(_), Some(reads)) if !reads.is_numeric() => Err(format!(
                        "a tolerance needs a number to read, and `{}` is {}",
                        of.as_ref().map_or(String::new(), Quantity::to_string),
                        reads.words()
                    )),
                    (Ok(_), _) => Ok(Some(t.into_inner())),
                };
                checked.map_err(|why| self.mistakes.push((span, why))).ok()
            }
            None => Some(None),
        };
        let mut choices = Vec::new();
        let mut seen = Vec::new();
        for choice in w.choices.map(Spanned::into_inner).unwrap_or_default() {
            let span = choice.span();
            let text = choice.into_inner().into_text();
            let Some(value) = Value::parse(&text) else {
                let why = "a choice is empty: expected the text of each answer".to_string();
                self.mistakes.push((span, why));
                continue;
            };
            if seen.contains(&value) {
                self.mistakes
                    .push((span, format!("the choice `{text}` is given twice")));
                continue;
            }
            if let (Some(reads), Some(of)) = (&reads, &of) {
                if let Err(why) = reads.accepts(&Expect::Is(value.clone())) {
                    self.mistakes
                        .push((span.clone(), format!("the choice `{text}`: `{of}` {why}")));
                }
                self.reference_in_value(of, &value, side, span);
            }
            seen.push(value);
            choices.push(text);
        }
        match (question, of, tolerance) {
            (Some(question), Some(of), Some(tolerance)) => Some(Check::Answer {
                question,
                of,
                tolerance,
                choices,
                side,
            }),
            _ => None,
        }
    }

    /// `key`'s value, or a mistake at the check's table saying it is
    /// missing.
    fn required<T>(
        &mut self,
        value: Option<Spanned<T>>,
        kind: &str,
        key: &str,
        table: &Range<usize>,
    ) -> Option<Spanned<T>> {
        if value.is_none() {
            let why = format!("a `{kind}` check needs `{key}`");
            self.mistakes.push((table.clone(), why));
        }
        value
    }

    fn side(&mut self, side: Option<Spanned<String>>) -> Which {
        side.and_then(|s| self.named::<Which>(s, "side"))
            .unwrap_or_default()
    }

    /// A name serde reads from a word (a metric, `by`, a side), the error
    /// at the word.
    fn named<T: for<'de> Deserialize<'de>>(
        &mut self,
        word: Spanned<String>,
        what: &str,
    ) -> Option<T> {
        let span = word.span();
        let text = word.into_inner();
        let read: Result<T, serde::de::value::Error> =
            T::deserialize(text.as_str().into_deserializer());
        read.map_err(|e| {
            let why = e
                .to_string()
                .replace("unknown variant", &format!("no {what}"));
            self.mistakes.push((span, why));
        })
        .ok()
    }

    /// The quantity `of` names, the numbers in it recorded as references.
    fn quantity(&mut self, of: Spanned<String>, side: Which) -> Option<Quantity> {
        let span = of.span();
        let quantity = Quantity::parse(of.get_ref())
            .map_err(|why| self.mistakes.push((span.clone(), why)))
            .ok()?;
        if let Some((part, word)) = quantity.part() {
            let span = self.word_span(&span, of.get_ref(), word);
            self.references.push(Reference { part, side, span });
        }
        Some(quantity)
    }

    /// What `is` expects, checked against what `of` reads (a number, yes or
    /// no, a word) when it is known: `"at least 5"` for a number is refused
    /// here, not compared as a word later.
    fn expect(
        &mut self,
        is: Spanned<RawExpect>,
        of: Option<&Quantity>,
        side: Which,
    ) -> Option<Expect> {
        let span = is.span();
        let expect = Expect::try_from(is.into_inner())
            .map_err(|why| self.mistakes.push((span.clone(), why)))
            .ok()?;
        let Some(of) = of else {
            return Some(expect);
        };
        if let Err(why) = of.reads().accepts(&expect) {
            self.mistakes.push((span, format!("`{of}` {why}")));
            return None;
        }
        if let Expect::Is(value) = &expect {
            self.reference_in_value(of, value, side, span);
        }
        Some(expect)
    }

    /// An expected object number (`tree eye-object`, `tree blocker L`) as
    /// a reference to check against the scene.
    fn reference_in_value(
        &mut self,
        of: &Quantity,
        value: &Value,
        side: Which,
        span: Range<usize>,
    ) {
        if let (Reads::ObjectOrNone, Value::Number(n)) = (of.reads(), value) {
            let part = Part::Object(*n as usize);
            self.references.push(Reference { part, side, span });
        }
    }

    fn sweep_values(
        &mut self,
        values: Option<Spanned<Vec<f32>>>,
        metric: Option<Metric>,
    ) -> Option<Vec<f32>> {
        let span = values.as_ref().map(Spanned::span);
        let values = values.map(Spanned::into_inner).unwrap_or_default();
        let why = match metric {
            Some(Metric::GridSweep) if values.is_empty() => Some(
                "a `grid-sweep` needs `values`: the grid multipliers to try, e.g. [0.5, 1, 2, 4]"
                    .to_string(),
            ),
            Some(Metric::GridSweep) => values
                .iter()
                .find(|m| !(**m > 0.0 && m.is_finite()))
                .map(|m| format!("a grid multiplier must be above 0, found {m}")),
            Some(_) if !values.is_empty() => Some("only a `grid-sweep` takes `values`".to_string()),
            _ => None,
        };
        match why {
            Some(why) => {
                self.mistakes.push((span.unwrap_or(0..0), why));
                None
            }
            None => Some(values),
        }
    }

    /// The span of word `index` (split at whitespace) inside the string
    /// value at `span`: after its opening quotes.
    fn word_span(&self, span: &Range<usize>, value: &str, index: usize) -> Range<usize> {
        let written = self.text.get(span.clone()).unwrap_or_default();
        let quotes = if written.starts_with("\"\"\"") || written.starts_with("'''") {
            3
        } else {
            1
        };
        let mut offset = 0;
        for (i, word) in value.split_whitespace().enumerate() {
            let at = offset + value[offset..].find(word).unwrap_or(0);
            if i == index {
                let start = span.start + quotes + at;
                return start..start + word.len();
            }
            offset = at + word.len();
        }
        span.clone()
    }
}
