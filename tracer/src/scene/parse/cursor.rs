//! The token stream as the command parsers see it: typed reads (finite
//! numbers, whole numbers, checked counts) that turn every problem into a
//! [`ParseError`] pointing at the offending token.

use std::path::Path;

use glam::Vec3;

use crate::scene::lexer::{Lexer, Pos, Token};
use crate::scene::{ParseError, ParseErrorKind};

/// A position in the token stream plus what errors need to name.
pub(super) struct Cursor<'a> {
    lexer: Lexer<'a>,
    /// Tokens not consumed yet, so counts can be checked against the input
    /// before anything is allocated for them.
    remaining: u64,
    /// Just after the last token taken: where a missing value is reported.
    last_end: Pos,
    file: Option<&'a Path>,
    /// The command being parsed, named in errors.
    command: Option<&'a str>,
}

/// Whether a token is meant as a number: it starts like one or Rust would
/// parse it as one (`nan`, `inf`). Such a token is never a command word.
pub(super) fn looks_numeric(text: &str) -> bool {
    text.starts_with(|c: char| c.is_ascii_digit() || matches!(c, '+' | '-' | '.'))
        || text.parse::<f32>().is_ok()
}

impl<'a> Cursor<'a> {
    pub fn new(text: &'a str, file: Option<&'a Path>) -> Self {
        let lexer = Lexer::new(text);
        Self {
            lexer,
            remaining: lexer.count().try_into().unwrap_or(u64::MAX),
            last_end: lexer.pos(),
            file,
            command: None,
        }
    }

    /// The file being parsed, if the text came from one.
    pub fn file(&self) -> Option<&'a Path> {
        self.file
    }

    /// Sets the command that later errors name.
    pub(crate) fn set_command(&mut self, command: Option<&'a str>) {
        self.command = command;
    }

    pub fn peek(&self) -> Option<Token<'a>> {
        let mut lexer = self.lexer;
        lexer.next()
    }

    pub(crate) fn next_token(&mut self) -> Option<Token<'a>> {
        let token = self.lexer.next()?;
        self.remaining = self.remaining.saturating_sub(1);
        self.last_end = self.lexer.pos();
        Some(token)
    }

    /// The position of the next token, or just after the last one when
    /// the input has run out.
    pub fn here(&self) -> Pos {
        self.peek().map_or(self.last_end, |t| t.pos)
    }

    pub(crate) fn error_at(&self, pos: Pos, kind: ParseErrorKind) -> ParseError {
        ParseError {
            file: self.file.map(Path::to_path_buf),
            line: pos.line,
            column: pos.column,
            command: self.command.map(str::to_string),
            kind,
        }
    }

    /// `message` with the place a warning is about, written the way errors
    /// are (`file:line:column: in `command`: message`).
    pub(crate) fn warning_at(&self, pos: Pos, message: &str) -> String {
        let file = self
            .file
            .map_or_else(|| "<input>".to_string(), |f| f.display().to_string());
        let command = self
            .command
            .map_or_else(String::new, |c| format!("in `{c}`: "));
        format!("{file}:{}:{}: {command}{message}", pos.line, pos.column)
    }

    /// The next token, or a [`ParseErrorKind::MissingValue`] at the end.
    pub fn expect(&mut self, expected: &'static str) -> Result<Token<'a>, ParseError> {
        let end = self.here();
        self.next_token()
            .ok_or_else(|| self.error_at(end, ParseErrorKind::MissingValue { expected }))
    }

    /// A finite number; NaN and infinity (which `f32::from_str` accepts)
    /// are rejected.
    pub fn number(&mut self, expected: &'static str) -> Result<f32, ParseError> {
        let token = self.expect(expected)?;
        let found = || token.text.to_string();
        match token.text.parse::<f32>() {
            Ok(value) if value.is_finite() => Ok(value),
            Ok(_) => Err(self.error_at(
                token.pos,
                ParseErrorKind::NonFinite {
                    found: found(),
                    expected,
                },
            )),
            Err(_) => Err(self.error_at(
                token.pos,
                ParseErrorKind::NotANumber {
                    found: found(),
                    expected,
                },
            )),
        }
    }

    pub(crate) fn vec3(&mut self, expected: &'static str) -> Result<Vec3, ParseError> {
        Ok(Vec3::new(
            self.number(expected)?,
            self.number(expected)?,
            self.number(expected)?,
        ))
    }

    /// A whole number with an optional sign. Values beyond `i128` saturate;
    /// every caller range-checks, and errors quote the token itself.
    pub fn integer(&mut self, expected: &'static str) -> Result<(i128, Token<'a>), ParseError> {
        let token = self.expect(expected)?;
        let (negative, digits) = match token.text.as_bytes().first() {
            Some(b'-') => (true, token.text.get(1..).unwrap_or_default()),
            Some(b'+') => (false, token.text.get(1..).unwrap_or_default()),
            _ => (false, token.text),
        };
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(self.error_at(
                token.pos,
                ParseErrorKind::NotAnInteger {
                    found: token.text.to_string(),
                    expected,
                },
            ));
        }
        let magnitude = digits.parse::<i128>().unwrap_or(i128::MAX);
        Ok((if negative { -magnitude } else { magnitude }, token))
    }

    /// A count in `0..=limit`, for sizing what follows.
    pub fn count(
        &mut self,
        expected: &'static str,
        limit: usize,
    ) -> Result<(usize, Pos), ParseError> {
        let (value, token) = self.integer(expected)?;
        let what = expected.strip_prefix("the ").unwrap_or(expected);
        if value < 0 {
            return Err(self.error_at(
                token.pos,
                ParseErrorKind::InvalidValue {
                    what,
                    why: format!("must not be negative, found {value}"),
                },
            ));
        }
        match usize::try_from(value) {
            Ok(count) if count <= limit => Ok((count, token.pos)),
            _ => Err(self.error_at(
                token.pos,
                ParseErrorKind::AboveLimit {
                    what,
                    found: token.text.to_string(),
                    limit: limit.try_into().unwrap_or(u64::MAX),
                },
            )),
        }
    }

    /// Checks that `count` items of `per_item` numbers can still follow,
    /// so nothing is reserved for data the input cannot hold.
    pub(crate) fn ensure_input(
        &self,
        what: &'static str,
        count: usize,
        per_item: u64,
        pos: Pos,
    ) -> Result<(), ParseError> {
        let count = u64::try_from(count).unwrap_or(u64::MAX);
        let needed = count.saturating_mul(per_item);
        if needed <= self.remaining {
            return Ok(());
        }
        Err(self.error_at(
            pos,
            ParseErrorKind::NotEnoughInput {
                what,
                count,
                needed,
                remaining: self.remaining,
            },
        ))
    }

    /// How many number-like tokens come next, for commands whose form
    /// depends on their count (`f`, `l`, `al`).
    pub(crate) fn numbers_ahead(&self) -> usize {
        let mut lexer = self.lexer;
        let mut count = 0;
        while lexer.next().is_some_and(|t| looks_numeric(t.text)) {
            count += 1;
        }
        count
    }
}
