//! The user guide's reference pages checked against the code they
//! document, so that a command, a camera field or an option added without
//! its documentation (or documented and then removed) fails here:
//! `docs/guide/scene-files.md` against the parser's own tables.

use pulldown_cmark::{Event, Options, Parser, Tag, TagEnd};
use std::collections::BTreeSet;
use std::path::Path;

/// A page of the user guide, read.
fn guide_page(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/guide")
        .join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// What a page names in code: the code spans of its headings, and those of
/// each table row's first cell with the heading of the section the table
/// sits in.
#[derive(Default)]
struct Named {
    headings: BTreeSet<String>,
    /// (the section heading's code spans, a first cell's code span).
    table_keys: Vec<(Vec<String>, String)>,
}

fn named(markdown: &str) -> Named {
    let mut found = Named::default();
    let mut in_heading = false;
    let mut section: Vec<String> = Vec::new();
    let mut cell = 0;
    let mut in_cell = false;
    for event in Parser::new_ext(markdown, Options::ENABLE_TABLES) {
        match event {
            Event::Start(Tag::Heading { .. }) => {
                in_heading = true;
                section.clear();
            }
            Event::End(TagEnd::Heading(_)) => in_heading = false,
            Event::Start(Tag::TableRow | Tag::TableHead) => cell = 0,
            Event::Start(Tag::TableCell) => {
                cell += 1;
                in_cell = true;
            }
            Event::End(TagEnd::TableCell) => in_cell = false,
            Event::Code(code) if in_heading => {
                found.headings.insert(code.to_string());
                section.push(code.to_string());
            }
            Event::Code(code) if in_cell && cell == 1 => {
                found.table_keys.push((section.clone(), code.to_string()));
            }
            _ => {}
        }
    }
    found
}

/// What `documented` lacks of `expected`, and what it holds beyond it, as
/// one message per difference.
fn differences(
    page: &str,
    what: &str,
    expected: &BTreeSet<String>,
    documented: &BTreeSet<String>,
) -> Vec<String> {
    let missing = expected
        .difference(documented)
        .map(|name| format!("{page} does not document the {what} `{name}`"));
    let gone = documented
        .difference(expected)
        .map(|name| format!("{page} documents the {what} `{name}`, which no longer exists"));
    missing.chain(gone).collect()
}

#[test]
fn the_scene_file_guide_documents_every_command_and_camera_field() {
    let page = "docs/guide/scene-files.md";
    let found = named(&guide_page("scene-files.md"));
    let commands: BTreeSet<String> = tracer::scene::COMMANDS.map(String::from).into();
    let fields: BTreeSet<String> = tracer::scene::VIEW_FIELDS.map(String::from).into();
    let camera_rows: BTreeSet<String> = (found.table_keys.iter())
        .filter(|(section, _)| section.iter().any(|code| code == "v"))
        .map(|(_, key)| key.clone())
        .collect();
    let mut problems = differences(page, "command (a heading)", &commands, &found.headings);
    problems.extend(differences(
        page,
        "camera field (a row of the `v` table)",
        &fields,
        &camera_rows,
    ));
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
