//! `workbench lesson new NAME`: a commented starting file a teacher edits,
//! which passes `lesson check` as written (a sphere over a floor, a
//! settings step and a pinned-pixel step), so every change is tested from
//! a lesson that worked.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

/// The starting file, `{title}` and `{file}` filled in.
const TEMPLATE: &str = include_str!("template.toml");

/// The file `name` means: `NAME.toml`, or `name` itself when it already
/// ends in `.toml`.
pub(crate) fn path_for(name: &str) -> PathBuf {
    let path = Path::new(name);
    if crate::load::is_lesson_file(path) {
        path.to_path_buf()
    } else {
        PathBuf::from(format!("{name}.toml"))
    }
}

/// The starting file's text for `path`: its title from the file's name
/// (`light_and_shadow` becomes "Light and shadow").
pub(crate) fn text_for(path: &Path) -> String {
    let stem = path.file_stem().map_or_else(
        || "lesson".into(),
        |s| s.to_string_lossy().replace(['_', '-'], " "),
    );
    let mut title: String = stem.trim().to_string();
    if let Some(first) = title.get(..1) {
        title = first.to_uppercase() + &title[1..];
    }
    TEMPLATE
        .replace("{title}", &title.replace('"', "'"))
        .replace("{file}", &path.display().to_string())
}

/// Writes the starting file for `name`, never over an existing file;
/// returns where.
pub(crate) fn write(name: &str) -> Result<PathBuf> {
    if name.trim().is_empty() {
        bail!("expected a lesson name, such as `light_and_shadow`");
    }
    let path = path_for(name);
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&path)
        .with_context(|| match path.exists() {
            true => format!("{} exists already: nothing written", path.display()),
            false => format!("cannot write {}", path.display()),
        })?;
    file.write_all(text_for(&path).as_bytes())
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lessons::format::{SceneFiles, parse_lesson};

    #[test]
    fn the_starting_file_reads_and_is_titled_by_its_name() {
        let path = path_for("light_and-shadow");
        assert_eq!(path, PathBuf::from("light_and-shadow.toml"));
        assert_eq!(path_for("a/b.toml"), PathBuf::from("a/b.toml"));
        let text = text_for(&path);
        assert!(
            !text.contains("{title}") && !text.contains("{file}"),
            "{text}"
        );
        let lesson = parse_lesson(
            &text,
            "light_and-shadow",
            "light_and-shadow.toml",
            SceneFiles::Nowhere,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(lesson.title, "Light and shadow");
        assert_eq!(lesson.steps.len(), 2);
    }
}
