//! Values a check reads from the workbench (a number, on/off, a word) and
//! what a lesson expects of them, written as a teacher would: `">= 4"`,
//! `"on"`, `"grid"`, `"1.33 +- 2%"`.

use std::fmt::{self, Display, Formatter};

use serde::Deserialize;

/// A value read from the workbench's state.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Number(f64),
    Bool(bool),
    /// A name: a structure (`grid`), an object's kind (`sphere`), `none`.
    Word(String),
}

impl Display for Value {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Value::Number(n) => write!(f, "{}", number(*n)),
            Value::Bool(true) => f.write_str("on"),
            Value::Bool(false) => f.write_str("off"),
            Value::Word(w) => f.write_str(w),
        }
    }
}

/// A number as people write it: `4`, `1.5`, `0.333`.
pub(crate) fn number(n: f64) -> String {
    let text = format!("{n:.4}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

impl Value {
    /// Reads what a person typed: a number, on/off (yes/no, true/false),
    /// or a word (lower-cased).
    pub(crate) fn parse(text: &str) -> Option<Value> {
        let text = text.trim();
        if text.is_empty() {
            return None;
        }
        if let Ok(n) = text.parse::<f64>() {
            return n.is_finite().then_some(Value::Number(n));
        }
        Some(match text.to_lowercase().as_str() {
            "on" | "yes" | "true" => Value::Bool(true),
            "off" | "no" | "false" => Value::Bool(false),
            word => Value::Word(word.to_string()),
        })
    }

    fn as_number(&self) -> Option<f64> {
        match self {
            Value::Number(n) => Some(*n),
            _ => None,
        }
    }
}

/// How close two numbers must be to count as equal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tolerance {
    /// Within this much either side.
    Absolute(f64),
    /// Within this fraction of the expected value (0.02 for 2%).
    Relative(f64),
}

impl Tolerance {
    /// `"2%"` or `"0.01"`.
    pub(crate) fn parse(text: &str) -> Result<Tolerance, String> {
        let text = text.trim();
        let (digits, relative) = match text.strip_suffix('%') {
            Some(digits) => (digits.trim(), true),
            None => (text, false),
        };
        match digits.parse::<f64>() {
            Ok(v) if v.is_finite() && v >= 0.0 && relative => Ok(Tolerance::Relative(v / 100.0)),
            Ok(v) if v.is_finite() && v >= 0.0 => Ok(Tolerance::Absolute(v)),
            _ => Err(format!(
                "expected a tolerance such as `2%` or `0.01`, found `{text}`"
            )),
        }
    }

    /// Whether `value` is within this tolerance of `expected`. Exact
    /// comparisons still allow the last bits of an f32 setting.
    pub(crate) fn holds(self, value: f64, expected: f64) -> bool {
        let slack = match self {
            Tolerance::Absolute(a) => a,
            Tolerance::Relative(r) => r * expected.abs(),
        };
        (value - expected).abs() <= slack.max(1e-6 * expected.abs().max(1.0))
    }
}

impl Display for Tolerance {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Tolerance::Absolute(a) => write!(f, "{}", number(*a)),
            Tolerance::Relative(r) => write!(f, "{}%", number(r * 100.0)),
        }
    }
}

/// What a check expects of a value.
#[derive(Debug, Clone, PartialEq)]
pub enum Expect {
    /// Equal (numbers up to rounding).
    Is(Value),
    /// A number within a tolerance of another.
    Near(f64, Tolerance),
    AtLeast(f64),
    AtMost(f64),
    Above(f64),
    Below(f64),
}

/// An expectation as TOML gives it: `is = 4`, `is = true`, `is = ">= 4"`.
#[derive(Deserialize)]
#[serde(untagged)]
pub(crate) enum RawExpect {
    Bool(bool),
    Integer(i64),
    Float(f64),
    Text(String),
}

impl TryFrom<RawExpect> for Expect {
    type Error = String;

    fn try_from(raw: RawExpect) -> Result<Self, String> {
        match raw {
            RawExpect::Bool(b) => Ok(Expect::Is(Value::Bool(b))),
            RawExpect::Integer(i) => Ok(Expect::Is(Value::Number(i as f64))),
            RawExpect::Float(f) => Ok(Expect::Is(Value::Number(f))),
            RawExpect::Text(text) => Expect::parse(&text),
        }
    }
}

impl Expect {
    /// `">= 4"`, `"< 0.05"`, `"1.33 +- 2%"`, `"on"`, `"grid"`, `"3"`.
    pub(crate) fn parse(text: &str) -> Result<Expect, String> {
        let trimmed = text.trim();
        let bound = |rest: &str, make: fn(f64) -> Expect| {
            rest.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .map(make)
                .ok_or_else(|| format!("expected a number after the comparison in `{trimmed}`"))
        };
        for (prefix, make) in [
            (">=", Expect::AtLeast as fn(f64) -> Expect),
            ("<=", Expect::AtMost),
            (">", Expect::Above),
            ("<", Expect::Below),
        ] {
            if let Some(rest) = trimmed.strip_prefix(prefix) {
                return bound(rest, make);
            }
        }
        if let Some(rest) = trimmed.strip_prefix('=') {
            return bound(rest, |v| Expect::Is(Value::Number(v)));
        }
        if let Some((value, tolerance)) = trimmed.split_once("+-") {
            let value = value
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("expected a number before `+-` in `{trimmed}`"))?;
            return Ok(Expect::Near(value, Tolerance::parse(tolerance)?));
        }
        Value::parse(trimmed)
            .map(Expect::Is)
            .ok_or_else(|| "expected a value such as `>= 4`, `on`, `grid` or `1.5 +- 2%`".into())
    }

    /// Whether `value` meets the expectation.
    pub(crate) fn holds(&self, value: &Value) -> bool {
        let n = value.as_number();
        match self {
            Expect::Is(Value::Number(e)) => {
                n.is_some_and(|v| Tolerance::Absolute(0.0).holds(v, *e))
            }
            Expect::Is(e) => e == value,
            Expect::Near(e, tolerance) => n.is_some_and(|v| tolerance.holds(v, *e)),
            Expect::AtLeast(e) => n.is_some_and(|v| v >= *e),
            Expect::AtMost(e) => n.is_some_and(|v| v <= *e),
            Expect::Above(e) => n.is_some_and(|v| v > *e),
            Expect::Below(e) => n.is_some_and(|v| v < *e),
        }
    }
}

