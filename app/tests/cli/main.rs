//! The command line end to end: the real `workbench` binary run on scene
//! files, one module per area. `cargo test --test cli`.

#[path = "../support/mod.rs"]
mod support;

mod adaptive;
mod bad_scenes;
mod bench_rays;
#[cfg(unix)]
mod closed_stdout;
mod compare;
mod determinism;
mod docs;
mod edits;
mod flags;
mod golden;
mod lesson_explain;
mod lesson_folders;
mod lesson_progress;
mod lessons;
mod meshes_and_images;
mod observe;
mod reference_docs;
mod render;
mod report;
mod sweep;
mod views;
