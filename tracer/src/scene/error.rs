//! Parse errors that name the file, line, column and command.

use std::path::PathBuf;

/// Where and why a scene file could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}:{line}:{column}: {kind}", file_name(.file))]
pub struct ParseError {
    /// The file, or `None` for text that did not come from a file.
    pub file: Option<PathBuf>,
    /// 1-based line of the offending token.
    pub line: u32,
    /// 1-based column (in characters) of the offending token.
    pub column: u32,
    /// The command being parsed, if any.
    pub command: Option<String>,
    pub kind: ParseErrorKind,
}

fn file_name(file: &Option<PathBuf>) -> String {
    file.as_ref()
        .map_or_else(|| "<input>".to_string(), |f| f.display().to_string())
}

/// What went wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ParseErrorKind {
    #[error("unknown command `{0}`")]
    UnknownCommand(String),
}
