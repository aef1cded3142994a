//! A soak of the window: a seeded random sequence of what a user does (every
//! command's key, orbits and pans over the image, sliders, scenes from the
//! list including the largest mesh and a broken file, compare mode, the
//! benchmark matrix opened and cancelled, window resizes), run through
//! `egui_kittest`. Nothing may panic, no error may show but the broken file's,
//! memory stays bounded, and at the end the image on screen equals a fresh
//! headless render of the final settings.
//!
//! `cargo test` runs a short version; `WORKBENCH_SOAK_EVENTS=5000 cargo test
//! --test window soak` a long one (`WORKBENCH_SOAK_SEED` picks another sequence).

use std::sync::Arc;
use std::thread::sleep;
use std::time::Duration;

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tracer::accel::SceneIndex;
use tracer::render::JobState;
use workbench::gui::{Activity, Command, WorkbenchApp};
use workbench::load::SceneSource;

use crate::harness::{DroppedPath, broken_scene, small_window, wait_for};

/// Events of the short version, run by `cargo test`.
const SHORT_SOAK: usize = 300;
/// The most the process may hold, a guard against runaway growth: sessions
/// with mesh_large (and its structures, on both sides in compare mode) peak
/// around 1.6 GiB.
const MEMORY_CAP: u64 = 3 << 30;
/// From this many events on, the memory must level off: the second half of
/// the session may not grow past the first's peak by more than
/// [`MEMORY_GROWTH`].
const LONG_SOAK: usize = 1000;
/// How much the second half of a long session may grow past the first's peak.
const MEMORY_GROWTH: u64 = 256 << 20;
/// Events between two readings of the resident memory.
const MEMORY_SAMPLE: usize = 50;
/// Scenes the soak opens from the list: small ones, and the largest mesh.
const SCENES: [&str; 4] = ["balls_low", "balls_medium", "tetra", "mesh_large"];

/// A small, seedable generator (splitmix64): the same seed, the same soak.
struct Random(u64);

impl Random {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn unit(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 24) as f32
    }
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// The process's resident memory, where the OS tells it.
fn resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib << 10)
}

/// Lets texture uploads go: the soak never draws, and kittest's default
/// renderer keeps every upload until its first drawing (hundreds of MiB
/// over a session, which would hide the window's own memory use).
struct NoDrawing;

impl egui_kittest::TestRenderer for NoDrawing {
    fn handle_delta(&mut self, delta: &mut egui::TexturesDelta) {
        delta.clear();
    }

    fn render(
        &mut self,
        _: &egui::Context,
        _: &egui::FullOutput,
    ) -> Result<image::RgbaImage, String> {
        Err("the soak does not draw".into())
    }
}

