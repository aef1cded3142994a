//! `workbench lesson list`, `check`, `new` and `explain`: lessons tested like
//! code, one at a time or a folder at once. `check` reads each lesson, opens its scene and replays its steps,
//! one line per step, and fails when any step's check already holds before
//! the student acts or does not hold after the step's solution. `explain`
//! says what a step starts from and where its tree figures hold.
//! `progress` turns a student's record into a table, or a class's into one.

use std::io::Write as _;
use std::path::Path;

use anyhow::{Context as _, Result, anyhow, bail};

use crate::cli::{
    ExplainArgs, LessonArgs, LessonCommand, MetricsFormat, ProgressArgs, ProgressFormat,
};
use crate::lessons::format::LessonErrors;
use crate::lessons::progress::table as tables;
use crate::lessons::replay::replay;
use crate::lessons::{Lesson, bundled};
use crate::lessons::{explain, folder, progress};

pub fn run(args: &LessonArgs) -> Result<()> {
    match &args.command {
        LessonCommand::List { format, folder } => list(*format, folder.as_deref()),
        LessonCommand::Check { lessons, format } => check(lessons, *format),
        LessonCommand::New { name } => new(name),
        LessonCommand::Explain(args) => explain(args),
        LessonCommand::Progress(args) => progress(args),
    }
}

