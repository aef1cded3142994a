//! Figures drawn into images, for the command line and the window alike:
//! 3D segments projected through a camera ([`projection`]), a view's heat
//! map with its legend, the acceleration structure over a render, the
//! observer figure (the scene seen from outside), and a study's chart
//! (its text drawn in Rust on every target: [`chart_text`]).
//! Nothing here writes a file: [`crate::image_file`] does.

pub(crate) mod chart_text;
pub(crate) mod heat_map;
pub(crate) mod observer;
pub(crate) mod overlay;
pub(crate) mod projection;
pub(crate) mod study_plot;
