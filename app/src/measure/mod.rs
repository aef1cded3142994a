//! Headless measuring, shared by the command line (`commands/`) and the
//! window (`gui/`): the benchmark runner with its cases and the seed's timing
//! matrix, A/B comparison, settings described in words, and result tables.
//! Nothing here prints or draws.

pub mod bench_report;
pub mod benchmark;
pub mod compare;
pub mod describe;
pub mod overlay_image;
pub mod ray_tree_report;
pub mod view_image;