/// One student's progress, or (`--merge`) a class's, written in the
/// format asked or that `-o`'s extension names.
fn progress(args: &ProgressArgs) -> Result<()> {
    let format =
        args.format
            .unwrap_or_else(|| match args.output.as_deref().and_then(Path::extension) {
                Some(e) if e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm") => {
                    ProgressFormat::Html
                }
                Some(e) if e.eq_ignore_ascii_case("csv") => ProgressFormat::Csv,
                _ => ProgressFormat::Json,
            });
    let text = if args.merge.is_empty() {
        let file = match &args.file {
            Some(file) => file.clone(),
            None => progress::window_state_file()
                .filter(|f| f.exists())
                .ok_or_else(|| {
                    anyhow!(
                        "no saved window state{}: the window has not been closed on this \
                         account yet; give an exported progress file instead",
                        progress::window_state_file()
                            .map_or(String::new(), |f| format!(" at {}", f.display()))
                    )
                })?,
        };
        let record = progress::read(&file)?;
        let student = record.student_or("").to_string();
        match format {
            ProgressFormat::Json => record.to_json(),
            ProgressFormat::Csv => tables::steps_csv(&record, &student),
            ProgressFormat::Html => tables::steps_html(&record, &student),
        }
    } else {
        let class = (args.merge.iter())
            .map(|file| {
                let record = progress::read(file)?;
                let stem = file.file_stem().unwrap_or_default().to_string_lossy();
                Ok(tables::Student {
                    student: record.student_or(&stem).to_string(),
                    file: file.display().to_string(),
                    lessons: record.lessons,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        match format {
            ProgressFormat::Json => tables::class_json(&class),
            ProgressFormat::Csv => tables::class_csv(&class),
            ProgressFormat::Html => tables::class_html(&class),
        }
    };
    match &args.output {
        Some(path) => {
            crate::image_file::write_atomically(path, |file| Ok(file.write_all(text.as_bytes())?))
                .with_context(|| format!("cannot write {}", path.display()))?;
            eprintln!("wrote {}", path.display());
        }
        None => print!("{text}"),
    }
    Ok(())
}

fn explain(args: &ExplainArgs) -> Result<()> {
    let lesson = bundled::read_name_or_file(Path::new(&args.lesson))?;
    let text = if args.find.is_empty() {
        let pixel = args.pixel.as_deref().map(|p| (p[0], p[1]));
        explain::explain(&lesson, args.step, pixel)?
    } else {
        let conditions = (args.find.iter())
            .map(|text| explain::Condition::parse(text).map_err(|e| anyhow!("--find {e}")))
            .collect::<Result<Vec<_>>>()?;
        explain::find(&lesson, args.step, &conditions)?
    };
    print!("{text}");
    Ok(())
}

/// The bundled lessons, or a folder's in the panel's order; a file of the
/// folder that does not read is said on stderr and fails the command once
/// the others are listed.
fn list(format: MetricsFormat, folder: Option<&Path>) -> Result<()> {
    let Some(dir) = folder else {
        return print_list(format, &bundled::all()?);
    };
    let mut lessons = Vec::new();
    let mut broken = 0;
    for (_, lesson) in folder::read(dir)? {
        match lesson {
            Ok(lesson) => lessons.push(lesson),
            Err(LessonErrors(errors)) => {
                broken += 1;
                errors.iter().for_each(|e| eprintln!("error: {e}"));
            }
        }
    }
    folder::in_chapter_order(&mut lessons);
    print_list(format, &lessons)?;
    if broken > 0 {
        bail!("{broken} lesson file(s) in {} do not read", dir.display());
    }
    Ok(())
}

fn print_list(format: MetricsFormat, lessons: &[Lesson]) -> Result<()> {
    match format {
        MetricsFormat::Text => {
            let width = lessons.iter().map(|l| l.name.len()).max().unwrap_or(0);
            for lesson in lessons {
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
                        "file": l.file,
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

fn check(names: &[String], format: MetricsFormat) -> Result<()> {
    let lessons: Vec<(String, Result<Lesson>)> = if names.is_empty() {
        (bundled::all()?.into_iter())
            .map(|l| (l.name.clone(), Ok(l)))
            .collect()
    } else {
        let mut lessons = Vec::new();
        for name in names {
            match Path::new(name) {
                dir if dir.is_dir() => lessons.extend(
                    (folder::read(dir)?.into_iter())
                        .map(|(path, l)| (path.display().to_string(), l.map_err(Into::into))),
                ),
                file_or_name => {
                    lessons.push((name.clone(), bundled::read_name_or_file(file_or_name)))
                }
            }
        }
        lessons
    };
    let print = format == MetricsFormat::Text;
    let (mut steps, mut failures, mut report) = (0, 0, Vec::new());
    for (asked, lesson) in lessons {
        let checked = check_one(&asked, lesson, print);
        steps += checked.steps;
        failures += checked.failures;
        report.push(checked.json);
    }
    if !print {
        let all = serde_json::json!({ "lessons": report, "steps": steps, "failures": failures });
        println!("{}", serde_json::to_string_pretty(&all)?);
    }
    if failures > 0 {
        bail!("{failures} failure(s) in the lessons checked");
    }
    if print {
        println!("all {steps} steps pass");
    }
    Ok(())
}

/// One lesson checked: its steps and failures counted, said as JSON.
struct Checked {
    steps: usize,
    failures: usize,
    json: serde_json::Value,
}

/// Replays `lesson` (asked for as `asked`), printing its lines when
/// `print`; a lesson that does not read or cannot be walked is one
/// failure, each of its mistakes said.
fn check_one(asked: &str, lesson: Result<Lesson>, print: bool) -> Checked {
    let lesson = match lesson {
        Ok(lesson) => lesson,
        Err(e) => {
            if print {
                print_error("", &e);
            }
            let json = serde_json::json!({ "lesson": asked, "errors": errors_json(&e) });
            return Checked {
                steps: 0,
                failures: 1,
                json,
            };
        }
    };
    if print {
        println!(
            "{} (chapter {}): {}",
            lesson.name, lesson.chapter, lesson.title
        );
    }
    let count = lesson.steps.len();
    let walked = replay(&lesson, &mut |i, step| {
        if print {
            match step.failure() {
                None => println!("  step {}/{count} {}: pass", i + 1, step.title),
                Some(why) => println!("  step {}/{count} {}: FAIL: {why}", i + 1, step.title),
            }
        }
    });
    let (replays, errors) = match walked {
        Ok(replays) => (replays, Vec::new()),
        Err(e) => {
            if print {
                print_error("  ", &e);
            }
            (Vec::new(), errors_json(&e))
        }
    };
    let failed = replays.iter().filter(|r| r.failure().is_some()).count();
    let steps_json: Vec<_> = (replays.iter().enumerate())
        .map(|(i, r)| serde_json::json!({ "step": i + 1, "title": r.title, "pass": r.failure().is_none(), "failure": r.failure() }))
        .collect();
    let json = serde_json::json!({
        "lesson": asked, "name": lesson.name, "file": lesson.file, "chapter": lesson.chapter,
        "title": lesson.title, "steps": steps_json, "errors": errors,
    });
    Checked {
        steps: replays.len(),
        failures: failed + usize::from(!errors.is_empty()),
        json,
    }
}

/// An error's mistakes as JSON: file, line and column (null for the whole
/// file) and the message; any other error as its message alone.
fn errors_json(error: &anyhow::Error) -> Vec<serde_json::Value> {
    match error.downcast_ref::<LessonErrors>() {
        Some(LessonErrors(errors)) => (errors.iter())
            .map(|e| {
                let place = (e.line > 0).then_some((e.line, e.column));
                serde_json::json!({
                    "file": e.file, "line": place.map(|p| p.0), "column": place.map(|p| p.1),
                    "message": e.message,
                })
            })
            .collect(),
        None => vec![serde_json::json!({ "message": format!("{error:#}") })],
    }
}

/// Writes a starting lesson and says what to do next.
fn new(name: &str) -> Result<()> {
    let path = crate::lessons::new::write(name)?;
    let path = path.display();
    println!("wrote {path}: a two-step lesson that passes its check; edit it, then");
    println!("  workbench lesson check {path}");
    println!("  workbench lesson explain {path} --step N");
    println!("  workbench --lesson {path}");
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
