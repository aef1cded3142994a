//! Headless measuring, shared by the command line (`commands/`) and the
//! window (`gui/`): the benchmark runner with its cases and the seed's timing
//! matrix, rays cast without shading (`bench --rays`), A/B comparison, what
//! a frame will cost, parameter studies with their charts, settings
//! described in words, result tables, and two sides' view values compared. Nothing here prints or touches a window.

pub mod bench_report;
pub mod benchmark;
pub mod compare;
pub mod cost;
pub mod describe;
pub mod overlay_image;
pub mod ray_cast;
pub mod ray_tree_report;
pub mod study;
pub mod value_difference;
pub mod view_image;
