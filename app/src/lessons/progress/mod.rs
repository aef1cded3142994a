//! What a student did in the Lessons panel, as the window keeps it and as
//! it leaves the window: the exported file (JSON, with a `format-version`
//! as lesson files have) that `workbench lesson progress` reads, turns into
//! tables and merges for a class. A record, not a proof: anyone can edit it.

pub(crate) mod table;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use serde::{Deserialize, Serialize};

/// The version of the exported file this workbench writes and reads.
pub(crate) const FORMAT_VERSION: u32 = 1;

/// The steps done, per lesson name, counted from 0: what the panel colours
/// and what persists across restarts.
pub(crate) type StepsDone = BTreeMap<String, BTreeSet<usize>>;

/// What the window noted when a step turned done, per lesson name and
/// step (from 0). States saved before it was kept have none.
pub(crate) type StepNotes = BTreeMap<String, BTreeMap<usize, StepNote>>;

/// When a step turned done, and the answer it was done with.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub(crate) struct StepNote {
    /// The wall clock then, `YYYY-MM-DD HH:MM UTC`.
    pub(crate) done_at: Option<String>,
    /// The answer submitted, as typed or picked, when the step asked one.
    pub(crate) answer: Option<String>,
}

/// What the window keeps of the lessons across restarts: the name the
/// student typed, the steps done and what was noted when each turned done.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Record {
    pub(crate) student: String,
    pub done: StepsDone,
    pub(crate) notes: StepNotes,
}

impl Record {
    /// Marks step `step` (from 0) of `lesson` done, noting `done_at` and
    /// the `answer` it was done with the first time only: a step done again
    /// keeps when it was first done.
    pub(crate) fn mark_done(
        &mut self,
        lesson: &str,
        step: usize,
        done_at: String,
        answer: Option<String>,
    ) {
        if self
            .done
            .entry(lesson.to_string())
            .or_default()
            .insert(step)
        {
            let note = StepNote {
                done_at: Some(done_at),
                answer,
            };
            self.notes
                .entry(lesson.to_string())
                .or_default()
                .insert(step, note);
        }
    }

    /// Forgets every step done of `lesson`.
    pub(crate) fn forget(&mut self, lesson: &str) {
        self.done.remove(lesson);
        self.notes.remove(lesson);
    }

    /// The exported file's form: steps from 1, a blank name as none.
    pub(crate) fn export(&self) -> Progress {
        let student = self.student.trim();
        let lessons = (self.done.iter())
            .filter(|(_, steps)| !steps.is_empty())
            .map(|(lesson, steps)| LessonProgress {
                lesson: lesson.clone(),
                steps: steps
                    .iter()
                    .map(|&step| {
                        let note = self.notes.get(lesson).and_then(|n| n.get(&step));
                        StepDone {
                            step: step + 1,
                            done_at: note.and_then(|n| n.done_at.clone()),
                            answer: note.and_then(|n| n.answer.clone()),
                        }
                    })
                    .collect(),
            })
            .collect();
        Progress {
            format_version: FORMAT_VERSION,
            student: (!student.is_empty()).then(|| student.to_string()),
            lessons,
        }
    }
}

/// The exported file: who, and per lesson the steps done.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct Progress {
    pub(crate) format_version: u32,
    /// The name the student typed in the panel, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub student: Option<String>,
    pub lessons: Vec<LessonProgress>,
}

/// One lesson's steps done, in order.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct LessonProgress {
    /// The lesson's name (its file stem), as `lesson check` takes it.
    pub lesson: String,
    pub steps: Vec<StepDone>,
}

/// A step done: its number from 1 (as the panel and `lesson check` count),
/// when, and the answer given, each only if the window recorded it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub struct StepDone {
    pub step: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub done_at: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub answer: Option<String>,
}

