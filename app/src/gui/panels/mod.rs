//! The panels around the image, each a function of a narrow view of the
//! window's state that records what the user asked as commands (or
//! returns it): the side panel (scene, settings, views), the statistics
//! panel, the image area in the middle, compare mode's header and numbers.

pub(crate) mod banners;
pub(crate) mod central;
pub(crate) mod comparison;
pub(crate) mod observer;
pub(crate) mod scene_list;
pub(crate) mod settings;
pub(crate) mod side_panel;
pub(crate) mod stats;

use egui::Color32;

/// `frame` without its fill: the window's clear paints the panels' colour
/// at almost no cost, where a filled panel is a rectangle of fragments that a
/// software rasterizer shades one by one in every frame.
pub(crate) fn unfilled(frame: egui::Frame) -> egui::Frame {
    frame.fill(Color32::TRANSPARENT)
}
