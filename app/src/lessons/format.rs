//! The lesson file: TOML read with serde, then checked, every error
//! located by file, line and column (toml's byte spans turned into lines
//! and columns) and saying what was expected, as scene files' errors do.
//! `docs/LESSONS.md` documents the format for teachers.

use std::ops::Range;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;
use tracer::render::View;

use crate::bundled;

use super::actions::{Actions, Located, SettingsLine};
use super::check::Check;
use super::check::Part;
use super::check::written::{Reader, WrittenCheck, WrittenValue};
use super::state::Which;

/// Where a lesson file could not be read, and why.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{file}{}: {message}", place(*.line, *.column))]
pub struct LessonError {
    /// The file's path, or `lessons/NAME.toml` for a bundled lesson.
    pub(crate) file: String,
    /// 1-based line; 0 when the whole file is at fault (it cannot be read).
    pub(crate) line: usize,
    /// 1-based column, in characters; 0 with line 0.
    pub(crate) column: usize,
    pub(crate) message: String,
}

/// `:line:column`, or nothing for the whole file.
fn place(line: usize, column: usize) -> String {
    if line == 0 {
        String::new()
    } else {
        format!(":{line}:{column}")
    }
}

/// Every mistake found in a lesson, in the file's order: a teacher fixes
/// them in one pass.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}", .0.iter().map(ToString::to_string).collect::<Vec<_>>().join("\n"))]
pub struct LessonErrors(pub Vec<LessonError>);

impl From<LessonError> for LessonErrors {
    fn from(error: LessonError) -> Self {
        LessonErrors(vec![error])
    }
}

/// One lesson: a scene, where it starts, and its ordered steps.
#[derive(Debug, Clone)]
pub struct Lesson {
    /// The file stem: what `workbench lesson check NAME` takes.
    pub name: String,
    /// The file as errors name it.
    pub(crate) file: String,
    pub title: String,
    /// The course report's chapter it follows (1 = the camera).
    pub chapter: u32,
    /// What the lesson is about, in a sentence or two.
    pub(crate) summary: String,
    pub scene: LessonScene,
    /// Settings, edits and layout before the first step.
    pub(crate) start: Actions,
    pub(crate) steps: Vec<LessonStep>,
}

/// Where a lesson's scene comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum LessonScene {
    /// One of the scenes embedded in the binary, by name.
    Bundled(String),
    /// A scene file, its path made from the lesson file's folder, where
    /// the lesson names it.
    File(Located<PathBuf>),
    /// A scene file fetched beside a lesson linked from the web page: its
    /// URL, where the lesson names it, and its text.
    Fetched { url: Located<String>, text: String },
    /// P3F written in the lesson; `first_line` is the lesson file's line
    /// holding the scene's line 1, so its errors name the lesson's lines.
    Inline { text: String, first_line: usize },
}

/// One step: what to read, what to do, and the check that says it is done.
#[derive(Debug, Clone)]
pub(crate) struct LessonStep {
    pub(crate) title: String,
    /// The why, with the formula where the course gives one (Markdown).
    pub(crate) text: String,
    /// Shown one at a time, on request.
    pub(crate) hints: Vec<String>,
    /// Optional steps may be skipped; the lesson's summary counts them apart.
    pub(crate) required: bool,
    /// Applied over the earlier steps' solutions when the step is set up.
    pub(crate) setup: Actions,
    pub(crate) check: Located<Check>,
    /// The objects, materials and lights its check names, with the side
    /// read, checked against the scene when the lesson opens.
    pub(crate) references: Vec<Located<(Part, Which)>>,
    /// What a student who solved the step did: `lesson check` applies it
    /// and expects the check to pass.
    pub(crate) solution: Actions,
}

impl Actions {
    /// Whether it does nothing at all.
    pub(crate) fn is_empty(&self) -> bool {
        self.settings.is_none()
            && self.edits.is_empty()
            && self.compare.is_none()
            && self.compare_edits.is_empty()
            && self.pixel.is_none()
            && self.answer.is_none()
            && self.view.is_none()
            && self.observer.is_none()
    }
}

