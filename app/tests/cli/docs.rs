//! The user's documents: README, CONTRIBUTING and everything under `docs/`
//! (the user guide among them). Every relative link resolves, down to the
//! heading it points at, and no user-facing text calls the course's report
//! "the seed", a name from the project's history that no user can decode.

use pulldown_cmark::{Event, Parser, Tag, TagEnd};
use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("app/ sits in the workspace")
        .to_path_buf()
}

/// Every file under `dir` whose name ends in `extension`, sorted.
fn files_under(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.expect("a readable folder entry").path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == extension) {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

/// README, CONTRIBUTING and every Markdown file under `docs/`.
fn documents() -> Vec<PathBuf> {
    let root = repo_root();
    let mut documents = vec![root.join("README.md"), root.join("CONTRIBUTING.md")];
    documents.extend(files_under(&root.join("docs"), "md"));
    documents
}

fn read(path: &Path) -> String {
    fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A heading's anchor as GitHub makes it: lower case, every character but
/// letters, digits, spaces, `-` and `_` dropped, spaces made `-`.
fn slug(heading: &str) -> String {
    heading
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .flat_map(char::to_lowercase)
        .collect()
}

/// What a Markdown document links to and which anchors its headings make.
struct Outline {
    links: Vec<String>,
    anchors: Vec<String>,
}

fn outline(markdown: &str) -> Outline {
    let mut links = Vec::new();
    let mut anchors = Vec::new();
    let mut seen: HashMap<String, usize> = HashMap::new();
    let mut heading: Option<String> = None;
    for event in Parser::new(markdown) {
        match event {
            Event::Start(Tag::Link { dest_url, .. } | Tag::Image { dest_url, .. }) => {
                links.push(dest_url.to_string());
            }
            Event::Start(Tag::Heading { .. }) => heading = Some(String::new()),
            Event::Text(text) | Event::Code(text) => {
                if let Some(heading) = &mut heading {
                    heading.push_str(&text);
                }
            }
            Event::End(TagEnd::Heading(_)) => {
                let base = slug(&heading.take().unwrap_or_default());
                // GitHub numbers a repeated heading's anchor: `a`, `a-1`, ...
                let count = seen.entry(base.clone()).or_insert(0);
                anchors.push(match *count {
                    0 => base.clone(),
                    n => format!("{base}-{n}"),
                });
                *count += 1;
            }
            _ => {}
        }
    }
    Outline { links, anchors }
}

fn is_external(target: &str) -> bool {
    target.contains("://") || target.starts_with("mailto:")
}

#[test]
fn every_relative_link_in_the_documents_resolves() {
    let root = repo_root();
    let mut broken = Vec::new();
    let mut checked = 0;
    for document in documents() {
        let text = read(&document);
        let name = document.strip_prefix(&root).unwrap().display().to_string();
        for target in outline(&text).links {
            if is_external(&target) {
                continue;
            }
            checked += 1;
            let (path, anchor) = target.split_once('#').unwrap_or((&target, ""));
            let file = if path.is_empty() {
                document.clone()
            } else {
                document.parent().unwrap().join(path)
            };
            if !file.exists() {
                broken.push(format!("{name}: {target}: no file {}", file.display()));
                continue;
            }
            let is_markdown = file.extension().is_some_and(|e| e == "md");
            if !anchor.is_empty() && is_markdown {
                let anchors = outline(&read(&file)).anchors;
                if !anchors.iter().any(|a| a == anchor) {
                    broken.push(format!(
                        "{name}: {target}: no heading makes #{anchor}; there are {anchors:?}"
                    ));
                }
            }
        }
    }
    assert!(
        checked > 50,
        "only {checked} links found: is the parser reading the documents?"
    );
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_readme_links_every_page_of_the_guide() {
    let root = repo_root();
    let links = outline(&read(&root.join("README.md"))).links;
    let unlinked: Vec<String> = files_under(&root.join("docs/guide"), "md")
        .iter()
        .map(|page| page.strip_prefix(&root).unwrap().display().to_string())
        .filter(|page| {
            !links
                .iter()
                .any(|link| link.split('#').next() == Some(page))
        })
        .collect();
    assert!(
        unlinked.is_empty(),
        "README.md should link these pages of the guide: {unlinked:?}"
    );
}

#[test]
fn anchors_are_made_as_github_makes_them() {
    assert_eq!(
        slug("Against Embree: `bench --rays`"),
        "against-embree-bench---rays"
    );
    assert_eq!(
        slug("On a 2-core AMD EPYC (Zen 3) VM"),
        "on-a-2-core-amd-epyc-zen-3-vm"
    );
    let doc = outline("# Setup\n\ntext [a](b.md#c)\n\n## Setup\n\n```\n# not a heading\n```\n");
    assert_eq!(doc.anchors, ["setup", "setup-1"]);
    assert_eq!(doc.links, ["b.md#c"]);
}

/// The user-facing texts: README, the user guide, the command line's help
/// (`cli.rs`, whose doc comments clap shows) and the window's sources.
fn user_facing_texts() -> Vec<PathBuf> {
    let root = repo_root();
    let mut texts = vec![root.join("README.md"), root.join("app/src/cli.rs")];
    texts.extend(files_under(&root.join("docs/guide"), "md"));
    texts.extend(files_under(&root.join("app/src/gui"), "rs"));
    texts
}

/// Words that, after "the seed", make it the course's report rather than
/// the random numbers' seed: what the report did, or what it is.
const REPORT_WORDS: [&str; 14] = [
    "needed", "measured", "took", "used", "had", "did", "only", "ran", "gave", "report", "course",
    "paper", "table", "timing",
];

/// The phrases of `text` that speak of the course's report as "the seed",
/// each with a little of its context. The random numbers' seed (`--seed`,
/// "seed of every random number", "the `seed` setting") passes.
fn seed_report_phrases(text: &str) -> Vec<String> {
    // One line of prose, whatever wrapped it: comment markers, string
    // continuations and line breaks become single spaces.
    let prose = text
        .replace("\\\n", " ")
        .replace("//!", " ")
        .replace("///", " ")
        .replace('\u{2019}', "'")
        .to_lowercase();
    let words: Vec<&str> = prose.split_whitespace().collect();
    let mut found = Vec::new();
    for (i, word) in words.iter().enumerate() {
        let bare = word.trim_matches(|c: char| !c.is_alphanumeric() && c != '\'' && c != '-');
        let next = words.get(i + 1).map_or("", |w| {
            let w = w.trim_matches(|c: char| !c.is_alphanumeric());
            w.strip_suffix("'s").unwrap_or(w)
        });
        let after_the = i > 0 && words[i - 1] == "the";
        let speaks_of_the_report = bare == "seed's"
            || bare.contains("seed-report")
            || (bare == "seed" && next == "report")
            || (bare == "seed" && after_the && REPORT_WORDS.contains(&next));
        if speaks_of_the_report {
            let from = i.saturating_sub(4);
            let to = (i + 5).min(words.len());
            found.push(words[from..to].join(" "));
        }
    }
    found
}

#[test]
fn no_user_facing_text_calls_the_course_report_the_seed() {
    let root = repo_root();
    let mut found = Vec::new();
    for path in user_facing_texts() {
        let name = path.strip_prefix(&root).unwrap().display().to_string();
        for phrase in seed_report_phrases(&read(&path)) {
            found.push(format!("{name}: \"... {phrase} ...\""));
        }
    }
    assert!(
        found.is_empty(),
        "call it the course's report, not the seed:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_seed_report_is_told_from_the_random_seed() {
    for report in [
        "`M` opens the seed report's timing table (Figure 5.1)",
        "The seed needed 0.77-1.03 s for the first row",
        "/// as the seed\n    /// measured it",
        "see ../shared/docs/seed-report.md",
        "\"the seed \\\n  report's matrix\"",
    ] {
        assert_eq!(seed_report_phrases(report).len(), 1, "missed in {report:?}");
    }
    for seed in [
        "| `--seed S` | seed of every random number |",
        "a pure function of the pixel, the sample index and the `seed` setting",
        "/// Seed of the generator's randomness (default 0).\n pub seed: Option<u64>,",
        "WORKBENCH_SOAK_SEED=N for another sequence; 300 seeded random actions",
        "with the seed 3 the image changes",
    ] {
        assert_eq!(
            seed_report_phrases(seed),
            Vec::<String>::new(),
            "flagged {seed:?}"
        );
    }
}
