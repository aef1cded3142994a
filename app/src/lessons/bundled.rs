//! The lessons shipped in the binary (`assets/lessons/`, embedded by
//! `build.rs`), in the course's order.

use std::path::Path;

use anyhow::{Result, anyhow};

use crate::bundled::{BundledLesson, LESSONS};

use super::format::{Lesson, LessonErrors, read_bundled, read_lesson_file};

/// The bundled lesson called `name`.
pub(crate) fn find(name: &str) -> Option<&'static BundledLesson> {
    LESSONS.iter().find(|l| l.name == name)
}

/// The names of the bundled lessons, for messages.
pub(crate) fn names() -> Vec<&'static str> {
    LESSONS.iter().map(|l| l.name).collect()
}

/// Every bundled lesson read, in chapter order (then by name); the first
/// one that does not read is the error.
pub fn all() -> Result<Vec<Lesson>, LessonErrors> {
    let mut lessons = LESSONS
        .iter()
        .map(read_bundled)
        .collect::<Result<Vec<_>, _>>()?;
    lessons.sort_by(|a, b| (a.chapter, &a.name).cmp(&(b.chapter, &b.name)));
    Ok(lessons)
}

/// What `workbench --lesson` and `lesson check` take: a bundled lesson by
/// name, or a lesson file (a `.toml` name or a path that exists is a file).
pub(crate) fn read_name_or_file(name_or_file: &Path) -> Result<Lesson> {
    if name_or_file.extension().is_some_and(|e| e == "toml") || name_or_file.exists() {
        return Ok(read_lesson_file(name_or_file)?);
    }
    let name = name_or_file.to_string_lossy();
    let lesson = find(&name).ok_or_else(|| {
        anyhow!(
            "no bundled lesson called `{name}` and no such file; lessons: {}",
            names().join(", ")
        )
    })?;
    Ok(read_bundled(lesson)?)
}
