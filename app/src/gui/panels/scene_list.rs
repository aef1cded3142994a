//! Choosing a scene: the bundled ones with their sizes, files in `scenes/`
//! on disk, recent files, and a native open dialog.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use web_time::Instant;

use crate::gui::platform::clock::Clock;
use crate::gui::platform::target;

use egui::{RichText, Ui};
use tracer::scene::{Limits, Primitive, Scene, parse_scene};

use crate::bundled;
use crate::describe::si;
use crate::load::SceneSource;

use super::settings::command_button;
use crate::gui::commands::Command;

/// Longest wait for the first render before the scene list's counts start.
const CATALOG_DELAY: Duration = Duration::from_secs(3);

/// What the list shows beside the bundled scenes' names.
pub struct SceneList {
    pub catalog: Catalog,
    /// Files in `scenes/` when the window opened.
    disk_scenes: Vec<PathBuf>,
    opened_at: Instant,
    /// Counting starts this long after opening even if the first render
    /// still runs.
    pub delay: Duration,
    /// Times the delay.
    clock: Clock,
}

impl SceneList {
    /// The list as the window opens, `clock` timing its counting's delay.
    pub fn new(clock: Clock) -> Self {
        Self {
            catalog: Catalog::default(),
            disk_scenes: scene_files(Path::new("scenes")),
            opened_at: clock.now(),
            delay: CATALOG_DELAY,
            clock,
        }
    }

    /// Starts counting the bundled scenes once the first render no longer
    /// needs the machine (`busy` false), or `delay` ([`CATALOG_DELAY`]) after opening
    /// at the latest: parsing them took a noticeable share of a short first
    /// render's CPU on two cores, its thread's lowest priority
    /// notwithstanding. `wake` redraws as counts arrive.
    pub fn count_when_due(&mut self, busy: bool, wake: impl Fn() + Send + 'static) {
        if self.catalog.is_started() || (busy && self.clock.now() - self.opened_at < self.delay) {
            return;
        }
        self.catalog.start(wake);
    }
}

/// Object counts of the bundled scenes, parsed once on a background thread
/// so the list opens at once even with a 262k-triangle mesh among them.
pub struct Catalog {
    /// A size summary per scene name; `None` for a scene that does not parse.
    summaries: Arc<Mutex<HashMap<&'static str, Option<String>>>>,
    started: bool,
    /// Whether the counting thread yields to everything else (the
    /// window's default); tests waiting for the counts turn it off, as
    /// beside a build on two cores the lowest priority gets almost nothing.
    pub lowest_priority: bool,
}

impl Default for Catalog {
    fn default() -> Self {
        Self {
            summaries: Arc::default(),
            started: false,
            lowest_priority: true,
        }
    }
}

impl Catalog {
    /// Starts counting, once; `wake` asks the window to redraw as counts
    /// arrive. Until then the list shows no counts.
    pub fn start(&mut self, wake: impl Fn() + Send + 'static) {
        if std::mem::replace(&mut self.started, true) {
            return;
        }
        let summaries = self.summaries.clone();
        let lowest_priority = self.lowest_priority;
        // Without the thread the list simply shows no counts.
        let _ = target::spawn("scene-catalog", move || {
            // Counting can wait: a render must not.
            if lowest_priority {
                target::lowest_priority();
            }
            for scene in bundled::SCENES {
                let parsed =
                    parse_scene(scene.text, Some(Path::new(scene.file)), &Limits::default());
                if let Ok(mut summaries) = summaries.lock() {
                    summaries.insert(scene.name, parsed.ok().map(|s| summary(&s)));
                }
                wake();
            }
        });
    }

    /// Whether [`Catalog::start`] was called.
    pub fn is_started(&self) -> bool {
        self.started
    }