/// What the soak can do; each is one user action.
#[derive(Debug, Clone, Copy)]
enum Action {
    Key(Command),
    Drag { secondary: bool, shift: bool },
    Slider(&'static str, bool),
    OpenScene(&'static str),
    DropBrokenFile,
    DismissError,
    Benchmark,
    Resize,
    Idle,
}

const SLIDERS: [&str; 5] = [
    "Samples N",
    "Max depth",
    "Grid multiplier m",
    "Ambient",
    "Resolution scale",
];

fn pick(random: &mut Random) -> Action {
    match random.below(20) {
        0..=7 => {
            // Native file dialogs need a desktop portal: not in a test.
            let commands: Vec<Command> = Command::ALL
                .into_iter()
                .filter(|c| !matches!(c, Command::Open | Command::Save | Command::SaveExr))
                .collect();
            Action::Key(commands[random.below(commands.len())])
        }
        8..=10 => Action::Drag {
            secondary: random.below(4) == 0,
            shift: random.below(3) == 0,
        },
        11..=13 => Action::Slider(SLIDERS[random.below(SLIDERS.len())], random.below(2) == 0),
        14 | 15 => Action::OpenScene(SCENES[random.below(SCENES.len())]),
        16 => Action::DropBrokenFile,
        17 => {
            if random.below(2) == 0 {
                Action::DismissError
            } else {
                Action::Benchmark
            }
        }
        18 => Action::Resize,
        _ => Action::Idle,
    }
}

/// Does `action`; `broken` is the broken scene file to drop (written once,
/// so no load ever reads it half written).
fn act(
    harness: &mut Harness<'static, WorkbenchApp>,
    random: &mut Random,
    action: Action,
    broken: &std::path::Path,
) {
    match action {
        Action::Key(command) => {
            let shortcut = command.shortcuts()[0];
            harness.key_press_modifiers(shortcut.modifiers, shortcut.logical_key);
        }
        Action::Drag { secondary, shift } => {
            let Some(view) = harness
                .query_all_by_role_and_label(Role::Image, "Render")
                .next()
            else {
                return;
            };
            let rect = view.rect();
            let button = if secondary {
                egui::PointerButton::Secondary
            } else {
                egui::PointerButton::Primary
            };
            let modifiers = if shift {
                egui::Modifiers::SHIFT
            } else {
                egui::Modifiers::NONE
            };
            let mut at = rect.center();
            let press = |pos, pressed| egui::Event::PointerButton {
                pos,
                button,
                pressed,
                modifiers,
            };
            harness.event_modifiers(press(at, true), modifiers);
            harness.step();
            for _ in 0..1 + random.below(6) {
                at += egui::vec2(random.unit() * 40.0 - 20.0, random.unit() * 40.0 - 20.0);
                harness.event_modifiers(egui::Event::PointerMoved(at), modifiers);
                harness.step();
            }
            harness.event_modifiers(press(at, false), modifiers);
            harness.remove_cursor();
        }
        Action::Slider(label, up) => {
            let Some(slider) = harness
                .query_all_by_role_and_label(Role::Slider, label)
                .next()
            else {
                return;
            };
            slider.focus();
            harness.step();
            harness.key_press(if up {
                egui::Key::ArrowRight
            } else {
                egui::Key::ArrowLeft
            });
        }
        Action::OpenScene(name) => {
            let Some(entry) = harness.query_all_by_label(name).next() else {
                return;
            };
            entry.scroll_to_me();
            harness.step();
            if let Some(entry) = harness.query_all_by_label(name).next() {
                entry.click();
            }
            // A user waits for the scene they picked to appear.
            harness.step();
            wait_for(harness, name, |app| !app.engine().is_loading());
        }
        Action::DropBrokenFile => harness
            .input_mut()
            .dropped_files
            .push(Arc::new(DroppedPath(broken.to_path_buf()))),
        Action::DismissError => {
            if let Some(button) = harness
                .query_all_by_role_and_label(Role::Button, "Dismiss")
                .next()
            {
                button.click();
            }
        }
        Action::Benchmark => {
            // Open the matrix, start it, cancel it, close it.
            harness.key_press(egui::Key::M);
            harness.step();
            for label in ["Run", "Cancel"] {
                let clicked = harness
                    .query_all_by_role_and_label(Role::Button, label)
                    .next()
                    .map(|button| button.click())
                    .is_some();
                if clicked {
                    harness.step();
                }
            }
            harness.key_press(egui::Key::M);
        }
        Action::Resize => {
            let size = egui::vec2(640.0 + random.unit() * 960.0, 400.0 + random.unit() * 600.0);
            harness.set_size(size);
        }
        Action::Idle => sleep(Duration::from_millis(random.below(30) as u64)),
    }
}

/// Fails on any error but the broken file's.
fn check_error(app: &WorkbenchApp, log: &[Action]) {
    if let Some(error) = app.error() {
        assert!(
            error.contains("broken.p3f:5:7"),
            "unexpected error {error:?} after {:?}",
            &log[log.len().saturating_sub(8)..]
        );
    }
}

#[test]
fn a_random_session_ends_with_the_right_image_and_bounded_memory() {
    let events = env_number("WORKBENCH_SOAK_EVENTS", SHORT_SOAK as u64) as usize;
    let seed = env_number("WORKBENCH_SOAK_SEED", 14);
    let mut random = Random(seed);
    let mut harness = small_window(Harness::builder().renderer(NoDrawing));
    wait_for(&mut harness, "the first render", |app| {
        app.engine().activity() == Activity::Job(JobState::Done) && app.is_catalog_complete()
    });
    // Resident memory every SAMPLE events: the allocator keeps what the
    // largest scene needed, so growth is judged from the first half's peak.
    let mut memory = Vec::new();

    let (_folder, broken) = broken_scene("soak");
    let mut log = Vec::with_capacity(events);
    // What the session went through, so a soak that missed the hard parts
    // does not pass for one that survived them.
    let (mut saw_error, mut saw_mesh, mut saw_compare) = (false, false, false);
    for i in 0..events {
        // The hard parts happen in every session, whatever the seed draws;
        // the rest is random.
        let action = match i {
            _ if i == events / 4 => {
                // Through the app, not the list: a window the session opened
                // may cover the list.
                harness
                    .state_mut()
                    .open(SceneSource::Bundled("mesh_large".into()));
                wait_for(&mut harness, "mesh_large", |app| !app.engine().is_loading());
                Action::Idle
            }
            _ if i == events / 2 => Action::DropBrokenFile,
            _ if i == 3 * events / 4 && harness.state().comparison().is_none() => {
                // Out of any text field that a drag focused, so the key
                // reaches the window.
                harness.ctx.memory_mut(|m| m.stop_text_input());
                Action::Key(Command::ToggleCompare)
            }
            _ => pick(&mut random),
        };
        log.push(action);
        act(&mut harness, &mut random, action, &broken);
        harness.run_steps(1 + random.below(3));
        let app = harness.state();
        check_error(app, &log);
        saw_error |= app.error().is_some();
        saw_mesh |= app
            .engine()
            .scene()
            .is_some_and(|s| s.source == SceneSource::Bundled("mesh_large".into()));
        saw_compare |= app.comparison().is_some();
        if log.len() % MEMORY_SAMPLE == 0 {
            memory.extend(resident_bytes());
        }
        // Keep the renders small, as a user on a slow machine would: a
        // finer grid over mesh_large alone takes gigabytes, by design.
        let controls = harness.state_mut().controls_mut();
        controls.resolution_scale = controls.resolution_scale.min(0.25);
        controls.render.samples = controls.render.samples.min(3);
        controls.render.grid_multiplier = controls.render.grid_multiplier.min(2.0);
    }

    if events >= SHORT_SOAK {
        assert!(
            saw_error && saw_mesh && saw_compare,
            "the session missed a part: broken file {saw_error}, mesh_large {saw_mesh}, \
             compare mode {saw_compare}"
        );
    }

    // Settle: no refining forever, not paused, nothing loading; then the
    // image on screen must be the final render of the final settings.
    harness.state_mut().controls_mut().render.keep_refining = false;
    // A drag may have put the keyboard focus in a text field (the Studies
    // window's values), which then takes the keys as text.
    harness.ctx.memory_mut(|m| m.stop_text_input());
    harness.step();
    if harness.state().engine().is_paused() {
        harness.key_press(egui::Key::Space);
    }
    // Back to the shaded image (the session may end on a cost view).
    for _ in 0..16 {
        if harness.state().views().view == tracer::render::View::Shaded {
            break;
        }
        let shortcut = Command::CycleView.shortcuts()[0];
        harness.key_press_modifiers(shortcut.modifiers, shortcut.logical_key);
        harness.step();
    }
    assert_eq!(harness.state().views().view, tracer::render::View::Shaded);
    harness.remove_cursor();
    wait_for(&mut harness, "the final image", |app| {
        !app.engine().is_loading()
            && app.engine().activity() == Activity::Job(JobState::Done)
            && app.is_display_current()
    });
    check_error(harness.state(), &log);
    let app = harness.state();
    let scene = app.engine().scene().expect("a scene");
    let settings = app.engine().settings().cloned().expect("a render");
    let index = Arc::new(SceneIndex::build(
        &scene.world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    let (film, _) = tracer::render::render(scene.world.clone(), index, settings.clone(), None)
        .expect("the headless render");
    let shown = app.shown().expect("an image on screen");
    assert_eq!(
        (shown.width, shown.height),
        (settings.width, settings.height)
    );
    assert!(
        shown.rgba == film.to_rgba8(app.controls().encoding()),
        "the window shows another image than a headless render of {settings:?}"
    );

    let readings = || memory.iter().map(|m| m >> 20).collect::<Vec<_>>();
    if let Some(peak) = memory.iter().max() {
        assert!(
            *peak < MEMORY_CAP,
            "memory reached {} MiB (MiB every {MEMORY_SAMPLE} events: {:?})",
            peak >> 20,
            readings()
        );
    }
    let half = memory.len() / 2;
    if events >= LONG_SOAK
        && let (Some(first), Some(second)) =
            (memory[..half].iter().max(), memory[half..].iter().max())
    {
        assert!(
            *second < first + MEMORY_GROWTH,
            "memory keeps growing: peak {} MiB in the first half, {} MiB in the second \
             (MiB every {MEMORY_SAMPLE} events: {:?})",
            first >> 20,
            second >> 20,
            readings()
        );
    }
}
