//! What the window needs of the machine it runs on: the clock of what it
//! times itself, the frame meter and progress pace, the CPU clocks they
//! read, the software rasterizer's priority, and screenshots for
//! `--screenshot`.

pub mod clock;
pub mod cpu_clock;
pub mod frame_meter;
pub mod paint_priority;
pub mod screenshot;