/// The lesson format this workbench reads: a file's `format-version`,
/// absent meaning this one. A later change to the format's names raises
/// it, so that an older workbench refuses a newer file clearly rather than
/// at its first unknown key.
pub(crate) const FORMAT_VERSION: i64 = 1;

/// The version alone, read before the rest (whose keys a later version
/// may have changed).
#[derive(Deserialize)]
struct RawVersion {
    #[serde(rename = "format-version")]
    version: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLesson {
    /// Read by [`RawVersion`] first.
    #[serde(rename = "format-version")]
    _version: Option<i64>,
    title: Spanned<String>,
    chapter: Spanned<u32>,
    #[serde(default)]
    summary: String,
    scene: Spanned<RawScene>,
    #[serde(default)]
    start: Option<Spanned<RawActions>>,
    #[serde(default, rename = "step")]
    steps: Vec<Spanned<RawStep>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    bundled: Option<Spanned<String>>,
    file: Option<Spanned<String>>,
    p3f: Option<Spanned<String>>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawActions {
    settings: Option<Spanned<String>>,
    #[serde(default)]
    edits: Vec<Spanned<String>>,
    compare: Option<Spanned<String>>,
    #[serde(default, rename = "compare-edits")]
    compare_edits: Vec<Spanned<String>>,
    pixel: Option<[u32; 2]>,
    answer: Option<Spanned<WrittenValue>>,
    view: Option<Spanned<String>>,
    observer: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStep {
    title: Spanned<String>,
    text: Spanned<String>,
    #[serde(default)]
    hints: Vec<String>,
    #[serde(default = "required_by_default")]
    required: bool,
    setup: Option<Spanned<RawActions>>,
    check: Spanned<WrittenCheck>,
    solution: Spanned<RawActions>,
}

fn required_by_default() -> bool {
    true
}

/// Reads a lesson file from disk. A file that cannot be read is an error
/// about the whole file, with no line.
pub(crate) fn read_lesson_file(path: &Path) -> Result<Lesson, LessonErrors> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| LessonError {
        file: file.clone(),
        line: 0,
        column: 0,
        message: format!("cannot read the lesson: {e}"),
    })?;
    let name = path
        .file_stem()
        .map_or_else(|| "lesson".into(), |s| s.to_string_lossy().into_owned());
    let scenes = path
        .parent()
        .map_or(SceneFiles::Nowhere, SceneFiles::Folder);
    parse_lesson(&text, &name, &file, scenes)
}

/// The bundled lesson `name`, read.
pub(crate) fn read_bundled(lesson: &bundled::BundledLesson) -> Result<Lesson, LessonErrors> {
    let file = format!("lessons/{}.toml", lesson.name);
    parse_lesson(lesson.text, lesson.name, &file, SceneFiles::Nowhere)
}

/// Where a lesson's `file = ...` scene is read from.
#[derive(Debug, Clone, Copy)]
pub(crate) enum SceneFiles<'a> {
    /// Nowhere: a bundled lesson, or one dropped on the web page.
    Nowhere,
    /// The lesson file's folder on disk.
    Folder(&'a Path),
    /// Fetched beside a lesson linked from the web page: the scene's URL
    /// (the lesson's `file` read beside the lesson's URL) and its text.
    Fetched { url: &'a str, text: &'a str },
}

/// A scene a lesson's `[scene]` names by file or bundled name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum NamedScene {
    /// `file = "prism.p3f"`, relative to the lesson.
    File(String),
    /// `bundled = "tetra"`.
    Bundled(String),
}

/// The scene a lesson's `[scene]` names by file or bundled name, if any,
/// read before the lesson is, so a page can fetch it first.
pub(crate) fn scene_named(text: &str) -> Option<NamedScene> {
    #[derive(Deserialize)]
    struct SceneOnly {
        scene: Option<Named>,
    }
    #[derive(Deserialize)]
    struct Named {
        file: Option<String>,
        bundled: Option<String>,
    }
    let named = toml::from_str::<SceneOnly>(text).ok()?.scene?;
    (named.file.map(NamedScene::File)).or(named.bundled.map(NamedScene::Bundled))
}

