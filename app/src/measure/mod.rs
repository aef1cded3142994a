//! Runners that measure, shared by the command line (`headless/`) and the
//! window (`gui/`): the benchmark runner with its cases and the course
//! report's timing matrix, rays cast without shading (`bench --rays`), A/B
//! comparison, what a frame will cost, parameter studies, two sides' view
//! values compared, and the time sampling takes to a given error. What
//! they find is drawn by [`crate::figures`] and written by
//! [`crate::reports`]; nothing here prints or touches a window.

pub mod ab;
pub(crate) mod benchmark;
pub(crate) mod cost;
pub(crate) mod ray_cast;
pub(crate) mod study;
pub(crate) mod to_error;
pub(crate) mod value_difference;
