//! The user guide's reference pages checked against the code they
//! document, so that a command, a camera field or an option added without
//! its documentation (or documented and then removed) fails here:
//! `docs/guide/scene-files.md` against the parser's own tables,
//! `docs/guide/command-line.md` against clap's command tree.

use clap::{Args, CommandFactory};
use pulldown_cmark::{CodeBlockKind, Event, Options, Parser, Tag, TagEnd};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use workbench::cli::{Cli, EncodingArgs, SettingsArgs};

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

/// The `--options` a text names.
fn options_in(text: &str) -> impl Iterator<Item = String> + '_ {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
        .filter(|word| word.len() > 2 && word.starts_with("--"))
        .map(|word| word.trim_end_matches('-').to_string())
}

/// One section of a page, under one heading.
#[derive(Default)]
struct Section {
    /// The options of its tables' first cells: what it documents.
    rows: BTreeSet<String>,
    /// Every option it names, in code and code blocks.
    named: BTreeSet<String>,
}

/// The page's sections by heading text.
fn sections(markdown: &str) -> BTreeMap<String, Section> {
    let mut sections: BTreeMap<String, Section> = BTreeMap::new();
    let mut heading: Option<String> = None;
    let mut current = String::new();
    let (mut cell, mut in_cell, mut in_code_block) = (0, false, false);
    for event in Parser::new_ext(markdown, Options::ENABLE_TABLES) {
        match event {
            Event::Start(Tag::Heading { .. }) => heading = Some(String::new()),
            Event::End(TagEnd::Heading(_)) => {
                current = heading.take().unwrap_or_default();
                sections.entry(current.clone()).or_default();
            }
            Event::Text(text) | Event::Code(text) if heading.is_some() => {
                heading.get_or_insert_default().push_str(&text);
            }
            Event::Start(Tag::TableRow | Tag::TableHead) => cell = 0,
            Event::Start(Tag::TableCell) => {
                cell += 1;
                in_cell = true;
            }
            Event::End(TagEnd::TableCell) => in_cell = false,
            Event::Start(Tag::CodeBlock(CodeBlockKind::Fenced(_) | CodeBlockKind::Indented)) => {
                in_code_block = true;
            }
            Event::End(TagEnd::CodeBlock) => in_code_block = false,
            Event::Code(code) => {
                let section = sections.entry(current.clone()).or_default();
                section.named.extend(options_in(&code));
                if in_cell && cell == 1 {
                    section.rows.extend(options_in(&code));
                }
            }
            Event::Text(text) if in_code_block => {
                let section = sections.entry(current.clone()).or_default();
                section.named.extend(options_in(&text));
            }
            _ => {}
        }
    }
    sections
}

/// A command's long options as `--name`, with their aliases when asked.
fn long_options(command: &clap::Command, aliases: bool) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    for arg in command.get_arguments() {
        let Some(long) = arg.get_long() else { continue };
        if matches!(long, "help" | "version") {
            continue;
        }
        names.insert(format!("--{long}"));
        if aliases {
            let more = arg.get_all_aliases().unwrap_or_default();
            names.extend(more.into_iter().map(|a| format!("--{a}")));
        }
    }
    names
}

/// Every command that has no subcommand, by its path (`lesson check`).
fn leaves(command: &clap::Command, path: &str, found: &mut Vec<(String, clap::Command)>) {
    for sub in command.get_subcommands() {
        let name = format!("{path} {}", sub.get_name()).trim().to_string();
        if sub.has_subcommands() {
            leaves(sub, &name, found);
        } else {
            found.push((name, sub.clone()));
        }
    }
}

/// The options every renderer shares: the settings, the encoding and
/// `--threads`, documented once in their own table.
fn shared_options() -> BTreeSet<String> {
    let command = EncodingArgs::augment_args(SettingsArgs::augment_args(clap::Command::new("s")));
    let mut shared = long_options(&command, true);
    shared.insert("--threads".into());
    shared
}

#[test]
fn the_command_line_guide_documents_every_subcommand_and_option() {
    let page = "docs/guide/command-line.md";
    let sections = sections(&guide_page("command-line.md"));
    let root = Cli::command();
    let shared = shared_options();
    let mut commands = vec![("the window".to_string(), root.clone())];
    leaves(&root, "", &mut commands);
    let mut every_option = BTreeSet::from(["--help".to_string(), "--version".to_string()]);
    let mut problems = Vec::new();
    for (name, command) in &commands {
        let options = long_options(command, true);
        every_option.extend(options.iter().cloned());
        let heading = if name == "the window" {
            "The window"
        } else {
            name
        };
        let Some(section) = sections.get(heading) else {
            problems.push(format!("{page} has no section `## {heading}`"));
            continue;
        };
        let own: BTreeSet<String> = long_options(command, false)
            .difference(&shared)
            .cloned()
            .collect();
        problems.extend(
            own.difference(&section.rows)
                .map(|o| format!("{page}: `## {heading}` has no row for `{name} {o}`")),
        );
        problems.extend(section.rows.difference(&options).map(|o| {
            format!("{page}: `## {heading}` documents `{o}`, which `{name}` does not take")
        }));
    }
    match sections.iter().find(|(h, _)| h.starts_with("Settings")) {
        Some((heading, section)) => {
            problems.extend(
                (shared.iter())
                    .filter(|o| !section.rows.contains(*o))
                    .map(|o| format!("{page}: `## {heading}` has no row for `{o}`")),
            );
            problems.extend(section.rows.difference(&shared).map(|o| {
                format!("{page}: `## {heading}` documents `{o}`, which is not a shared option")
            }));
        }
        None => problems.push(format!("{page} has no section `## Settings...`")),
    }
    let named: BTreeSet<&String> = sections.values().flat_map(|s| &s.named).collect();
    problems.extend(
        named
            .into_iter()
            .filter(|o| !every_option.contains(*o))
            .map(|o| format!("{page} names `{o}`, which no command takes")),
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
