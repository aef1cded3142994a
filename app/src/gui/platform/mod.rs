//! What the window needs of the machine it runs on: the clock of what it
//! times itself, the frame meter and progress pace, the CPU clocks they
//! read, the software rasterizer's priority, screenshots for
//! `--screenshot`, and `target`: what differs between the desktop
//! (`native.rs`) and the web page (`web.rs`), the one place the window
//! asks which it runs on.

pub mod clock;
pub mod cpu_clock;
pub mod frame_meter;
#[cfg(not(target_family = "wasm"))]
pub mod paint_priority;
pub mod screenshot;
#[cfg_attr(not(target_family = "wasm"), path = "native.rs")]
#[cfg_attr(target_family = "wasm", path = "web.rs")]
pub mod target;
