//! The values a study sweeps, as a user types them: a list of numbers and
//! ranges, e.g. `0.25,0.5,1`, `1..5` (integers 1 to 5), `1..2:0.25` (add
//! 0.25 each step) or `0.5..8:x2` (double each step). Ranges include their
//! end; the result is sorted and without repeats, as points on an x axis.

use std::fmt;

/// Most values one study may have: beyond this a typo (`1..1000000`) is
/// more likely than a wish.
pub(crate) const MAX_VALUES: usize = 1000;

/// Why a values text was refused, with the piece at fault.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct ValuesError(pub String);

impl fmt::Display for ValuesError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ValuesError {}

/// The syntax, for help texts and error messages.
pub(crate) const SYNTAX: &str = "a comma-separated list of numbers and ranges: `a..b` (a, a+1, ..., b), \
                          `a..b:s` (add s each step) or `a..b:xf` (multiply by f each step)";

fn fail<T>(message: String) -> Result<T, ValuesError> {
    Err(ValuesError(message))
}

fn number(text: &str, item: &str) -> Result<f64, ValuesError> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => fail(format!(
            "`{}` in `{item}` is not a number (expected {SYNTAX})",
            text.trim()
        )),
    }
}

/// Parses `text` into ascending values without repeats.
pub(crate) fn parse(text: &str) -> Result<Vec<f64>, ValuesError> {
    if text.trim().is_empty() {
        return fail(format!("no values given (expected {SYNTAX})"));
    }
    let mut values = Vec::new();
    for item in text.split(',') {
        let item = item.trim();
        if item.is_empty() {
            return fail(format!("an empty item in `{text}` (two commas?)"));
        }
        match item.split_once("..") {
            None => values.push(number(item, item)?),
            Some((start, rest)) => range(item, start, rest, &mut values)?,
        }
        if values.len() > MAX_VALUES {
            return fail(format!("more than {MAX_VALUES} values in `{text}`"));
        }
    }
    values.sort_by(f64::total_cmp);
    values.dedup();
    Ok(values)
}

/// Appends the values of the range `item` (`start..end[:step]`).
fn range(item: &str, start: &str, rest: &str, values: &mut Vec<f64>) -> Result<(), ValuesError> {
    let (end, step) = match rest.split_once(':') {
        Some((end, step)) => (end, Some(step.trim())),
        None => (rest, None),
    };
    let start = number(start, item)?;
    let end = number(end, item)?;
    if start > end {
        return fail(format!("`{item}` runs backwards: {start} is above {end}"));
    }
    let push = |v: f64, values: &mut Vec<f64>| -> Result<(), ValuesError> {
        values.push(v);
        if values.len() > MAX_VALUES {
            return fail(format!("`{item}` has more than {MAX_VALUES} values"));
        }
        Ok(())
    };
    match step.and_then(|s| s.strip_prefix(['x', 'X', '*'])) {
        Some(factor) => {
            let factor = number(factor, item)?;
            if factor <= 1.0 {
                return fail(format!("the factor in `{item}` must be above 1"));
            }
            if start <= 0.0 {
                return fail(format!(
                    "`{item}` multiplies, so it must start above 0, not at {start}"
                ));
            }
            let mut v = start;
            // A little slack so that 0.1..0.8:x2 ends at 0.8 despite rounding.
            while v <= end * (1.0 + 1e-9) {
                push(v, values)?;
                v *= factor;
            }
        }
        None => {
            let step = match step {
                Some(s) => number(s, item)?,
                None => 1.0,
            };
            if step <= 0.0 {
                return fail(format!("the step in `{item}` must be above 0"));
            }
            // Counted, not accumulated, so 1..2:0.1 has no drift.
            let count = ((end - start) / step + 1e-9).floor();
            if count >= MAX_VALUES as f64 {
                return fail(format!("`{item}` has more than {MAX_VALUES} values"));
            }
            for i in 0..=count as usize {
                push(start + i as f64 * step, values)?;
            }
        }
    }
    Ok(())
}

/// A value as a user would write it: `2`, `0.25`.
pub(crate) fn format(value: f64) -> String {
    let text = format!("{value:.6}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ok(text: &str) -> Vec<f64> {
        parse(text).unwrap_or_else(|e| panic!("{text}: {e}"))
    }

    #[test]
    fn lists_are_sorted_without_repeats() {
        assert_eq!(ok("0.25, 0.5,1,2"), [0.25, 0.5, 1.0, 2.0]);
        assert_eq!(ok("4,1,4,2"), [1.0, 2.0, 4.0]);
        assert_eq!(ok("7"), [7.0]);
    }

    #[test]
    fn ranges_step_by_one_by_a_step_or_by_a_factor() {
        assert_eq!(ok("1..5"), [1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!(ok("1..2:0.25"), [1.0, 1.25, 1.5, 1.75, 2.0]);
        assert_eq!(ok("0.5..8:x2"), [0.5, 1.0, 2.0, 4.0, 8.0]);
        // The end is included only when a step lands on it.
        assert_eq!(ok("1..10:x3"), [1.0, 3.0, 9.0]);
        assert_eq!(ok("0..1:0.4"), [0.0, 0.4, 0.8]);
        // No drift: ten steps of 0.1 land on 2.
        let tenths = ok("1..2:0.1");
        assert_eq!(tenths.len(), 11);
        assert!((tenths[10] - 2.0).abs() < 1e-12);
        assert_eq!(ok("3..3"), [3.0]);
        assert_eq!(ok("1..3, 8, 16..32:x2"), [1.0, 2.0, 3.0, 8.0, 16.0, 32.0]);
    }

    #[test]
    fn bad_input_says_what_is_wrong() {
        let error = |text: &str| parse(text).unwrap_err().to_string();
        assert!(error("").contains("no values"));
        assert!(error("1,,2").contains("empty item"));
        assert!(error("1,two").contains("`two`"));
        assert!(error("1..x").contains("`x` in `1..x`"));
        assert!(error("5..1").contains("backwards"));
        assert!(error("1..4:0").contains("step"));
        assert!(error("1..4:-1").contains("step"));
        assert!(error("1..4:x1").contains("factor"));
        assert!(error("0..4:x2").contains("above 0"));
        assert!(error("1..1e9").contains("more than"));
        assert!(error("nan").contains("not a number"));
        assert!(error("inf").contains("not a number"));
    }

    #[test]
    fn values_print_as_typed() {
        assert_eq!(format(2.0), "2");
        assert_eq!(format(0.25), "0.25");
        assert_eq!(format(1.0 / 3.0), "0.333333");
    }
}
