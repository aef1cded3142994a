//! A folder of lessons, as a teacher hands one to a class: the lesson files
//! it holds, their scenes found beside them. A folder may list its lessons
//! in an index file ([`INDEX`]), which then says which files, in which
//! order; that is also how a folder must be given where nothing can list it
//! (a static web host), so the list comes from [`from_index`] there and
//! from [`files`] here, and everything after reads the same list.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use super::format::{Lesson, LessonErrors, read_lesson_file};
use crate::load::is_lesson_file;

/// The index file's name: one lesson file a line, relative to the folder;
/// blank lines and lines starting with `#` are skipped.
pub(crate) const INDEX: &str = "lessons.index";

/// The lesson files of `dir`: those its index names, else every `.toml`
/// file in it, by name.
pub(crate) fn files(dir: &Path) -> Result<Vec<PathBuf>> {
    let index = dir.join(INDEX);
    if index.is_file() {
        let text = std::fs::read_to_string(&index)
            .with_context(|| format!("cannot read {}", index.display()))?;
        return Ok(from_index(dir, &text));
    }
    let entries =
        std::fs::read_dir(dir).with_context(|| format!("cannot list {}", dir.display()))?;
    let mut files: Vec<PathBuf> = (entries.filter_map(|e| e.ok()))
        .map(|e| e.path())
        .filter(|p| p.is_file() && is_lesson_file(p))
        .collect();
    files.sort();
    Ok(files)
}

/// The lesson files an index in `dir` names, in its order.
pub(crate) fn from_index(dir: &Path, text: &str) -> Vec<PathBuf> {
    from_index_lines(text).map(|l| dir.join(l)).collect()
}

/// The lesson files an index names, as written (relative to its folder),
/// in its order: also what a page fetches, beside the index's URL.
pub(crate) fn from_index_lines(text: &str) -> impl Iterator<Item = &str> {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
}

/// Every lesson of `dir` read, each with its file: a teacher sees every
/// file that does not read, the others still offered.
pub(crate) fn read(dir: &Path) -> Result<Vec<(PathBuf, Result<Lesson, LessonErrors>)>> {
    Ok(files(dir)?
        .into_iter()
        .map(|path| {
            let lesson = read_lesson_file(&path);
            (path, lesson)
        })
        .collect())
}

/// `lessons` in the panel's order: by chapter, and within a chapter in the
/// order they came (the bundled ones first, then each folder's by file).
pub(crate) fn in_chapter_order(lessons: &mut [Lesson]) {
    lessons.sort_by_key(|l| l.chapter);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lessons::format::{SceneFiles, parse_lesson};

    #[test]
    fn an_index_names_the_files_in_its_order() {
        let dir = Path::new("class");
        let text = "# week 1\nprism.toml\n\n  mirrors/plane.toml \n";
        assert_eq!(
            from_index(dir, text),
            [dir.join("prism.toml"), dir.join("mirrors/plane.toml")]
        );
    }

    #[test]
    fn lessons_go_by_chapter_bundled_first() {
        let lesson = |name: &str, chapter: u32| {
            let text = format!(
                "title = \"{name}\"\nchapter = {chapter}\n[scene]\nbundled = \"glass\"\n\
                 [[step]]\ntitle = \"t\"\ntext = \"t\"\n\
                 check = {{ kind = \"value\", of = \"aa\", is = \"on\" }}\n\
                 solution = {{ settings = \"--aa\" }}\n"
            );
            parse_lesson(&text, name, name, SceneFiles::Nowhere).unwrap()
        };
        let mut lessons = vec![
            lesson("bundled 3", 3),
            lesson("bundled 5", 5),
            lesson("mine 5", 5),
            lesson("mine 1", 1),
            lesson("mine 3", 3),
        ];
        in_chapter_order(&mut lessons);
        let names: Vec<&str> = lessons.iter().map(|l| l.name.as_str()).collect();
        assert_eq!(
            names,
            ["mine 1", "bundled 3", "mine 3", "bundled 5", "mine 5"]
        );
    }
}