impl Progress {
    /// The exported file's text.
    pub(crate) fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("progress serializes") + "\n"
    }

    /// Reads an exported file's `text`; a mistake is said with `file`, its
    /// line and column.
    pub fn from_json(text: &str, file: &Path) -> Result<Progress> {
        let at = |e: serde_json::Error| {
            let message = e.to_string();
            let message = message
                .rsplit_once(" at line ")
                .map_or(message.as_str(), |(m, _)| m);
            let column = token_start(text, e.line(), e.column());
            anyhow!("{}:{}:{column}: {message}", file.display(), e.line())
        };
        #[derive(Deserialize)]
        struct Version {
            #[serde(rename = "format-version")]
            version: Option<serde_json::Value>,
        }
        let version: Version = serde_json::from_str(text).map_err(at)?;
        match version.version {
            None => bail!(
                "{}: no format-version: not a progress file the workbench exported",
                file.display()
            ),
            Some(v) if v.as_u64().is_some_and(|v| v > u64::from(FORMAT_VERSION)) => bail!(
                "{}: format-version {v} is newer than this workbench reads (up to \
                 {FORMAT_VERSION}): read it with a newer workbench",
                file.display()
            ),
            Some(_) => {}
        }
        serde_json::from_str(text).map_err(at)
    }

    /// The student's name: the file's `student`, else `fallback`.
    pub(crate) fn student_or<'a>(&'a self, fallback: &'a str) -> &'a str {
        self.student.as_deref().unwrap_or(fallback)
    }
}

/// serde_json places a mistake in a string (a key misspelt, a value of
/// the wrong kind) at its closing quote: the column of its opening quote
/// instead, where the word starts. Other places are kept.
fn token_start(text: &str, line: usize, column: usize) -> usize {
    let Some(chars) = text
        .lines()
        .nth(line.wrapping_sub(1))
        .map(|l| l.chars().collect::<Vec<_>>())
    else {
        return column;
    };
    if column == 0 || chars.get(column - 1) != Some(&'"') {
        return column;
    }
    let opening = (0..column - 1)
        .rev()
        .find(|&i| chars[i] == '"' && (i == 0 || chars[i - 1] != '\\'));
    opening.map_or(column, |i| i + 1)
}

/// The part of the window's saved state (eframe's `app` key, RON) the
/// lessons own, under the names the window saves them with
/// (`gui::app::persisted`); the rest is ignored.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct SavedLessons {
    lessons: StepsDone,
    lesson_notes: StepNotes,
    student: String,
}

/// Where the window keeps its state (eframe's storage file), as eframe
/// finds it for the window's title; `None` without a home folder.
pub(crate) fn window_state_file() -> Option<PathBuf> {
    let folder = if cfg!(target_os = "macos") {
        std::env::home_dir()?.join("Library/Application Support/Whitted-Workbench")
    } else if cfg!(windows) {
        PathBuf::from(std::env::var_os("APPDATA")?).join("Whitted Workbench\\data")
    } else {
        std::env::var_os("XDG_DATA_HOME")
            .map(PathBuf::from)
            .filter(|p| p.is_absolute())
            .or_else(|| std::env::home_dir().map(|h| h.join(".local/share")))?
            .join("whittedworkbench")
    };
    Some(folder.join("app.ron"))
}

/// Reads the progress in `file`: an exported file, or (a `.ron` file) the
/// window's saved state.
pub(crate) fn read(file: &Path) -> Result<Progress> {
    let text = std::fs::read_to_string(file)
        .with_context(|| format!("cannot read the progress file {}", file.display()))?;
    if file.extension().is_some_and(|e| e == "ron") {
        of_window_state(&text, file)
    } else {
        Progress::from_json(&text, file)
    }
}

