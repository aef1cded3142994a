//! What the window tells the user: the error shown above the image until
//! dismissed or replaced, and short notices that fade after a few seconds.

use std::time::Duration;

use web_time::Instant;

use crate::gui::platform::clock::Clock;

/// How long a notice stays on screen.
const NOTICE_TIME: Duration = Duration::from_secs(5);

pub(crate) struct Messages {
    /// Shown above the image until dismissed.
    pub(crate) error: Option<String>,
    /// An error about what the user asked for rather than about the scene
    /// on screen (a lesson that does not read, a link to nothing): a
    /// scene loaded next, such as the one the window opens with, leaves
    /// it shown ([`Self::scene_loaded`]).
    lasting: Option<String>,
    notice: Option<(String, Instant)>,
    /// Times the notice's fade.
    clock: Clock,
}

impl Messages {
    pub(crate) fn new(clock: Clock) -> Self {
        Self {
            error: None,
            lasting: None,
            notice: None,
            clock,
        }
    }

    /// Shows the error `text` until dismissed or replaced, even across a
    /// scene load.
    pub(crate) fn lasting_error(&mut self, text: String) {
        self.lasting = Some(text.clone());
        self.error = Some(text);
    }

    /// A scene loaded: the error of an earlier scene (a load or a render
    /// that failed) goes; a [`Self::lasting_error`] stays.
    pub(crate) fn scene_loaded(&mut self) {
        if self.error != self.lasting {
            self.error = None;
        }
    }

    /// Shows `text` for a few seconds.
    pub(crate) fn notify(&mut self, text: impl Into<String>) {
        self.notice = Some((text.into(), self.clock.now()));
    }

    /// Draws the notice while it lasts, at the top of the window.
    pub(crate) fn show_notice(&mut self, ctx: &egui::Context) {
        let Some((text, since)) = &self.notice else {
            return;
        };
        let shown_for = self.clock.now() - *since;
        if shown_for >= NOTICE_TIME {
            self.notice = None;
            return;
        }
        let text = text.clone();
        egui::Area::new(egui::Id::unique("notice"))
            .anchor(egui::Align2::CENTER_TOP, [0.0, 12.0])
            .show(ctx, |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| ui.label(text));
            });
        ctx.request_repaint_after(NOTICE_TIME - shown_for);
    }
}
