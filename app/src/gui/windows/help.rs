//! The help window: every command with its shortcut, from the command
//! table, and the mouse gestures.

use crate::gui::commands::Command;

/// Shows the help while `open`; its close button clears `open`.
pub(crate) fn window(ctx: &egui::Context, open: &mut bool) {
    egui::Window::new("Keyboard shortcuts and mouse")
        .open(open)
        .collapsible(false)
        .resizable(false)
        .show(ctx, |ui| {
            egui::Grid::new("help")
                .num_columns(3)
                .striped(true)
                .show(ui, |ui| {
                    for command in Command::ALL {
                        ui.monospace(command.shortcut_text(ctx));
                        ui.label(command.label());
                        ui.label(command.description());
                        ui.end_row();
                    }
                    for (gesture, what) in [
                        ("Left drag", "Orbit the camera around its target"),
                        ("Shift + left drag, middle drag", "Pan the camera"),
                        ("Ctrl + wheel", "Dolly the camera in and out"),
                        ("Wheel", "Zoom the image around the cursor"),
                        ("Right drag", "Pan the image"),
                    ] {
                        ui.monospace(gesture);
                        ui.label("");
                        ui.label(what);
                        ui.end_row();
                    }
                });
        });
}