/// Reads lesson `text`, named `name`, from `file` (as errors name it);
/// a scene `file = ...` is found in `scenes`. A file TOML cannot read is
/// one error; past that, every mistake is collected.
pub(crate) fn parse_lesson(
    text: &str,
    name: &str,
    file: &str,
    scenes: SceneFiles<'_>,
) -> Result<Lesson, LessonErrors> {
    let source = Source { file, text };
    source.check_version()?;
    let raw: RawLesson = toml::from_str(text)
        .map_err(|e| source.error(e.span().unwrap_or(0..0), e.message().trim_end().to_string()))?;
    let mut errors = Vec::new();
    let title = keep(
        &mut errors,
        nonempty(&source, raw.title, "the lesson's `title`"),
    );
    let chapter = *raw.chapter.get_ref();
    if !(1..=99).contains(&chapter) {
        errors.push(source.error(
            raw.chapter.span(),
            format!("expected a chapter from 1 to 99, found {chapter}"),
        ));
    }
    let scene = keep(&mut errors, source.scene(raw.scene, scenes));
    let start = match raw.start {
        Some(actions) => keep(&mut errors, source.actions(actions, Role::Setup)),
        None => Some(Actions::default()),
    };
    if raw.steps.is_empty() {
        errors.push(source.error(0..0, "expected at least one `[[step]]` table".to_string()));
    }
    let mut steps = Vec::new();
    for step in raw.steps {
        match source.step(step) {
            Ok(step) => steps.push(step),
            Err(LessonErrors(mut more)) => errors.append(&mut more),
        }
    }
    match (title, scene, start) {
        (Some(title), Some(scene), Some(start)) if errors.is_empty() => Ok(Lesson {
            name: name.to_string(),
            file: file.to_string(),
            title,
            chapter,
            summary: raw.summary.trim().to_string(),
            scene,
            start,
            steps,
        }),
        _ => {
            errors.sort_by_key(|e| (e.line, e.column));
            Err(LessonErrors(errors))
        }
    }
}

/// `result`'s value, or `None` with its error kept among `errors`.
fn keep<T>(errors: &mut Vec<LessonError>, result: Result<T, LessonError>) -> Option<T> {
    result.map_err(|e| errors.push(e)).ok()
}

/// The text of `value`, trimmed; an error when it is empty.
fn nonempty(source: &Source, value: Spanned<String>, what: &str) -> Result<String, LessonError> {
    let span = value.span();
    let text = value.into_inner().trim().to_string();
    if text.is_empty() {
        return Err(source.error(span, format!("{what} is empty")));
    }
    Ok(text)
}

/// What a block of actions is for: a solution may answer, a setup may not.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Role {
    Setup,
    Solution,
}

/// The file being read, to turn byte spans into lines and columns.
struct Source<'a> {
    file: &'a str,
    text: &'a str,
}