    /// How big the bundled scene `name` is, once counted. Read without
    /// waiting (`try_lock`): the window's thread must never wait for the
    /// counting one, which on the web page is an error ("Atomics.wait
    /// cannot be called in this context"); a count being written shows
    /// on the next frame.
    pub fn summary(&self, name: &str) -> Option<String> {
        self.summaries.try_lock().ok()?.get(name).cloned().flatten()
    }

    /// Whether every bundled scene was counted (false while the counting
    /// thread writes, as [`Self::summary`] does not wait).
    pub fn is_complete(&self) -> bool {
        self.summaries
            .try_lock()
            .is_ok_and(|counts| counts.len() == bundled::SCENES.len())
    }
}

/// "93 objects", or "1 object, 262.1k triangles" when meshes hide the size.
fn summary(scene: &Scene) -> String {
    let objects = scene.objects.len();
    let triangles: usize = scene
        .objects
        .iter()
        .map(|o| match &o.primitive {
            Primitive::Mesh { triangles, .. } => triangles.len(),
            _ => 0,
        })
        .sum();
    let plural = if objects == 1 { "" } else { "s" };
    if triangles == 0 {
        format!("{objects} object{plural}")
    } else {
        format!(
            "{objects} object{plural}, {} triangles",
            si(triangles as f64)
        )
    }
}

/// Scene files in `dir` (not recursive), sorted.
pub fn scene_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| is_scene_file(p))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

/// Whether `path` looks like a scene file, or a mesh file the window
/// frames into one.
pub fn is_scene_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("p3f") || e.eq_ignore_ascii_case("nff"))
        || tracer::scene::mesh_io::MeshFormat::of(path).is_some()
}

/// Draws the picker; returns the scene the user chose, if any.
pub fn show(
    ui: &mut Ui,
    list: &SceneList,
    current: Option<&SceneSource>,
    recent: &[PathBuf],
    commands: &mut Vec<Command>,
) -> Option<SceneSource> {
    let (catalog, disk_scenes) = (&list.catalog, &list.disk_scenes);
    let mut chosen = None;
    ui.heading("Scene");
    ui.horizontal(|ui| {
        command_button(ui, Command::Open, commands);
        command_button(ui, Command::Reload, commands);
        command_button(ui, Command::CopyLink, commands);
    });
    egui::ScrollArea::vertical()
        .id_salt("scene_list")
        .max_height(220.0)
        .show(ui, |ui| {
            for scene in bundled::SCENES {
                let source = SceneSource::Bundled(scene.name.to_string());
                let selected = current == Some(&source);
                let response = ui
                    .horizontal(|ui| {
                        let response = ui
                            .selectable_label(selected, scene.name)
                            .on_hover_text(scene.description);
                        if let Some(summary) = catalog.summary(scene.name) {
                            ui.weak(summary);
                        }
                        response
                    })
                    .inner;
                if response.clicked() {
                    chosen = Some(source);
                }
            }
            // Files on disk that are not bundled copies (edited or new).
            for path in disk_scenes {
                let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned());
                if stem.as_deref().is_some_and(|s| bundled::find(s).is_some()) {
                    continue;
                }
                let source = SceneSource::File(path.clone());
                let label = format!("{} (file)", source.label());
                if ui
                    .selectable_label(current == Some(&source), label)
                    .on_hover_text(path.display().to_string())
                    .clicked()
                {
                    chosen = Some(source);
                }
            }
        });
    if let Some(SceneSource::Bundled(name)) = current
        && let Some(scene) = bundled::find(name)
    {
        // The first sentence; the whole line on hover.
        let first = scene.description.split(';').next().unwrap_or_default();
        ui.label(RichText::new(first).small().weak())
            .on_hover_text(scene.description);
    }
    if !recent.is_empty() {
        ui.collapsing("Recent files", |ui| {
            for path in recent {
                let source = SceneSource::File(path.clone());
                if ui
                    .selectable_label(current == Some(&source), source.label())
                    .on_hover_text(path.display().to_string())
                    .clicked()
                {
                    chosen = Some(source);
                }
            }
        });
    }
    chosen
}
