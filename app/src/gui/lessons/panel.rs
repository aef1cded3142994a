//! The Lessons panel: the lesson picker with each lesson's progress, the
//! current step's text (emphasis, code and indented formulas set apart),
//! its hints on request, the question and answer, the check's state, the
//! buttons that move between steps or set one up, and the student's name
//! and Export progress... for the teacher.

use egui::text::LayoutJob;
use egui::{Color32, FontId, RichText, TextFormat, Ui};

use super::Lessons;
use crate::gui::panels::unfilled;
use crate::gui::platform::file_button;
use crate::lessons::Verdict;

/// The colour of what is done: the step numbers and the check's state.
const DONE: Color32 = Color32::from_rgb(90, 200, 110);

/// What the window asks of the app this frame.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Asked {
    /// Restore the step's scene, settings and layout.
    pub(crate) set_up: bool,
    /// Ask for a folder of lessons to add to the list.
    pub(crate) folder: bool,
    /// Ask where to save the progress (Export progress...).
    pub(crate) export: bool,
}

/// Draws the panel when it is open: docked at the right of the image, so
/// the image shrinks beside the step's text instead of hiding under it (a
/// floating window covered the right of the image, where a teacher's
/// lesson had put the object the step was about).
pub(crate) fn show(ui: &mut Ui, lessons: &mut Lessons) -> Asked {
    let mut asked = Asked::default();
    if !lessons.open {
        return asked;
    }
    egui::Panel::right("lessons")
        .resizable(true)
        .default_size(380.0)
        .size_range(240.0..=720.0)
        .frame(unfilled(egui::Frame::side_top_panel(ui.style())))
        .show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.heading("Lessons");
                ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                    if ui
                        .small_button("Close")
                        .on_hover_text("Close the Lessons panel (L)")
                        .clicked()
                    {
                        lessons.open = false;
                    }
                });
            });
            egui::ScrollArea::vertical().show(ui, |ui| body(ui, lessons, &mut asked));
        });
    asked
}

fn body(ui: &mut Ui, lessons: &mut Lessons, asked: &mut Asked) {
    if let Some(problem) = &lessons.problem {
        ui.colored_label(ui.visuals().error_fg_color, problem);
    }
    picker(ui, lessons);
    if file_button(ui, true, egui::Button::new("Lesson folder...").small())
        .on_hover_text("Add a folder of lessons to the list, by chapter")
        .clicked()
    {
        asked.folder = true;
    }
    // A copy: the buttons below change the panel's state while it is shown.
    let Some(lesson) = lessons.lesson().cloned() else {
        ui.label("No lesson.");
        return;
    };
    let done = lessons.done_steps();
    let steps = lesson.steps.len();
    let step_index = lessons.step();
    let Some(step) = lesson.steps.get(step_index) else {
        return;
    };
    if !lesson.summary.is_empty() {
        let summary: Vec<&str> = lesson.summary.split_whitespace().collect();
        ui.label(RichText::new(summary.join(" ")).weak());
    }
    ui.separator();
    ui.horizontal_wrapped(|ui| {
        for (i, each) in lesson.steps.iter().enumerate() {
            let mut text = RichText::new(format!(" {} ", i + 1));
            if done.contains(&i) {
                text = text.color(DONE).strong();
            }
            if ui
                .selectable_label(i == step_index, text)
                .on_hover_text(&each.title)
                .clicked()
            {
                lessons.go_to(i);
            }
        }
    });
    let optional = if step.required { "" } else { " (optional)" };
    ui.heading(format!(
        "Step {} of {steps}: {}{optional}",
        step_index + 1,
        step.title
    ));
    formatted(ui, &step.text);
    let (hints_total, question) = (step.hints.len(), step.check.value.question());
    let question = question.map(|(q, choices)| (q.to_string(), choices.to_vec()));
    for (i, hint) in lessons.hints().iter().enumerate() {
        ui.label(RichText::new(format!("Hint {}: {hint}", i + 1)).italics());
    }
    if lessons.hints().len() < hints_total && ui.button("Show a hint").clicked() {
        lessons.more_hint();
    }
    if let Some((question, choices)) = question {
        answer(ui, lessons, &question, &choices);
    }
    ui.separator();
    status(ui, lessons);
    ui.horizontal(|ui| {
        let at = step_index;
        if ui.add_enabled(at > 0, egui::Button::new("Back")).clicked() {
            lessons.go_to(at - 1);
        }
        if ui.button("Set up this step").clicked() {
            asked.set_up = true;
        }
        if ui
            .add_enabled(at + 1 < steps, egui::Button::new("Next"))
            .clicked()
        {
            lessons.go_to(at + 1);
        }
    });
    if done.len() == steps {
        ui.label(
            RichText::new(format!("Lesson complete: {steps} of {steps} steps done.")).strong(),
        );
    }
    ui.separator();
    ui.horizontal(|ui| {
        if ui
            .small_button("Reset progress")
            .on_hover_text("Forget the steps done in this lesson")
            .clicked()
        {
            lessons.reset_progress();
        }
        if ui
            .small_button("Export progress...")
            .on_hover_text("Save the steps done in every lesson, with your name, for your teacher")
            .clicked()
        {
            asked.export = true;
        }
    });
    ui.horizontal(|ui| {
        let label = ui.label("Your name:");
        ui.add(
            egui::TextEdit::singleline(&mut lessons.progress.student)
                .desired_width(160.0)
                .hint_text("for the exported progress"),
        )
        .labelled_by(label.id);
    });
}