impl Source<'_> {
    /// The 1-based line and column (in characters) of byte `offset`.
    fn locate(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.text.len());
        let before = self.text.get(..offset).unwrap_or(self.text);
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before[line_start..].chars().count() + 1;
        (line, column)
    }

    fn error(&self, span: Range<usize>, message: String) -> LessonError {
        let (line, column) = self.locate(span.start);
        LessonError {
            file: self.file.to_string(),
            line,
            column,
            message,
        }
    }

    /// A `format-version` other than this workbench's is the one error
    /// said, at its value: a newer file's other keys may mean other
    /// things. A file TOML cannot read is left to the full reading.
    fn check_version(&self) -> Result<(), LessonError> {
        let Ok(RawVersion {
            version: Some(version),
        }) = toml::from_str(self.text)
        else {
            return Ok(());
        };
        let message = match *version.get_ref() {
            FORMAT_VERSION => return Ok(()),
            later if later > FORMAT_VERSION => format!(
                "format-version {later} is newer than this workbench reads (up to \
                 {FORMAT_VERSION}): open the lesson with a newer workbench"
            ),
            other => format!("expected format-version {FORMAT_VERSION}, found {other}"),
        };
        Err(self.error(version.span(), message))
    }

    fn located<T>(&self, span: Range<usize>, value: T) -> Located<T> {
        let (line, column) = self.locate(span.start);
        Located {
            value,
            line,
            column,
        }
    }

    fn scene(
        &self,
        raw: Spanned<RawScene>,
        scenes: SceneFiles<'_>,
    ) -> Result<LessonScene, LessonError> {
        let span = raw.span();
        let raw = raw.into_inner();
        let mut given = Vec::new();
        if let Some(name) = raw.bundled {
            given.push(self.bundled_scene(name, scenes)?);
        }
        if let Some(file) = raw.file {
            given.push(self.scene_file(file, scenes)?);
        }
        if let Some(p3f) = raw.p3f {
            let span = p3f.span();
            // A `"""` string drops the line break right after its quotes,
            // so its first line is the next one.
            let quotes = self.text.get(span.start..).unwrap_or_default();
            let (line, _) = self.locate(span.start);
            let first_line = if quotes.starts_with("\"\"\"\n") || quotes.starts_with("'''\n") {
                line + 1
            } else {
                line
            };
            given.push(LessonScene::Inline {
                text: p3f.into_inner(),
                first_line,
            });
        }
        match given.len() {
            1 => Ok(given.remove(0)),
            found => Err(self.error(
                span,
                format!(
                    "expected exactly one of `bundled`, `file` or `p3f` in [scene], found {found}"
                ),
            )),
        }
    }

    /// A step, with every mistake of its check, its actions and its texts.
    fn step(&self, raw: Spanned<RawStep>) -> Result<LessonStep, LessonErrors> {
        let raw = raw.into_inner();
        let check_span = raw.check.span();
        let mut reader = Reader::new(self.text);
        let check = reader.check(raw.check);
        let mut errors: Vec<LessonError> = (reader.mistakes.into_iter())
            .map(|(span, why)| self.error(span, why))
            .collect();
        let solution_span = raw.solution.span();
        let solution = keep(&mut errors, self.actions(raw.solution, Role::Solution));
        if solution.as_ref().is_some_and(Actions::is_empty) {
            errors.push(self.error(
                solution_span,
                "the solution is empty: expected what a student does to pass the check".into(),
            ));
        }
        let title = keep(&mut errors, nonempty(self, raw.title, "the step's `title`"));
        let text = keep(&mut errors, nonempty(self, raw.text, "the step's `text`"));
        let setup = match raw.setup {
            Some(setup) => keep(&mut errors, self.actions(setup, Role::Setup)),
            None => Some(Actions::default()),
        };
        let references = (reader.references.into_iter())
            .map(|r| self.located(r.span, (r.part, r.side)))
            .collect();
        match (check, solution, title, text, setup) {
            (Some(check), Some(solution), Some(title), Some(text), Some(setup))
                if errors.is_empty() =>
            {
                Ok(LessonStep {
                    title,
                    text,
                    hints: raw.hints,
                    required: raw.required,
                    setup,
                    check: self.located(check_span, check),
                    references,
                    solution,
                })
            }
            _ => Err(LessonErrors(errors)),
        }
    }

    /// The bundled scene `name`: embedded, or on the page a scene of
    /// `scenes/` it does not embed, fetched with the lesson.
    fn bundled_scene(
        &self,
        name: Spanned<String>,
        scenes: SceneFiles<'_>,
    ) -> Result<LessonScene, LessonError> {
        if bundled::find(name.get_ref()).is_some() {
            return Ok(LessonScene::Bundled(name.into_inner()));
        }
        if let SceneFiles::Fetched { url, text } = scenes
            && bundled::site_scene(name.get_ref()).is_some_and(|s| s.url() == url)
        {
            return Ok(LessonScene::Fetched {
                url: self.located(name.span(), url.to_string()),
                text: text.to_string(),
            });
        }
        if bundled::site_scene(name.get_ref()).is_some() {
            return Err(self.error(
                name.span(),
                format!(
                    "the scene `{}` is beside the page, not in it: a lesson linked from the \
                     page (?lesson=URL or ?folder=INDEX) fetches it, a dropped one cannot",
                    name.get_ref()
                ),
            ));
        }
        let offered = bundled::offered();
        let names: Vec<&str> = offered.iter().map(|s| s.name()).collect();
        Err(self.error(
            name.span(),
            format!(
                "no bundled scene called `{}`; expected one of {}",
                name.get_ref(),
                names.join(", ")
            ),
        ))
    }

    /// The scene `file` names, from where `scenes` says files are.
    fn scene_file(
        &self,
        file: Spanned<String>,
        scenes: SceneFiles<'_>,
    ) -> Result<LessonScene, LessonError> {
        match scenes {
            SceneFiles::Nowhere => Err(self.error(
                file.span(),
                "this lesson has no folder to read a scene file from (a bundled lesson, or \
                 one dropped on the web page): give its scene as `bundled` or `p3f`"
                    .into(),
            )),
            SceneFiles::Folder(dir) => {
                let path = dir.join(file.get_ref());
                if !path.is_file() {
                    return Err(self.error(
                        file.span(),
                        format!(
                            "no scene file {} (`file` is read from the lesson's folder)",
                            path.display()
                        ),
                    ));
                }
                Ok(LessonScene::File(self.located(file.span(), path)))
            }
            SceneFiles::Fetched { url, text } => Ok(LessonScene::Fetched {
                url: self.located(file.span(), url.to_string()),
                text: text.to_string(),
            }),
        }
    }

    fn actions(&self, raw: Spanned<RawActions>, role: Role) -> Result<Actions, LessonError> {
        let raw = raw.into_inner();
        let flags = |text: Spanned<String>| -> Result<Located<SettingsLine>, LessonError> {
            let span = text.span();
            let line = SettingsLine::parse(text.get_ref()).map_err(|e| {
                self.error(
                    span.clone(),
                    format!("expected settings (docs/guide/settings.md): {e}"),
                )
            })?;
            Ok(self.located(span, line))
        };
        let answer = match raw.answer {
            Some(answer) if role == Role::Setup => {
                return Err(self.error(
                    answer.span(),
                    "only a step's `solution` may give an `answer`".into(),
                ));
            }
            Some(answer) => Some(answer.into_inner().into_text()),
            None => None,
        };
        let view = match raw.view {
            Some(name) => Some(View::from_name(name.get_ref()).ok_or_else(|| {
                let names: Vec<&str> = View::ALL.iter().map(|v| v.name()).collect();
                self.error(
                    name.span(),
                    format!(
                        "no view `{}`; expected one of {}",
                        name.get_ref(),
                        names.join(", ")
                    ),
                )
            })?),
            None => None,
        };
        let lines = |edits: Vec<Spanned<String>>| -> Vec<Located<String>> {
            edits
                .into_iter()
                .map(|e| {
                    let span = e.span();
                    self.located(span, e.into_inner())
                })
                .collect()
        };
        Ok(Actions {
            settings: raw.settings.map(flags).transpose()?,
            edits: lines(raw.edits),
            compare: raw.compare.map(flags).transpose()?,
            compare_edits: lines(raw.compare_edits),
            pixel: raw.pixel.map(|[x, y]| (x, y)),
            answer,
            view,
            observer: raw.observer,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MINIMAL: &str = r#"title = "Eye rays"
chapter = 1

[scene]
bundled = "glass"

[start]
settings = "--width 32 --height 32"
pixel = [3, 4]

[[step]]
title = "Anti-aliasing"
text = "Turn it on."
check = { kind = "value", of = "aa", is = "on" }
solution = { settings = "--aa" }
"#;

    /// The lesson, or its first mistake.
    fn parse(text: &str) -> Result<Lesson, LessonError> {
        parse_lesson(text, "test", "test.toml", SceneFiles::Nowhere)
            .map_err(|LessonErrors(mut e)| e.remove(0))
    }

    #[test]
    fn a_minimal_lesson_reads() {
        let lesson = parse(MINIMAL).unwrap();
        assert_eq!(lesson.title, "Eye rays");
        assert_eq!(lesson.scene, LessonScene::Bundled("glass".into()));
        assert_eq!(lesson.start.pixel, Some((3, 4)));
        assert_eq!(lesson.steps.len(), 1);
        let step = &lesson.steps[0];
        assert!(step.required);
        assert_eq!((step.check.line, step.check.column), (14, 9));
        assert!(step.solution.settings.as_ref().unwrap().value.overrides.aa);
    }

    #[test]
    fn a_syntax_error_names_its_line_and_column() {
        let broken = MINIMAL.replace("chapter = 1", "chapter = = 1");
        let e = parse(&broken).unwrap_err();
        assert_eq!(
            (e.file.as_str(), e.line, e.column),
            ("test.toml", 2, 11),
            "{e}"
        );
    }

    #[test]
    fn a_scene_file_without_a_folder_says_where_the_scene_can_be() {
        let text = MINIMAL.replace("bundled = \"glass\"", "file = \"prism.p3f\"");
        assert_ne!(text, MINIMAL);
        let e = parse(&text).unwrap_err();
        assert!(
            e.message.contains("no folder to read a scene file from"),
            "{e}"
        );
        assert!(e.message.contains("dropped on the web page"), "{e}");
    }

    #[test]
    fn a_bad_flag_is_located_at_its_string() {
        let broken = MINIMAL.replace("--aa\" }", "--fast\" }");
        let e = parse(&broken).unwrap_err();
        assert_eq!((e.line, e.column), (15, 25), "{e}");
        assert!(e.message.contains("`--fast` is not a setting"), "{e}");
    }

    #[test]
    fn an_unknown_field_says_what_was_expected() {
        let broken = MINIMAL.replace("pixel = [3, 4]", "pixle = [3, 4]");
        let e = parse(&broken).unwrap_err();
        assert_eq!(e.line, 9, "{e}");
        assert!(
            e.message.contains("pixle") && e.message.contains("pixel"),
            "{e}"
        );
    }

    #[test]
    fn a_scene_must_be_given_once() {
        let both = MINIMAL.replace(
            "bundled = \"glass\"",
            "bundled = \"glass\"\np3f = \"s 0 0 0 1\"",
        );
        let e = parse(&both).unwrap_err();
        assert!(e.message.contains("exactly one"), "{e}");
        let unknown = MINIMAL.replace("\"glass\"", "\"glas\"");
        let e = parse(&unknown).unwrap_err();
        assert_eq!((e.line, e.column), (5, 11), "{e}");
    }

    #[test]
    fn an_inline_scene_knows_its_first_line() {
        let inline = MINIMAL.replace(
            "bundled = \"glass\"",
            "p3f = \"\"\"\nv from 0 0 5 at 0 0 0\ns 0 0 0 1\n\"\"\"",
        );
        let lesson = parse(&inline).unwrap();
        let LessonScene::Inline { first_line, .. } = lesson.scene else {
            panic!("{:?}", lesson.scene)
        };
        assert_eq!(first_line, 6);
    }

    #[test]
    fn only_a_solution_answers() {
        let broken = MINIMAL.replace("pixel = [3, 4]", "answer = 3");
        let e = parse(&broken).unwrap_err();
        assert!(e.message.contains("only a step's `solution`"), "{e}");
    }

    #[test]
    fn a_later_format_version_is_the_one_error_said() {
        let current = format!("format-version = {FORMAT_VERSION}\n{MINIMAL}");
        assert!(parse(&current).is_ok());
        let later = format!("format-version = 2\nnew-key = 1\n{MINIMAL}");
        let LessonErrors(errors) =
            parse_lesson(&later, "t", "t.toml", SceneFiles::Nowhere).unwrap_err();
        assert_eq!(errors.len(), 1, "{errors:?}");
        let e = &errors[0];
        assert_eq!((e.line, e.column), (1, 18), "{e}");
        assert!(e.message.contains("format-version 2 is newer"), "{e}");
        let e = parse(&format!("format-version = 0\n{MINIMAL}")).unwrap_err();
        assert_eq!(e.message, "expected format-version 1, found 0");
    }

    #[test]
    fn byte_offsets_become_character_columns() {
        let source = Source {
            file: "f",
            text: "ab\nçé x",
        };
        assert_eq!(source.locate(0), (1, 1));
        assert_eq!(source.locate(3), (2, 1));
        // "çé " is 5 bytes and 3 characters.
        assert_eq!(source.locate(8), (2, 4));
    }
}