impl Display for Expect {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Expect::Is(v) => write!(f, "{v}"),
            Expect::Near(v, t) => write!(f, "{} +- {t}", number(*v)),
            Expect::AtLeast(v) => write!(f, ">= {}", number(*v)),
            Expect::AtMost(v) => write!(f, "<= {}", number(*v)),
            Expect::Above(v) => write!(f, "> {}", number(*v)),
            Expect::Below(v) => write!(f, "< {}", number(*v)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn expectations_read_as_written() {
        assert_eq!(Expect::parse(">= 4"), Ok(Expect::AtLeast(4.0)));
        assert_eq!(Expect::parse("<0.05"), Ok(Expect::Below(0.05)));
        assert_eq!(Expect::parse("on"), Ok(Expect::Is(Value::Bool(true))));
        assert_eq!(
            Expect::parse("Grid"),
            Ok(Expect::Is(Value::Word("grid".into())))
        );
        assert_eq!(
            Expect::parse("1.33 +- 2%"),
            Ok(Expect::Near(1.33, Tolerance::Relative(0.02)))
        );
        assert!(Expect::parse(">= many").is_err());
        assert!(Expect::parse("1 +- lots").is_err());
    }

    #[test]
    fn expectations_hold_or_not() {
        let four = Value::Number(4.0);
        assert!(Expect::AtLeast(4.0).holds(&four));
        assert!(!Expect::Above(4.0).holds(&four));
        assert!(Expect::Is(Value::Number(4.0)).holds(&Value::Number(4.000_000_1)));
        assert!(!Expect::Is(Value::Number(4.0)).holds(&Value::Number(4.01)));
        assert!(
            Expect::parse("1.5 +- 5%")
                .unwrap()
                .holds(&Value::Number(1.55))
        );
        assert!(
            !Expect::parse("1.5 +- 1%")
                .unwrap()
                .holds(&Value::Number(1.55))
        );
        // A word never compares with a number.
        assert!(!Expect::AtLeast(0.0).holds(&Value::Word("grid".into())));
        assert!(!Expect::parse("off").unwrap().holds(&Value::Bool(true)));
    }

    #[test]
    fn typed_answers_read_as_values() {
        assert_eq!(Value::parse(" 9 "), Some(Value::Number(9.0)));
        assert_eq!(Value::parse("Yes"), Some(Value::Bool(true)));
        assert_eq!(Value::parse("Sphere"), Some(Value::Word("sphere".into())));
        assert_eq!(Value::parse("  "), None);
        assert_eq!(number(0.25), "0.25");
        assert_eq!(number(3.0), "3");
        assert_eq!(number(-10.0), "-10");
        assert_eq!(number(1e16), "10000000000000000");
        assert_eq!(number(2.0 / 3.0), "0.6667");
    }

    #[test]
    fn tolerances_read_as_written_and_refuse_what_is_not_one() {
        assert_eq!(Tolerance::parse(" 0.01 "), Ok(Tolerance::Absolute(0.01)));
        assert_eq!(Tolerance::parse("0"), Ok(Tolerance::Absolute(0.0)));
        assert_eq!(Tolerance::parse("2 %"), Ok(Tolerance::Relative(0.02)));
        for bad in ["-1", "-2%", "inf", "inf%", "NaN", "lots", "%"] {
            assert!(Tolerance::parse(bad).is_err(), "{bad}");
        }
        assert_eq!(Tolerance::Absolute(0.01).to_string(), "0.01");
        assert_eq!(Tolerance::Relative(0.02).to_string(), "2%");
        assert_eq!(
            Expect::Near(1.5, Tolerance::Relative(0.02)).to_string(),
            "1.5 +- 2%"
        );
    }

    #[test]
    fn a_relative_tolerance_scales_with_the_expected_value() {
        // 10% of 10 is 1: 10.5 is within it, 11.5 is not.
        assert!(Tolerance::Relative(0.1).holds(10.5, 10.0));
        assert!(Tolerance::Relative(0.1).holds(-10.5, -10.0));
        assert!(!Tolerance::Relative(0.1).holds(11.5, 10.0));
        // Exact still allows a millionth of a large value (an f32
        // setting's last bits), not more.
        assert!(Tolerance::Absolute(0.0).holds(1e6 + 0.5, 1e6));
        assert!(!Tolerance::Absolute(0.0).holds(1e6 + 2.0, 1e6));
    }

    #[test]
    fn strict_bounds_refuse_the_bound_itself() {
        let four = Value::Number(4.0);
        assert!(!Expect::Below(4.0).holds(&four));
        assert!(Expect::Below(4.0).holds(&Value::Number(3.9)));
        assert!(!Expect::Above(4.0).holds(&four));
        assert!(Expect::AtMost(4.0).holds(&four));
        assert!(!Expect::AtMost(4.0).holds(&Value::Number(4.1)));
    }
}
