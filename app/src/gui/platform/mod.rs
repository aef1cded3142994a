//! What the window needs of the machine it runs on: the clock of what it
//! times itself, the frame meter and progress pace, the CPU clocks they
//! read, the software rasterizer's priority, screenshots for
//! `--screenshot`, and `target`: what differs between the desktop
//! (`native.rs`) and the web page (`web.rs`), the one place the window
//! asks which it runs on; `transfer`, a fetch's progress; on the web, `page_modes`: what a page's query
//! can ask instead of the window (`?replay`).

pub(crate) mod clock;
pub(crate) mod cpu_clock;
#[cfg(target_family = "wasm")]
pub(crate) mod download;
pub(crate) mod frame_meter;
#[cfg(target_family = "wasm")]
pub(crate) mod page_modes;
#[cfg(not(target_family = "wasm"))]
pub(crate) mod paint_priority;
pub(crate) mod screenshot;
#[cfg_attr(not(target_family = "wasm"), path = "native.rs")]
#[cfg_attr(target_family = "wasm", path = "web.rs")]
pub(crate) mod target;
pub(crate) mod transfer;
#[cfg(target_family = "wasm")]
pub(crate) mod web_link;

/// A button that opens or writes files or folders on this computer
/// (Open..., Lesson folder..., Compare with image..., a window's
/// Export...): greyed out where that cannot work (the web page), saying
/// why when hovered ([`target::NO_FILES`]), instead of doing nothing.
pub(crate) fn file_button(
    ui: &mut egui::Ui,
    enabled: bool,
    button: egui::Button,
) -> egui::Response {
    match target::NO_FILES {
        Some(why) => ui.add_enabled(false, button).on_disabled_hover_text(why),
        None => ui.add_enabled(enabled, button),
    }
}

/// What background work calls when it has something to show: a repaint
/// of the window on the desktop, nothing on the web page. A worker cannot
/// call into eframe there (its repaint reads the page's clock through
/// `window`, which a worker lacks: "should have a Window"), so the page
/// looks again while work is in flight instead (`target::busy`).
pub(crate) fn waker(ctx: &egui::Context) -> impl Fn() + Send + Sync + Clone + 'static {
    let ctx = ctx.clone();
    move || {
        if target::WORK_WAKES_WINDOW {
            ctx.request_repaint();
        }
    }
}

/// [`waker`] redrawing no sooner than `pace` asks: progress arriving
/// during a render needs no frame of its own.
pub(crate) fn paced_waker(
    ctx: &egui::Context,
    pace: &frame_meter::ProgressPace,
) -> impl Fn() + Send + Sync + Clone + 'static {
    let (ctx, pace) = (ctx.clone(), pace.clone());
    move || {
        if target::WORK_WAKES_WINDOW {
            ctx.request_repaint_after(pace.get());
        }
    }
}
