//! Lesson progress as a teacher reads it (`workbench lesson progress`): one
//! student's steps done as CSV or an HTML page, and a class's files merged
//! into one table, a row per student and a column per lesson. Answers are
//! shown as given: nothing is graded here.

use std::collections::BTreeSet;

use serde::Serialize;

use super::{FORMAT_VERSION, LessonProgress, Progress};
use crate::reports::bench_table::csv;
use crate::reports::lab::html;

/// One student's file in a class: the name shown and what it holds.
#[derive(Debug, Clone, Serialize)]
#[serde(rename_all = "kebab-case")]
pub(crate) struct Student {
    /// The file's `student`, or its file stem when it names none.
    pub(crate) student: String,
    /// The file it was read from, as given.
    pub(crate) file: String,
    pub(crate) lessons: Vec<LessonProgress>,
}

/// The headers of one student's table.
const STEP_HEADERS: [&str; 5] = ["student", "lesson", "step", "done-at", "answer"];

/// One row per (lesson, step done): the student, the lesson, the step from
/// 1, when and the answer (empty when not recorded).
fn step_rows(progress: &Progress, student: &str) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for lesson in &progress.lessons {
        for step in &lesson.steps {
            rows.push(vec![
                student.to_string(),
                lesson.lesson.clone(),
                step.step.to_string(),
                step.done_at.clone().unwrap_or_default(),
                step.answer.clone().unwrap_or_default(),
            ]);
        }
    }
    rows
}

/// One student's steps as CSV, one row per (lesson, step).
pub(crate) fn steps_csv(progress: &Progress, student: &str) -> String {
    let headers = STEP_HEADERS.map(String::from);
    csv(&headers, &step_rows(progress, student))
}

/// One student's steps as a self-contained HTML page.
pub(crate) fn steps_html(progress: &Progress, student: &str) -> String {
    let rows = step_rows(progress, student)
        .into_iter()
        .map(|cells| {
            let id = format!("{}/{}", cells[1], cells[2]);
            (id, cells.iter().map(|c| html::escape(c)).collect())
        })
        .collect::<Vec<_>>();
    let title = format!("Lesson progress: {student}");
    let table = html::table("progress", &STEP_HEADERS, &rows);
    html::page(
        &title,
        &[html::titled_section(
            "steps",
            "Steps done",
            &(NOTE.to_string() + &table),
        )],
    )
}

/// Said on every page: what the file is worth.
const NOTE: &str = "<p>A record of what the workbench saw, as the student's file says it: the \
                    file can be edited, so it is not a proof.</p>\n";

/// The lessons any student did a step of, by name.
fn lessons_of(class: &[Student]) -> Vec<String> {
    let names: BTreeSet<&String> = class
        .iter()
        .flat_map(|s| s.lessons.iter().map(|l| &l.lesson))
        .collect();
    names.into_iter().cloned().collect()
}

/// A class's table: a row per student, the steps done per lesson (`1 2 4`).
fn class_rows(class: &[Student], lessons: &[String]) -> Vec<Vec<String>> {
    class
        .iter()
        .map(|s| {
            let mut row = vec![s.student.clone()];
            row.extend(lessons.iter().map(|name| {
                let lesson = s.lessons.iter().find(|l| &l.lesson == name);
                let steps = lesson.map(|l| l.steps.iter().map(|s| s.step.to_string()));
                steps
                    .map(|s| s.collect::<Vec<_>>().join(" "))
                    .unwrap_or_default()
            }));
            row
        })
        .collect()
}

/// The class as CSV: `student`, then a column per lesson.
pub(crate) fn class_csv(class: &[Student]) -> String {
    let lessons = lessons_of(class);
    let headers: Vec<String> = std::iter::once("student".to_string())
        .chain(lessons.iter().cloned())
        .collect();
    csv(&headers, &class_rows(class, &lessons))
}

/// The class as a self-contained HTML page.
pub(crate) fn class_html(class: &[Student]) -> String {
    let lessons = lessons_of(class);
    let headers: Vec<&str> = std::iter::once("student")
        .chain(lessons.iter().map(String::as_str))
        .collect();
    let rows = class_rows(class, &lessons)
        .into_iter()
        .map(|cells| {
            (
                cells[0].clone(),
                cells.iter().map(|c| html::escape(c)).collect(),
            )
        })
        .collect::<Vec<_>>();
    let table = html::table("class", &headers, &rows);
    let intro = format!("{NOTE}<p>The steps done in each lesson, counted from 1.</p>\n");
    html::page(
        "Lesson progress of a class",
        &[html::titled_section(
            "class",
            "Steps done",
            &(intro + &table),
        )],
    )
}

/// The class as JSON: every student's file, named.
pub(crate) fn class_json(class: &[Student]) -> String {
    let value = serde_json::json!({
        "format-version": FORMAT_VERSION,
        "students": class,
    });
    serde_json::to_string_pretty(&value).expect("a class serializes") + "\n"
}
