//! Parse errors that name the file, line, column and command, so a user can
//! find and fix the offending token without guessing.

use std::path::PathBuf;

/// Where and why a scene file could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}:{line}:{column}: {}{kind}", file_name(.file), command_prefix(.command))]
pub struct ParseError {
    /// The file, or `None` for text that did not come from a file.
    pub file: Option<PathBuf>,
    /// 1-based line of the offending token; 0 for problems with the whole
    /// file (it cannot be read or is too large).
    pub line: u32,
    /// 1-based column (in characters) of the offending token; 0 with line 0.
    pub column: u32,
    /// The command being parsed, if any.
    pub command: Option<String>,
    /// What went wrong.
    pub kind: ParseErrorKind,
}

fn file_name(file: &Option<PathBuf>) -> String {
    file.as_ref()
        .map_or_else(|| "<input>".to_string(), |f| f.display().to_string())
}

fn command_prefix(command: &Option<String>) -> String {
    command
        .as_ref()
        .map_or_else(String::new, |c| format!("in `{c}`: "))
}

/// The camera's fields as a sentence: `from, at, ... and focal`.
fn view_fields() -> String {
    match super::VIEW_FIELDS.split_last() {
        Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// What went wrong. Texts are owned or static so the error stays `Clone` and
/// comparable in tests.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParseErrorKind {
    /// A word where a command was expected that names no command.
    #[error("unknown command `{0}`")]
    UnknownCommand(String),
    /// A number where a command was expected: usually one value too many
    /// for the previous command.
    #[error(
        "found the number `{0}` where a command was expected (too many values for the previous command?)"
    )]
    UnexpectedNumber(String),
    /// A word after the `v` fields that is neither a field nor a command.
    #[error("unknown camera field `{0}` (`v` takes {fields})", fields = view_fields())]
    UnknownViewField(String),
    /// The input ended where a value was needed.
    #[error("missing {expected}: the input ends here")]
    MissingValue {
        /// What was expected, e.g. "the sphere radius".
        expected: &'static str,
    },
    /// A token that does not parse as a number.
    #[error("expected {expected}, found `{found}`")]
    NotANumber {
        /// The token as written.
        found: String,
        /// What was expected there, e.g. "the sphere radius".
        expected: &'static str,
    },
    /// A token that should be a whole number but is not one.
    #[error("expected {expected} as a whole number, found `{found}`")]
    NotAnInteger {
        /// The token as written.
        found: String,
        /// What was expected there, e.g. "the sphere radius".
        expected: &'static str,
    },
    /// NaN or infinity, spelt out (`nan`, `inf`) or overflowing (`1e99`).
    #[error("{expected} must be a finite number, found `{found}`")]
    NonFinite {
        /// The token as written.
        found: String,
        /// What was expected there, e.g. "the sphere radius".
        expected: &'static str,
    },
    /// A command with a variable number of values (`f`, `l`, `al`) got a
    /// count it does not accept; reported at the command word.
    #[error("expected {expected} numbers, found {found}")]
    WrongNumberCount {
        /// The accepted counts, e.g. "8 (NFF) or 11 (P3F)".
        expected: &'static str,
        /// How many numbers the line had.
        found: usize,
    },
    /// A value that parses but makes no sense (zero radius, index 0, ...).
    #[error("invalid {what}: {why}")]
    InvalidValue {
        /// The value, e.g. "sphere radius".
        what: &'static str,
        /// The rule it breaks.
        why: String,
    },
    /// A camera that cannot form an image.
    #[error("degenerate camera: {0}")]
    DegenerateCamera(&'static str),
    /// A count or size above a [`super::Limits`] bound.
    #[error("{what} {found} exceeds the limit of {limit}")]
    AboveLimit {
        /// What is counted or measured, e.g. "mesh vertex count".
        what: &'static str,
        /// The value found.
        found: String,
        /// The bound it exceeds.
        limit: u64,
    },
    /// A count that promises more values than the rest of the input holds.
    #[error("{what} {count} needs {needed} more values, but only {remaining} remain in the input")]
    NotEnoughInput {
        /// What the count counts, e.g. "mesh vertices".
        what: &'static str,
        /// The count as written.
        count: u64,
        /// Values the count needs after it.
        needed: u64,
        /// Values the input still holds.
        remaining: u64,
    },
    /// A file with nothing to render; says what is missing.
    #[error("the scene is empty: {0}")]
    EmptyScene(&'static str),
    /// A `mesh_file` that cannot be used: the mesh file's own error, which
    /// names it and the line or element at fault.
    #[error("{0}")]
    MeshFile(String),
    /// The file could not be read (the message of the I/O error).
    #[error("cannot read the scene: {0}")]
    Io(String),
}
