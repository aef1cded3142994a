//! Tests of the scene parser and writer, split by concern.

mod commands;
mod corpus;
mod errors;
mod fuzz;
mod mesh_file;
mod roundtrip;

use std::path::Path;

use super::{Limits, ParseError, ParseErrorKind, Scene, parse_scene, write_p3f};

/// Parses text with the default limits.
fn parse(text: &str) -> Result<Scene, ParseError> {
    parse_scene(text, None, &Limits::default())
}

/// Parses text that must be valid.
fn parse_ok(text: &str) -> Scene {
    parse(text).unwrap_or_else(|e| panic!("{e}\n--- in ---\n{text}"))
}

/// Parses text that must fail, and checks where and in which command.
fn parse_err(text: &str, line: u32, column: u32, command: Option<&str>) -> ParseErrorKind {
    parse_err_with(text, &Limits::default(), line, column, command)
}

fn parse_err_with(
    text: &str,
    limits: &Limits,
    line: u32,
    column: u32,
    command: Option<&str>,
) -> ParseErrorKind {
    let error = match parse_scene(text, None, limits) {
        Ok(scene) => panic!("expected an error, parsed {scene:?}\n--- from ---\n{text}"),
        Err(error) => error,
    };
    assert_eq!(
        (error.line, error.column, error.command.as_deref()),
        (line, column, command),
        "{error}"
    );
    error.kind
}

/// Writes a scene and parses it again, checking it comes back equal.
fn assert_round_trip(scene: &Scene) {
    let text = write_p3f(scene);
    let again = parse_scene(&text, None, &Limits::default())
        .unwrap_or_else(|e| panic!("{e}\n--- in written ---\n{text}"));
    let original = Scene {
        base_dir: None,
        ..scene.clone()
    };
    assert_eq!(again, original, "--- written ---\n{text}");
}

/// The shared corpus of real scene files, if this checkout has it (under
/// `CI` its absence fails the test: [`crate::optional_input::missing`]).
fn corpus_dir() -> Option<&'static Path> {
    let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/corpus"));
    if !dir.is_dir() {
        crate::optional_input::missing(&format!("the shared corpus {}", dir.display()));
        return None;
    }
    Some(dir)
}
