//! One table of commands drives the buttons, the keyboard shortcuts and the
//! help overlay, so they can never disagree.

use egui::{Key, KeyboardShortcut, Modifiers};

/// Everything the user can ask the window to do by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    ToggleAntialiasing,
    ToggleSoftShadows,
    ToggleDepthOfField,
    ToggleGrid,
    TogglePause,
    Restart,
    ToggleKeepRefining,
    Save,
    SaveExr,
    Open,
    Reload,
    CopyLink,
    ResetCamera,
    ZoomFit,
    ZoomActualSize,
    ToggleStats,
    CycleView,
    ToggleHelp,
    ToggleCompare,
    SwapSides,
    CopyAToB,
    ToggleBenchmark,
    ExportReport,
    ToggleStudies,
    ToggleObserver,
    ToggleLessons,
    ToggleEditor,
    Undo,
    Redo,
    SaveScene,
    ClearSelection,
}

const fn key(key: Key) -> KeyboardShortcut {
    KeyboardShortcut::new(Modifiers::NONE, key)
}

impl Command {
    /// Every command, in the order the help lists them.
    ///
    /// egui matches Ctrl+Z when Ctrl+Shift+Z is pressed, so a shortcut with
    /// Shift comes before the same one without.
    pub const ALL: [Command; 31] = [
        Command::ToggleAntialiasing,
        Command::ToggleSoftShadows,
        Command::ToggleDepthOfField,
        Command::ToggleGrid,
        Command::TogglePause,
        Command::Restart,
        Command::ToggleKeepRefining,
        Command::SaveScene,
        Command::Save,
        Command::SaveExr,
        Command::Open,
        Command::Reload,
        Command::CopyLink,
        Command::ResetCamera,
        Command::ZoomFit,
        Command::ZoomActualSize,
        Command::ToggleStats,
        Command::CycleView,
        Command::ToggleObserver,
        Command::ToggleLessons,
        Command::ToggleEditor,
        Command::ClearSelection,
        Command::Redo,
        Command::Undo,
        Command::ToggleCompare,
        Command::SwapSides,
        Command::CopyAToB,
        Command::ToggleBenchmark,
        Command::ExportReport,
        Command::ToggleStudies,
        Command::ToggleHelp,
    ];