/// The progress in eframe's storage file `text` (read from `file`).
pub(crate) fn of_window_state(text: &str, file: &Path) -> Result<Progress> {
    let at = |e: ron::error::SpannedError| {
        anyhow!(
            "{}:{}:{}: {}",
            file.display(),
            e.span.start.line,
            e.span.start.col,
            e.code
        )
    };
    let stored: BTreeMap<String, String> = ron::from_str(text).map_err(at)?;
    let Some(app) = stored.get("app") else {
        return Ok(Record::default().export());
    };
    let saved: SavedLessons = ron::from_str(app)
        .with_context(|| format!("{}: the window's saved state does not read", file.display()))?;
    let record = Record {
        student: saved.student,
        done: saved.lessons,
        notes: saved.lesson_notes,
    };
    Ok(record.export())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Progress {
        let done = StepsDone::from([
            ("camera".into(), [0, 2].into()),
            ("empty".into(), [].into()),
        ]);
        let note = StepNote {
            done_at: Some("2026-12-05 17:04 UTC".into()),
            answer: Some(" 16".into()),
        };
        let notes = StepNotes::from([("camera".into(), [(2, note)].into())]);
        let record = Record {
            student: " Ada ".into(),
            done,
            notes,
        };
        record.export()
    }

    #[test]
    fn a_step_done_again_keeps_its_first_note() {
        let mut record = Record::default();
        record.mark_done("camera", 1, "then".into(), Some("4".into()));
        record.mark_done("camera", 1, "later".into(), Some("5".into()));
        let steps = &record.export().lessons[0].steps;
        assert_eq!(steps[0].done_at.as_deref(), Some("then"));
        assert_eq!(steps[0].answer.as_deref(), Some("4"));
        record.forget("camera");
        assert_eq!(record, Record::default());
    }

    #[test]
    fn the_windows_record_is_exported_as_it_was_given() {
        let progress = sample();
        assert_eq!(progress.student.as_deref(), Some("Ada"));
        assert_eq!(progress.lessons.len(), 1, "a lesson without steps done");
        let steps = &progress.lessons[0].steps;
        assert_eq!(steps[0].step, 1);
        assert_eq!(
            (steps[0].done_at.as_ref(), steps[0].answer.as_ref()),
            (None, None)
        );
        assert_eq!(steps[1].step, 3);
        assert_eq!(steps[1].answer.as_deref(), Some(" 16"));
        let path = Path::new("p.json");
        assert_eq!(
            Progress::from_json(&progress.to_json(), path).unwrap(),
            progress
        );
    }

    #[test]
    fn a_malformed_or_later_file_is_refused_at_its_place() {
        let path = Path::new("p.json");
        let error = |text: &str| Progress::from_json(text, path).unwrap_err().to_string();
        let typo = "{\"format-version\": 1,\n  \"lesons\": []}";
        assert!(
            error(typo).starts_with("p.json:2:3: unknown field `lesons`"),
            "{}",
            error(typo)
        );
        let kind = "{\"format-version\": 1, \"lessons\": [{\"lesson\": \"a\", \"steps\": [\n {\"step\": \"two\"}]}]}";
        let wrong_kind = error(kind);
        assert!(
            wrong_kind.starts_with("p.json:2:11: invalid type: string \"two\""),
            "{wrong_kind}"
        );
        assert!(error("{\"format-version\": 1,").starts_with("p.json:1:21: "));
        assert!(error("{\"lessons\": []}").contains("no format-version"));
        assert!(error("{\"format-version\": 2, \"lessons\": []}").contains("newer"));
    }

    #[test]
    fn the_windows_saved_state_gives_its_lessons() {
        let app = "(controls:(samples:3),lessons:{\"camera\":[1]},student:\"Ada\",\
                   lesson_notes:{\"camera\":{1:(answer:Some(\"4\"))}})";
        let stored = format!("{{\"app\":{app:?},\"window\":\"()\"}}");
        let progress = of_window_state(&stored, Path::new("app.ron")).unwrap();
        assert_eq!(progress.student.as_deref(), Some("Ada"));
        assert_eq!(progress.lessons[0].steps[0].step, 2);
        assert_eq!(progress.lessons[0].steps[0].answer.as_deref(), Some("4"));
        let broken = of_window_state("{\"app\"", Path::new("app.ron")).unwrap_err();
        assert!(broken.to_string().starts_with("app.ron:1:"), "{broken}");
    }
}
