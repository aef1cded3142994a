//! Lessons: the course's chapters as guided tasks, each step checking what
//! the student achieved. `format` reads a lesson file into steps and
//! `actions` (what a start, setup or solution does), `check` says whether a
//! step is done, `state` is what a check looks at, `replay` walks a
//! lesson's steps the way a student would (for `workbench lesson check`
//! and the window's "Set up this step"), `bundled` is the set shipped in
//! the binary, `progress` what a student did, as kept and handed in.

pub(crate) mod actions;
pub mod bundled;
pub(crate) mod check;
pub(crate) mod explain;
pub(crate) mod folder;
pub mod format;
pub(crate) mod new;
pub mod progress;
pub(crate) mod replay;
pub(crate) mod state;

pub use check::{Check, Verdict, evaluate};
pub(crate) use format::Lesson;
