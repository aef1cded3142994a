//! The Lessons panel's state: the lessons offered (the bundled ones and any
//! opened from a file), the current lesson and step, the hints shown, the
//! answer typed, the check's verdict (evaluated on a thread of its own
//! whenever what it looks at changes) and the steps done, which persist.

mod panel;

use std::collections::BTreeSet;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::sync::mpsc::{Receiver, channel};
use web_time::SystemTime;

use crate::gui::platform::target;
use crate::lessons::progress::Record;
use crate::lessons::state::LessonState;
use crate::lessons::{self, Lesson, Verdict};
use crate::reports::lab::machine::utc_date;

pub(crate) use panel::show;

/// The Lessons panel.
pub struct Lessons {
    pub open: bool,
    lessons: Vec<Lesson>,
    /// A bundled lesson that did not read (a build of a broken file).
    pub(crate) problem: Option<String>,
    current: usize,
    step: usize,
    hints_shown: usize,
    /// The answer being typed or picked.
    pub answer: String,
    /// The answer the student submitted for the current step.
    submitted: Option<String>,
    verdict: Option<Verdict>,
    /// What the verdict was evaluated on, to evaluate again only on change.
    evaluated: Option<u64>,
    pending: Option<(u64, Receiver<Verdict>)>,
    /// The student's name and steps done: what persists and is exported.
    pub progress: Record,
}

impl Default for Lessons {
    fn default() -> Self {
        let (lessons, problem) = match lessons::bundled::all() {
            Ok(lessons) => (lessons, None),
            Err(e) => (Vec::new(), Some(e.to_string())),
        };
        Lessons {
            open: false,
            lessons,
            problem,
            current: 0,
            step: 0,
            hints_shown: 0,
            answer: String::new(),
            submitted: None,
            verdict: None,
            evaluated: None,
            pending: None,
            progress: Record::default(),
        }
    }
}

impl Lessons {
    /// The lesson shown.
    pub fn lesson(&self) -> Option<&Lesson> {
        self.lessons.get(self.current)
    }

    /// The step shown, from 0.
    pub fn step(&self) -> usize {
        self.step
    }

    /// The current check's verdict, once evaluated.
    pub fn verdict(&self) -> Option<&Verdict> {
        self.verdict.as_ref()
    }

    /// Adds `lesson` (a teacher's file) and makes it current; a lesson of
    /// the same name is replaced.
    pub(crate) fn add(&mut self, lesson: Lesson) {
        let at = match self.lessons.iter().position(|l| l.name == lesson.name) {
            Some(i) => {
                self.lessons[i] = lesson;
                i
            }
            None => {
                self.lessons.push(lesson);
                self.lessons.len() - 1
            }
        };
        self.choose(at);
    }

    /// Adds a folder's lessons to the list (one of the same name is
    /// replaced), in chapter order after the bundled ones of the same
    /// chapter, and shows the folder's first: the teacher's class opens on
    /// the teacher's lesson. A folder with none keeps the lesson shown.
    pub(crate) fn add_folder(&mut self, lessons: Vec<Lesson>) {
        let shown = self.lesson().map(|l| l.name.clone());
        let added: Vec<String> = lessons.iter().map(|l| l.name.clone()).collect();
        for lesson in lessons {
            match self.lessons.iter().position(|l| l.name == lesson.name) {
                Some(i) => self.lessons[i] = lesson,
                None => self.lessons.push(lesson),
            }
        }
        lessons::folder::in_chapter_order(&mut self.lessons);
        let position = |name: &String| self.lessons.iter().position(|l| &l.name == name);
        let first_added = self.lessons.iter().position(|l| added.contains(&l.name));
        let at = first_added.or_else(|| shown.as_ref().and_then(position));
        self.choose(at.unwrap_or(0));
    }

    /// The names of the lessons offered, in the list's order.
    pub fn names(&self) -> Vec<&str> {
        self.lessons.iter().map(|l| l.name.as_str()).collect()
    }

