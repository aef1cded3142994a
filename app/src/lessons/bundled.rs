//! The lessons shipped in the binary (`assets/lessons/`, embedded by
//! `build.rs`), in the course's order.

use crate::bundled::{BundledLesson, LESSONS};

use super::format::{Lesson, LessonErrors, read_bundled};

/// The bundled lesson called `name`.
pub fn find(name: &str) -> Option<&'static BundledLesson> {
    LESSONS.iter().find(|l| l.name == name)
}

/// The names of the bundled lessons, for messages.
pub fn names() -> Vec<&'static str> {
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
