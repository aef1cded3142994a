//! What the workbench writes as words: a render's statistics, benchmark
//! and study tables (text, Markdown, CSV, JSON), a pixel's ray tree,
//! settings described in words, a view's summary, the time to a given
//! error (`bench --to-error`), and the lab report (one HTML page of the
//! course's experiments on a scene). The command line
//! prints them, the window shows and exports them.

pub(crate) mod bench_table;
pub(crate) mod lab;
pub(crate) mod ray_tree;
pub(crate) mod render_stats;
pub(crate) mod study_table;
pub(crate) mod to_error;
pub(crate) mod view_summary;
