//! The window end to end: driven frame by frame with `egui_kittest`, and
//! the real window under Xvfb (`real_window`, ignored unless asked for:
//! `cargo test --test window -- --ignored`). One module per area.

#[path = "../support/mod.rs"]
mod support;

mod basics;
mod commands;
mod editing;
mod harness;
mod lessons;
mod observer;
mod persistence;
mod real_window;
mod report;
mod soak;
mod studies;
mod views;
