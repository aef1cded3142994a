//! A side's edits of its scene: what undo and redo apply (each edit with
//! the inverse its application returned), whether the scene differs from
//! the file, and the edits as `--set` lines for the command line.

use std::time::Duration;

use web_time::Instant;

use tracer::scene::Scene;
use tracer::scene::edit::Edit;

use crate::gui::platform::clock::Clock;

/// Changes of one field closer together than this are one step of undo: a
/// slider's drag, a colour picked in its popup.
const MERGE_WITHIN: Duration = Duration::from_millis(600);

/// One step: the edit as applied last, and what undoes the whole step.
#[derive(Debug, Clone)]
struct UndoStep {
    edit: Edit,
    inverse: Edit,
    /// The target and field ("object 5 ior"), for merging.
    slot: String,
    at: Instant,
    /// Unique within the history: names the state this step leads to.
    id: u64,
}

/// Undo and redo of one side's scene.
#[derive(Debug, Clone)]
pub(crate) struct History {
    done: Vec<UndoStep>,
    undone: Vec<UndoStep>,
    /// The state on disk ([`History::state`]); `None` when none of the
    /// states undo and redo reach is.
    saved: Option<u64>,
    /// The last step id given out.
    last_id: u64,
    /// Times how close together two changes of one field come.
    clock: Clock,
}

/// What two edits of one field in a row amount to: the later value, but
/// for translations, which add up.
fn joined(first: &Edit, then: Edit) -> Edit {
    use tracer::scene::edit::{GeometryChange, ObjectChange};
    match (first, &then) {
        (
            Edit::Object {
                change: ObjectChange::Geometry(GeometryChange::Translate(a)),
                ..
            },
            Edit::Object {
                index,
                change: ObjectChange::Geometry(GeometryChange::Translate(b)),
            },
        ) => Edit::Object {
            index: *index,
            change: ObjectChange::Geometry(GeometryChange::Translate(*a + *b)),
        },
        _ => then,
    }
}

/// The target and field of an edit: its `--set` text without the values.
fn slot(edit: &Edit) -> String {
    let text = edit.to_string();
    let words: Vec<&str> = text.split_whitespace().collect();
    let keep = if words.first() == Some(&"camera") {
        2
    } else {
        3
    };
    words[..keep.min(words.len())].join(" ")
}

impl History {
    /// A freshly opened scene: no edits, as on disk; `clock` times the
    /// merging of changes into one step.
    pub(crate) fn new(clock: Clock) -> Self {
        Self {
            done: Vec::new(),
            undone: Vec::new(),
            saved: Some(0),
            last_id: 0,
            clock,
        }
    }

    /// Records `edit`, applied, with its `inverse`. A change of the same
    /// field right after the last one joins its step.
    pub(crate) fn push(&mut self, edit: Edit, inverse: Edit) {
        let slot = slot(&edit);
        let now = self.clock.now();
        self.undone.clear();
        let saved_here = self.saved == Some(self.state());
        if let Some(last) = self.done.last_mut()
            && last.slot == slot
            && now - last.at < MERGE_WITHIN
            && !saved_here
        {
            last.edit = joined(&last.edit, edit);
            last.at = now;
            return;
        }
        self.last_id += 1;
        self.done.push(UndoStep {
            edit,
            inverse,
            slot,
            at: now,
            id: self.last_id,
        });
    }

    /// Names the scene as it stands: equal states, equal scenes (0: as
    /// opened).
    pub(crate) fn state(&self) -> u64 {
        self.done.last().map_or(0, |s| s.id)
    }

    /// The edit that undoes the last step, taken off it (apply it, then
    /// [`History::undone`] with what that returns).
    pub(crate) fn undo(&mut self) -> Option<Edit> {
        let step = self.done.pop()?;
        let inverse = step.inverse.clone();
        self.undone.push(step);
        Some(inverse)
    }

    /// The edit that redoes the last undone step.
    pub(crate) fn redo(&mut self) -> Option<Edit> {
        let step = self.undone.pop()?;
        let edit = step.edit.clone();
        self.done.push(step);
        Some(edit)
    }

