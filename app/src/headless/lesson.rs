//! `workbench lesson list`, `check` and `explain`: lessons tested like
//! code. `check` reads each lesson, opens its scene and replays its steps,
//! one line per step, and fails when any step's check already holds before
//! the student acts or does not hold after the step's solution. `explain`
//! says what a step starts from and where its tree figures hold.

use std::path::Path;

use anyhow::{Result, anyhow, bail};

use crate::cli::{ExplainArgs, LessonArgs, LessonCommand, MetricsFormat};
use crate::lessons::explain;
use crate::lessons::format::read_lesson_file;
use crate::lessons::replay::replay;
use crate::lessons::{Lesson, LessonErrors, bundled};

pub fn run(args: &LessonArgs) -> Result<()> {
    match &args.command {
        LessonCommand::List { format } => list(*format),
        LessonCommand::Check { lessons } => check(lessons),
        LessonCommand::Explain(args) => explain(args),
    }
}

fn explain(args: &ExplainArgs) -> Result<()> {
    let lesson = read(&args.lesson)?;
    let text = if args.find.is_empty() {
        let pixel = args.pixel.as_deref().map(|p| (p[0], p[1]));
        explain::explain(&lesson, args.step, pixel)?
    } else {
        explain::find(&lesson, args.step, &args.find)?
    };
    print!("{text}");
    Ok(())
}

fn list(format: MetricsFormat) -> Result<()> {
    let lessons = bundled::all()?;
    match format {
        MetricsFormat::Text => {
            let width = lessons.iter().map(|l| l.name.len()).max().unwrap_or(0);
            for lesson in &lessons {
                println!(
                    "{:>2}  {:width$}  {} ({} steps)",
                    lesson.chapter,
                    lesson.name,
                    lesson.title,
                    lesson.steps.len()
                );
            }
        }
        MetricsFormat::Json => {
            let rows: Vec<_> = lessons
                .iter()
                .map(|l| {
                    serde_json::json!({
                        "name": l.name,
                        "chapter": l.chapter,
                        "title": l.title,
                        "summary": l.summary,
                        "steps": l.steps.iter().map(|s| serde_json::json!({
                            "title": s.title,
                            "required": s.required,
                        })).collect::<Vec<_>>(),
                    })
                })
                .collect();
            println!("{}", serde_json::to_string_pretty(&rows)?);
        }
    }
    Ok(())
}

/// A bundled lesson by name, or a lesson file: a `.toml` name or a path
/// that exists is a file.
fn read(name_or_file: &str) -> Result<Lesson> {
    let path = Path::new(name_or_file);
    if path.extension().is_some_and(|e| e == "toml") || path.exists() {
        return Ok(read_lesson_file(path)?);
    }
    let lesson = bundled::find(name_or_file).ok_or_else(|| {
        anyhow!(
            "no bundled lesson called `{name_or_file}` and no such file; lessons: {}",
            bundled::names().join(", ")
        )
    })?;
    Ok(crate::lessons::format::read_bundled(lesson)?)
}

fn check(names: &[String]) -> Result<()> {
    let lessons: Vec<Result<Lesson>> = if names.is_empty() {
        bundled::all()?.into_iter().map(Ok).collect()
    } else {
        names.iter().map(|n| read(n)).collect()
    };
    let (mut steps, mut failures) = (0, 0);
    for lesson in lessons {
        let lesson = match lesson {
            Ok(lesson) => lesson,
            Err(e) => {
                print_error("", &e);
                failures += 1;
                continue;
            }
        };
        println!(
            "{} (chapter {}): {}",
            lesson.name, lesson.chapter, lesson.title
        );
        let count = lesson.steps.len();
        let walked = replay(&lesson, &mut |i, step| match step.failure() {
            None => println!("  step {}/{count} {}: pass", i + 1, step.title),
            Some(why) => println!("  step {}/{count} {}: FAIL: {why}", i + 1, step.title),
        });
        match walked {
            Ok(replays) => {
                steps += replays.len();
                failures += replays.iter().filter(|r| r.failure().is_some()).count();
            }
            Err(e) => {
                print_error("  ", &e);
                failures += 1;
            }
        }
    }
    if failures > 0 {
        bail!("{failures} failure(s) in the lessons checked");
    }
    println!("all {steps} steps pass");
    Ok(())
}

/// An error on its own lines, each of a lesson's mistakes on one.
fn print_error(indent: &str, error: &anyhow::Error) {
    match error.downcast_ref::<LessonErrors>() {
        Some(LessonErrors(errors)) => {
            for error in errors {
                println!("{indent}error: {error}");
            }
        }
        None => println!("{indent}error: {error:#}"),
    }
}
