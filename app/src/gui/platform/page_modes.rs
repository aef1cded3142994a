//! What a web page can do instead of opening the window, asked for by its
//! query: `?replay` walks every bundled lesson's steps in the browser, as
//! `workbench lesson check` does on the desktop, for a script (and a
//! teacher) to see that each step passes with the web's maths library.

use std::sync::mpsc;

use wasm_bindgen::prelude::*;

use crate::lessons::{bundled, replay};

use super::target;

/// The page mode `query` asks for, if any.
pub fn asked(query: &str) -> Option<PageMode> {
    match query {
        "?replay" => Some(PageMode::Replay),
        _ => None,
    }
}

/// A page that shows words instead of the window.
#[derive(Debug, Clone, Copy)]
pub enum PageMode {
    /// Every bundled lesson replayed, step by step.
    Replay,
}

impl PageMode {
    /// Runs the mode on the page's workers, saying its lines in the
    /// page's `#status` as they come and, at the end, `passed` or
    /// `failed: N steps` in `<body data-replay>`.
    pub async fn run(self) -> Result<(), JsValue> {
        let (tx, rx) = mpsc::channel();
        target::spawn("lesson replay", move || replay_all(&tx))
            .map_err(|e| JsValue::from_str(&e.to_string()))?;
        let mut said = String::new();
        loop {
            let mut finished = None;
            for line in rx.try_iter() {
                match line {
                    Said::Line(line) => said.push_str(&format!("{line}\n")),
                    Said::Finished(failures) => finished = Some(failures),
                }
            }
            show(&said, None);
            if let Some(failures) = finished {
                let verdict = match failures {
                    0 => "passed".to_string(),
                    n => format!("failed: {n} steps"),
                };
                show(&said, Some(&verdict));
                return Ok(());
            }
            pause(100).await?;
        }
    }
}

/// What the replay says as it goes.
enum Said {
    Line(String),
    /// How many steps failed (a lesson that cannot be walked counts one).
    Finished(usize),
}

fn replay_all(tx: &mpsc::Sender<Said>) {
    let say = |line: String| {
        let _ = tx.send(Said::Line(line));
    };
    let lessons = match bundled::all() {
        Ok(lessons) => lessons,
        Err(e) => {
            say(format!("the bundled lessons do not read: {e}"));
            let _ = tx.send(Said::Finished(1));
            return;
        }
    };
    let mut failures = 0;
    for lesson in &lessons {
        say(format!(
            "{} (chapter {}): {}",
            lesson.name, lesson.chapter, lesson.title
        ));
        let count = lesson.steps.len();
        let walked = replay::replay(lesson, &mut |i, step| match step.failure() {
            None => say(format!("  step {}/{count} {}: pass", i + 1, step.title)),
            Some(why) => say(format!(
                "  step {}/{count} {}: FAIL: {why}",
                i + 1,
                step.title
            )),
        });
        match walked {
            Ok(steps) => failures += steps.iter().filter(|s| s.failure().is_some()).count(),
            Err(e) => {
                say(format!("  cannot be walked: {e:#}"));
                failures += 1;
            }
        }
    }
    say(format!(
        "{} lessons replayed, {failures} steps failed",
        lessons.len()
    ));
    let _ = tx.send(Said::Finished(failures));
}

/// Writes `text` into the page's `#status` (shown, left-aligned), and the
/// verdict into `<body data-replay>` once there is one.
fn show(text: &str, verdict: Option<&str>) {
    let Some(document) = web_sys::window().and_then(|w| w.document()) else {
        return;
    };
    if let Some(status) = document.get_element_by_id("status") {
        status.set_text_content(Some(text));
        let _ = status.remove_attribute("hidden");
        let _ = status.set_attribute(
            "style",
            "white-space: pre; text-align: left; align-items: flex-start; overflow: auto",
        );
    }
    if let (Some(body), Some(verdict)) = (document.body(), verdict) {
        let _ = body.set_attribute("data-replay", verdict);
    }
}

/// Waits `ms` milliseconds without holding the page's thread.
async fn pause(ms: i32) -> Result<(), JsValue> {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        if let Some(window) = web_sys::window() {
            let _ = window.set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, ms);
        }
    });
    wasm_bindgen_futures::JsFuture::from(promise)
        .await
        .map(drop)
}