    /// Puts back a step [`History::undo`] or [`History::redo`] took when
    /// its edit was refused, so nothing is lost.
    pub(crate) fn refused(&mut self, undoing: bool) {
        if undoing {
            if let Some(step) = self.undone.pop() {
                self.done.push(step);
            }
        } else if let Some(step) = self.done.pop() {
            self.undone.push(step);
        }
    }

    pub(crate) fn can_undo(&self) -> bool {
        !self.done.is_empty()
    }

    pub(crate) fn can_redo(&self) -> bool {
        !self.undone.is_empty()
    }

    /// Whether the scene differs from the file it came from.
    pub(crate) fn is_modified(&self) -> bool {
        self.saved != Some(self.state())
    }

    /// The scene in `state` was written to disk (saving takes a dialog:
    /// the user may edit on meanwhile).
    pub(crate) fn mark_saved(&mut self, state: u64) {
        self.saved = Some(state);
    }

    /// A freshly opened scene: no edits, as on disk.
    pub(crate) fn reset(&mut self) {
        *self = History::new(self.clock.clone());
    }

    /// The edits made, in order, as `--set` arguments for the command line.
    pub(crate) fn set_lines(&self) -> String {
        self.texts()
            .iter()
            .map(|text| format!("--set '{text}'"))
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// The edits made, in order, in `--set`'s words (`object 5 ior 1.33`).
    pub(crate) fn texts(&self) -> Vec<String> {
        self.done.iter().map(|s| s.edit.to_string()).collect()
    }

    /// The edits made, described against `scene` ("sphere #5 ior 1.33"),
    /// for the labels of compare mode.
    pub(crate) fn describe(&self, scene: &Scene) -> Vec<String> {
        self.done.iter().map(|s| s.edit.describe(scene)).collect()
    }

    /// Steps that can be undone.
    pub(crate) fn len(&self) -> usize {
        self.done.len()
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.done.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use tracer::scene::edit::{Edit, MaterialField, ObjectChange};

    use super::*;

    fn ior(index: usize, value: f32) -> Edit {
        Edit::Object {
            index,
            change: ObjectChange::Material(MaterialField::Ior(value)),
        }
    }

    #[test]
    fn a_drag_of_one_field_is_one_step_and_saves_count() {
        let mut history = History::new(Clock::stopped());
        assert!(!history.is_modified());
        history.push(ior(5, 1.4), ior(5, 1.5));
        history.push(ior(5, 1.33), ior(5, 1.4));
        assert_eq!(history.len(), 1, "one field, moments apart: one step");
        history.push(ior(4, 1.2), ior(4, 1.5));
        assert_eq!(history.len(), 2, "another object: another step");
        assert!(history.is_modified());
        assert_eq!(
            history.set_lines(),
            "--set 'object 5 ior 1.33' --set 'object 4 ior 1.2'"
        );
        assert_eq!(history.undo(), Some(ior(4, 1.5)));
        assert_eq!(history.undo(), Some(ior(5, 1.5)), "back past the drag");
        assert_eq!(history.undo(), None);
        assert!(!history.is_modified(), "as on disk again");
        assert_eq!(history.redo(), Some(ior(5, 1.33)));
        history.mark_saved(history.state());
        assert!(!history.is_modified());
        history.push(ior(5, 1.2), ior(5, 1.33));
        assert_eq!(history.len(), 2, "a save ends the step");
        assert!(history.is_modified() && !history.can_redo());
        history.undo();
        assert!(!history.is_modified(), "back to the saved state");
        history.undo();
        history.push(ior(4, 1.1), ior(4, 1.5));
        assert_eq!(history.len(), 1);
        assert!(
            history.is_modified(),
            "as many steps as saved, another scene"
        );
    }

    #[test]
    fn a_pause_between_changes_of_one_field_makes_two_steps() {
        let clock = Clock::stopped();
        let mut history = History::new(clock.clone());
        history.push(ior(5, 1.4), ior(5, 1.5));
        clock.advance(MERGE_WITHIN - Duration::from_millis(1));
        history.push(ior(5, 1.33), ior(5, 1.4));
        assert_eq!(history.len(), 1, "just within: one step");
        clock.advance(MERGE_WITHIN);
        history.push(ior(5, 1.2), ior(5, 1.33));
        assert_eq!(history.len(), 2, "a pause: a step of its own");
        assert_eq!(history.undo(), Some(ior(5, 1.33)));
    }
}