    /// The name on buttons and in the help.
    pub(crate) fn label(self) -> &'static str {
        match self {
            Command::ToggleAntialiasing => "Anti-aliasing",
            Command::ToggleSoftShadows => "Soft shadows",
            Command::ToggleDepthOfField => "Depth of field",
            Command::ToggleGrid => "Uniform grid",
            Command::TogglePause => "Pause / resume",
            Command::Restart => "Restart",
            Command::ToggleKeepRefining => "Keep refining",
            Command::Save => "Save PNG...",
            Command::SaveExr => "Save as EXR...",
            Command::Open => "Open...",
            Command::CopyLink => "Copy link",
            Command::Reload => "Reload scene",
            Command::ResetCamera => "Reset camera",
            Command::ZoomFit => "Fit to window",
            Command::ZoomActualSize => "Actual size (1:1)",
            Command::ToggleStats => "Statistics panel",
            Command::CycleView => "Next view",
            Command::ToggleHelp => "Help",
            Command::ToggleCompare => "Compare A/B",
            Command::SwapSides => "Swap A and B",
            Command::CopyAToB => "Copy A to B",
            Command::ToggleBenchmark => "Benchmark matrix",
            Command::ExportReport => "Export report...",
            Command::ToggleStudies => "Studies",
            Command::ToggleObserver => "Observer view",
            Command::ToggleLessons => "Lessons",
            Command::ToggleEditor => "Scene editor",
            Command::Undo => "Undo edit",
            Command::Redo => "Redo edit",
            Command::SaveScene => "Save scene...",
            Command::ClearSelection => "Clear selection",
        }
    }

    /// What it does, for tooltips and the help.
    pub(crate) fn description(self) -> &'static str {
        match self {
            Command::ToggleAntialiasing => {
                "Jittered N x N samples per pixel instead of one at the centre"
            }
            Command::ToggleSoftShadows => {
                "Lights get an area: point lights become squares of the light size"
            }
            Command::ToggleDepthOfField => {
                "Thin lens: aperture in pixels, sharp at the focal ratio times the view distance"
            }
            Command::ToggleGrid => "Switch between the uniform grid and the other structure",
            Command::TogglePause => "Hold the render between tiles, or let it go on",
            Command::Restart => "Throw away the samples so far and render again",
            Command::ToggleKeepRefining => "Keep adding fresh samples past the N x N target",
            Command::Save => "Write the displayed render at full resolution to a PNG file",
            Command::SaveExr => {
                "Write the linear float film, before clamping and encoding, to an OpenEXR file"
            }
            Command::Open => {
                "Open a scene (.p3f, .nff), a mesh (.obj, .ply) or a lesson (.toml); you can also drop one on the window"
            }
            Command::Reload => "Read the current scene file again",
            Command::ResetCamera => "Back to the scene file's camera",
            Command::ZoomFit => "Scale the image to fill the view",
            Command::ZoomActualSize => "One image pixel per screen pixel",
            Command::ToggleStats => "Show or hide the statistics panel",
            Command::CycleView => "Show the next per-pixel view: tests, steps, rays, depth...",
            Command::ToggleHelp => "List every shortcut",
            Command::ToggleCompare => {
                "Render a second settings set B beside A, same scene and camera"
            }
            Command::SwapSides => "Exchange the two sides, images included",
            Command::CopyAToB => "Give B the settings of A",
            Command::ToggleBenchmark => {
                "Time every structure x shadows x sampling on this scene, as the course report's table"
            }
            Command::ExportReport => {
                "Measure the course's experiments on this scene, camera, settings and edits, and write them as one HTML page"
            }
            Command::ToggleStudies => {
                "Sweep one parameter (grid m, N, depth, ...) or a generated scene's size and chart the times"
            }
            Command::ToggleObserver => {
                "See the scene from outside: the camera, its image plane, the lights and the pinned pixel's rays"
            }
            Command::ToggleLessons => {
                "The course's chapters as guided steps, each checking what you achieved"
            }
            Command::ToggleEditor => {
                "Change materials, shapes, lights and the camera; a click on the image selects what it shows"
            }
            Command::Undo => "Take back the last edit of the edited side's scene",
            Command::Redo => "Apply again the edit last taken back",
            Command::SaveScene => "Write the edited scene to a P3F file",
            Command::CopyLink => {
                "Copy the web page's link to what is on screen: the lesson and its step, or the scene with its settings and edits"
            }
            Command::ClearSelection => {
                "Forget the selected object (no outline, nothing to move); cancels the unsaved-edits question"
            }
        }
    }

    /// Whether it opens or writes a file of the user's choosing, which
    /// the web page cannot (its button greyed out there, saying why).
    pub(crate) fn opens_files(self) -> bool {
        matches!(self, Command::Open | Command::SaveScene)
    }

    /// The keys that trigger it; the first is the one shown.
    pub fn shortcuts(self) -> &'static [KeyboardShortcut] {
        const CTRL: Modifiers = Modifiers::COMMAND;
        const A: &[KeyboardShortcut] = &[key(Key::A)];
        const S: &[KeyboardShortcut] = &[key(Key::S)];
        const D: &[KeyboardShortcut] = &[key(Key::D)];
        const G: &[KeyboardShortcut] = &[key(Key::G)];
        const SPACE: &[KeyboardShortcut] = &[key(Key::Space)];
        const R: &[KeyboardShortcut] = &[key(Key::R)];
        const K: &[KeyboardShortcut] = &[key(Key::K)];
        const CTRL_S: &[KeyboardShortcut] = &[KeyboardShortcut::new(CTRL, Key::S)];
        const CTRL_O: &[KeyboardShortcut] = &[KeyboardShortcut::new(CTRL, Key::O)];
        const CTRL_E: &[KeyboardShortcut] = &[KeyboardShortcut::new(CTRL, Key::E)];
        const CTRL_R: &[KeyboardShortcut] = &[KeyboardShortcut::new(CTRL, Key::R)];
        const F5: &[KeyboardShortcut] = &[key(Key::F5)];
        const C: &[KeyboardShortcut] = &[key(Key::C)];
        const F: &[KeyboardShortcut] = &[key(Key::F)];
        const ONE: &[KeyboardShortcut] = &[key(Key::Num1)];
        const TAB: &[KeyboardShortcut] = &[key(Key::Tab)];
        const HELP: &[KeyboardShortcut] = &[key(Key::H), key(Key::Questionmark)];
        const B: &[KeyboardShortcut] = &[key(Key::B)];
        const W: &[KeyboardShortcut] = &[key(Key::W)];
        const M: &[KeyboardShortcut] = &[key(Key::M)];
        const P: &[KeyboardShortcut] = &[key(Key::P)];
        const V: &[KeyboardShortcut] = &[key(Key::V)];
        const O: &[KeyboardShortcut] = &[key(Key::O)];
        const SHIFT_B: &[KeyboardShortcut] = &[KeyboardShortcut::new(Modifiers::SHIFT, Key::B)];
        const E: &[KeyboardShortcut] = &[key(Key::E)];
        const L: &[KeyboardShortcut] = &[key(Key::L)];
        const CTRL_Z: &[KeyboardShortcut] = &[KeyboardShortcut::new(CTRL, Key::Z)];
        const CTRL_SHIFT: Modifiers = CTRL.plus(Modifiers::SHIFT);
        const REDO: &[KeyboardShortcut] = &[
            KeyboardShortcut::new(CTRL_SHIFT, Key::Z),
            KeyboardShortcut::new(CTRL, Key::Y),
        ];
        const CTRL_SHIFT_S: &[KeyboardShortcut] = &[KeyboardShortcut::new(CTRL_SHIFT, Key::S)];
        const CTRL_SHIFT_L: &[KeyboardShortcut] = &[KeyboardShortcut::new(CTRL_SHIFT, Key::L)];
        const ESCAPE: &[KeyboardShortcut] = &[key(Key::Escape)];
        match self {
            Command::ToggleAntialiasing => A,
            Command::ToggleSoftShadows => S,
            Command::ToggleDepthOfField => D,
            Command::ToggleGrid => G,
            Command::TogglePause => SPACE,
            Command::Restart => R,
            Command::ToggleKeepRefining => K,
            Command::Save => CTRL_S,
            Command::SaveExr => CTRL_E,
            Command::Open => CTRL_O,
            Command::Reload => F5,
            Command::ResetCamera => C,
            Command::ZoomFit => F,
            Command::ZoomActualSize => ONE,
            Command::ToggleStats => TAB,
            Command::CycleView => V,
            Command::ToggleHelp => HELP,
            Command::ToggleCompare => B,
            Command::SwapSides => W,
            Command::CopyAToB => SHIFT_B,
            Command::ToggleBenchmark => M,
            Command::ExportReport => CTRL_R,
            Command::ToggleStudies => P,
            Command::ToggleObserver => O,
            Command::ToggleLessons => L,
            Command::ToggleEditor => E,
            Command::Undo => CTRL_Z,
            Command::Redo => REDO,
            Command::SaveScene => CTRL_SHIFT_S,
            Command::CopyLink => CTRL_SHIFT_L,
            Command::ClearSelection => ESCAPE,
        }
    }

    /// Whether the shortcut has no modifier, so it must not fire while a
    /// text field has the keyboard.
    fn is_plain(shortcut: &KeyboardShortcut) -> bool {
        shortcut.modifiers == Modifiers::NONE
    }

    /// The commands whose shortcut was pressed this frame, consuming the
    /// key presses. Shortcuts with modifiers are checked first so that
    /// Ctrl+S saves rather than toggling soft shadows.
    pub(crate) fn pressed(ctx: &egui::Context) -> Vec<Command> {
        let typing = ctx.egui_wants_keyboard_input();
        let mut found = Vec::new();
        ctx.input_mut(|input| {
            for plain in [false, true] {
                for command in Command::ALL {
                    for shortcut in command.shortcuts() {
                        if Self::is_plain(shortcut) != plain || (plain && typing) {
                            continue;
                        }
                        if input.consume_shortcut(shortcut) && !found.contains(&command) {
                            found.push(command);
                        }
                    }
                }
            }
        });
        found
    }

    /// The shortcut as text, e.g. "Ctrl+S" or "H / ?".
    pub(crate) fn shortcut_text(self, ctx: &egui::Context) -> String {
        self.shortcuts()
            .iter()
            .map(|s| match s.logical_key {
                // egui spells it out as "Questionmark".
                Key::Questionmark => "?".to_string(),
                _ => ctx.format_shortcut(s),
            })
            .collect::<Vec<_>>()
            .join(" / ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_two_commands_share_a_shortcut() {
        let mut seen = Vec::new();
        for command in Command::ALL {
            for s in command.shortcuts() {
                assert!(!seen.contains(s), "{command:?} reuses {s:?}");
                seen.push(*s);
            }
        }
    }

    /// The user guide's key table is the one users read; the help
    /// overlay is drawn from `ALL`, so only the guide can fall behind.
    #[test]
    fn the_guide_lists_every_command_with_its_shortcut() {
        let guide = include_str!("../../../docs/guide/window.md");
        let ctx = egui::Context::default();
        let table: String = Command::ALL
            .iter()
            .map(|c| {
                format!(
                    "| `{}` | {} | {} |\n",
                    c.shortcut_text(&ctx),
                    c.label(),
                    c.description()
                )
            })
            .collect();
        assert!(
            guide.contains(&table),
            "docs/guide/window.md's table of keys should read:\n{table}"
        );
    }

    #[test]
    fn the_original_keys_toggle_the_original_features() {
        assert_eq!(Command::ToggleAntialiasing.shortcuts()[0], key(Key::A));
        assert_eq!(Command::ToggleSoftShadows.shortcuts()[0], key(Key::S));
        assert_eq!(Command::ToggleDepthOfField.shortcuts()[0], key(Key::D));
        assert_eq!(Command::ToggleGrid.shortcuts()[0], key(Key::G));
    }
}