/// The lesson picker: chapter, title and steps done.
fn picker(ui: &mut Ui, lessons: &mut Lessons) {
    let label = |lessons: &Lessons, i: usize| {
        let lesson = &lessons.lessons[i];
        let done = (lessons.progress.done.get(&lesson.name)).map_or(0, |d| d.len());
        format!(
            "{}. {} ({done}/{})",
            lesson.chapter,
            lesson.title,
            lesson.steps.len()
        )
    };
    let selected = if lessons.lessons.is_empty() {
        String::new()
    } else {
        label(lessons, lessons.current)
    };
    let mut chosen = None;
    egui::ComboBox::from_label("Lesson")
        .selected_text(selected)
        .width(290.0)
        .show_ui(ui, |ui| {
            for i in 0..lessons.lessons.len() {
                if ui
                    .selectable_label(i == lessons.current, label(lessons, i))
                    .clicked()
                {
                    chosen = Some(i);
                }
            }
        });
    if let Some(i) = chosen {
        lessons.choose(i);
    }
}

/// The question, with the choices to pick or a box to type in.
fn answer(ui: &mut Ui, lessons: &mut Lessons, question: &str, choices: &[String]) {
    let asked = ui.label(RichText::new(question).strong());
    ui.horizontal(|ui| {
        if choices.is_empty() {
            ui.add(
                egui::TextEdit::singleline(&mut lessons.answer)
                    .desired_width(120.0)
                    .hint_text("your answer"),
            )
            .labelled_by(asked.id);
        } else {
            for choice in choices {
                ui.radio_value(&mut lessons.answer, choice.clone(), choice);
            }
        }
        if ui.button("Check answer").clicked() {
            lessons.submit();
        }
    });
}

fn status(ui: &mut Ui, lessons: &Lessons) {
    let (text, colour) = match lessons.verdict() {
        _ if lessons.is_checking() && lessons.verdict().is_none() => {
            ("Checking...".to_string(), ui.visuals().weak_text_color())
        }
        Some(Verdict::Done(why)) => (format!("Done: {why}"), DONE),
        Some(Verdict::NotYet(why)) => (format!("Not yet: {why}"), ui.visuals().text_color()),
        Some(Verdict::Wrong(why)) => (format!("Wrong: {why}"), ui.visuals().error_fg_color),
        None => (
            "Not checked yet".to_string(),
            ui.visuals().weak_text_color(),
        ),
    };
    ui.label(RichText::new(text).color(colour));
}

/// A step's text: paragraphs, lines indented by four spaces as formulas in
/// a monospace font, `**strong**`, `*emphasis*` and `` `code` ``.
fn formatted(ui: &mut Ui, text: &str) {
    for paragraph in text.split("\n\n") {
        let lines: Vec<&str> = paragraph.lines().collect();
        if lines.is_empty() {
            continue;
        }
        if lines.iter().all(|l| l.starts_with("    ")) {
            let formula: Vec<&str> = lines.iter().map(|l| &l[4..]).collect();
            ui.label(RichText::new(formula.join("\n")).monospace().strong());
            continue;
        }
        ui.label(inline(ui, &lines.join(" ")));
    }
}

/// `text` with its inline marks turned into formats.
fn inline(ui: &Ui, text: &str) -> LayoutJob {
    let body = FontId::proportional(14.0);
    let colour = ui.visuals().text_color();
    let mut job = LayoutJob::default();
    let (mut strong, mut emphasis, mut code) = (false, false, false);
    let mut rest = text;
    while !rest.is_empty() {
        let next = rest.find(['*', '`']).unwrap_or(rest.len());
        if next > 0 {
            let format = TextFormat {
                font_id: if code {
                    FontId::monospace(13.0)
                } else {
                    body.clone()
                },
                color: if strong {
                    ui.visuals().strong_text_color()
                } else {
                    colour
                },
                italics: emphasis,
                ..TextFormat::default()
            };
            job.append(&rest[..next], 0.0, format);
        }
        rest = &rest[next..];
        if let Some(after) = rest.strip_prefix("**") {
            strong ^= true;
            rest = after;
        } else if let Some(after) = rest.strip_prefix('*') {
            emphasis ^= true;
            rest = after;
        } else if let Some(after) = rest.strip_prefix('`') {
            code ^= true;
            rest = after;
        }
    }
    job
}