    /// Makes lesson `index` current, at its first step not done.
    pub(crate) fn choose(&mut self, index: usize) {
        if index >= self.lessons.len() {
            return;
        }
        self.current = index;
        let done = self.done_steps();
        let steps = self.lessons[index].steps.len();
        let first_open = (0..steps).find(|i| !done.contains(i)).unwrap_or(0);
        self.go_to(first_open);
    }

    /// Shows step `step` of the current lesson, its hints hidden, no answer.
    pub(crate) fn go_to(&mut self, step: usize) {
        let steps = self.lesson().map_or(0, |l| l.steps.len());
        self.step = step.min(steps.saturating_sub(1));
        self.hints_shown = 0;
        self.answer.clear();
        self.submitted = None;
        self.verdict = None;
        self.evaluated = None;
        self.pending = None;
    }

    /// The steps of the current lesson done so far.
    pub fn done_steps(&self) -> BTreeSet<usize> {
        self.lesson()
            .and_then(|l| self.progress.done.get(&l.name))
            .cloned()
            .unwrap_or_default()
    }

    /// Forgets every step done of the current lesson.
    pub(crate) fn reset_progress(&mut self) {
        if let Some(name) = self.lesson().map(|l| l.name.clone()) {
            self.progress.forget(&name);
        }
        self.go_to(0);
    }

    /// Checks the answer typed or picked.
    pub(crate) fn submit(&mut self) {
        let answer = self.answer.trim();
        self.submitted = (!answer.is_empty()).then(|| answer.to_string());
    }

    /// Shows one more hint.
    pub(crate) fn more_hint(&mut self) {
        self.hints_shown += 1;
    }

    /// Evaluates the current step's check when what it looks at changed
    /// (`looked_at` fingerprints the window's sides, pixel and layout;
    /// `state` builds what the check sees), on a thread, since a
    /// measurement renders. Takes a finished verdict, marking the step
    /// done with the time and the answer submitted: a done step stays
    /// done. `wake` asks for a frame when the verdict arrives.
    pub(crate) fn keep_checking(
        &mut self,
        looked_at: u64,
        state: impl FnOnce() -> Option<LessonState>,
        wake: impl Fn() + Send + 'static,
    ) {
        if let Some((key, receiver)) = &self.pending
            && let Ok(verdict) = receiver.try_recv()
        {
            self.evaluated = Some(*key);
            if verdict.is_done()
                && let Some(name) = self.lesson().map(|l| l.name.clone())
            {
                let (at, answer) = (utc_date(SystemTime::now()), self.submitted.clone());
                self.progress.mark_done(&name, self.step, at, answer);
            }
            self.verdict = Some(verdict);
            self.pending = None;
        }
        let Some(lesson) = self.lesson() else {
            return;
        };
        let Some(step) = lesson.steps.get(self.step) else {
            return;
        };
        let mut hasher = DefaultHasher::new();
        (looked_at, &lesson.name, self.step, &self.submitted).hash(&mut hasher);
        let key = hasher.finish();
        if self.evaluated == Some(key) || self.pending.is_some() {
            return;
        }
        let Some(mut state) = state() else {
            return;
        };
        state.answer = self.submitted.clone();
        let check = step.check.value.clone();
        let (sender, receiver) = channel();
        // Without a thread the verdict never comes: the step stays unchecked.
        let _ = target::spawn("lesson-check", move || {
            let _ = sender.send(lessons::evaluate(&check, &state));
            wake();
        });
        self.pending = Some((key, receiver));
    }

    /// Whether a verdict is being worked out.
    pub fn is_checking(&self) -> bool {
        self.pending.is_some()
    }

    /// The hints shown so far.
    fn hints(&self) -> &[String] {
        let hints = self
            .lesson()
            .and_then(|l| l.steps.get(self.step))
            .map_or(&[][..], |s| &s.hints[..]);
        &hints[..self.hints_shown.min(hints.len())]
    }
}
