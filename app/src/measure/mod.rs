//! Headless measuring, shared by the command line (`headless/`) and the
//! window (`gui/`): the benchmark runner with its cases and the course
//! report's timing matrix, rays cast without shading (`bench --rays`), A/B
//! comparison, what a frame will cost, parameter studies with their charts,
//! settings described in words, result tables, two sides' view values
//! compared, and the observer figure. Nothing here prints or touches a
//! window.

pub mod ab;
pub mod bench_report;
pub mod benchmark;
pub mod cost;
pub mod describe;
pub mod heatmap_image;
pub mod observer;
pub mod observer_image;
pub mod overlay_image;
pub mod projection;
pub mod ray_cast;
pub mod ray_tree_report;
pub mod study;
pub mod value_difference;
