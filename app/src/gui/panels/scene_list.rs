//! Choosing a scene: the bundled ones with their sizes (on the web page
//! also those beside it, fetched when picked, with a progress bar), files
//! in `scenes/` on disk, recent files, and a native open dialog.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use web_time::Instant;

use crate::gui::platform::clock::Clock;
use crate::gui::platform::target;
use crate::gui::platform::transfer::{self, Transfer};

use egui::{RichText, Ui};
use tracer::scene::{Limits, Primitive, Scene, parse_scene};

use crate::bundled::{self, Offered, SiteScene};
use crate::describe::si;
use crate::load::SceneSource;

use super::settings::command_button;
use crate::gui::commands::Command;

/// Longest wait for the first render before the scene list's counts start.
const CATALOG_DELAY: Duration = Duration::from_secs(3);

/// What the list shows beside the bundled scenes' names.
pub(crate) struct SceneList {
    pub(crate) catalog: Catalog,
    /// Files in `scenes/` when the window opened.
    disk_scenes: Vec<PathBuf>,
    opened_at: Instant,
    /// Counting starts this long after opening even if the first render
    /// still runs.
    pub(crate) delay: Duration,
    /// Times the delay.
    clock: Clock,
}

impl SceneList {
    /// The list as the window opens, `clock` timing its counting's delay.
    pub(crate) fn new(clock: Clock) -> Self {
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
    pub(crate) fn count_when_due(&mut self, busy: bool, wake: impl Fn() + Send + 'static) {
        if self.catalog.is_started() || (busy && self.clock.now() - self.opened_at < self.delay) {
            return;
        }
        self.catalog.start(wake);
    }
}

/// Object counts of the bundled scenes, parsed once on a background thread
/// so the list opens at once even with a 262k-triangle mesh among them.
pub(crate) struct Catalog {
    /// A size summary per scene name; `None` for a scene that does not parse.
    summaries: Arc<Mutex<HashMap<&'static str, Option<String>>>>,
    started: bool,
    /// Whether the counting thread yields to everything else (the
    /// window's default); tests waiting for the counts turn it off, as
    /// beside a build on two cores the lowest priority gets almost nothing.
    pub(crate) lowest_priority: bool,
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
    pub(crate) fn start(&mut self, wake: impl Fn() + Send + 'static) {
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
    pub(crate) fn is_started(&self) -> bool {
        self.started
    }

    /// How big the bundled scene `name` is, once counted. Read without
    /// waiting (`try_lock`): the window's thread must never wait for the
    /// counting one, which on the web page is an error ("Atomics.wait
    /// cannot be called in this context"); a count being written shows
    /// on the next frame.
    pub(crate) fn summary(&self, name: &str) -> Option<String> {
        self.summaries.try_lock().ok()?.get(name).cloned().flatten()
    }

    /// Whether every bundled scene was counted (false while the counting
    /// thread writes, as [`Self::summary`] does not wait).
    pub(crate) fn is_complete(&self) -> bool {
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
pub(crate) fn scene_files(dir: &Path) -> Vec<PathBuf> {
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
pub(crate) fn is_scene_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("p3f") || e.eq_ignore_ascii_case("nff"))
        || tracer::scene::mesh_io::MeshFormat::of(path).is_some()
}

/// What the user picked in the list.
pub(crate) enum Picked {
    /// A scene to open as it is.
    Scene(SceneSource),
    /// A scene beside the page, to fetch first.
    Site(&'static SiteScene),
}

/// What the picker shows beside its list.
pub(crate) struct Shown<'a> {
    /// The scene open on side A.
    pub(crate) current: Option<&'a SceneSource>,
    pub(crate) recent: &'a [PathBuf],
    /// The scene being fetched from the page's site, and its progress.
    pub(crate) fetching: Option<(&'a str, &'a Transfer)>,
}

/// Draws the picker; returns the scene the user chose, if any.
pub(crate) fn show(
    ui: &mut Ui,
    list: &SceneList,
    shown: Shown<'_>,
    commands: &mut Vec<Command>,
) -> Option<Picked> {
    let Shown {
        current,
        recent,
        fetching,
    } = shown;
    let (catalog, disk_scenes) = (&list.catalog, &list.disk_scenes);
    let mut chosen = None;
    ui.heading("Scene");
    ui.horizontal(|ui| {
        command_button(ui, Command::Open, commands);
        command_button(ui, Command::Reload, commands);
        command_button(ui, Command::CopyLink, commands);
    });
    let current_label = current.map(SceneSource::label);
    egui::ScrollArea::vertical()
        .id_salt("scene_list")
        .max_height(220.0)
        .show(ui, |ui| {
            for offered in bundled::offered() {
                let (hover, picked, selected, side_note) = match offered {
                    Offered::Embedded(scene) => {
                        let source = SceneSource::Bundled(scene.name.to_string());
                        let selected = current == Some(&source);
                        let summary = catalog.summary(scene.name);
                        (scene.description, Picked::Scene(source), selected, summary)
                    }
                    Offered::Site(scene) => {
                        let url = scene.url();
                        let selected = current_label.as_ref() == Some(&url)
                            || fetching.is_some_and(|(fetched, _)| fetched == url);
                        let size = transfer::bytes(scene.size);
                        (scene.description, Picked::Site(scene), selected, Some(size))
                    }
                };
                let response = ui
                    .horizontal(|ui| {
                        let response = ui
                            .selectable_label(selected, offered.name())
                            .on_hover_text(hover);
                        if let Some(note) = side_note {
                            ui.weak(note);
                        }
                        response
                    })
                    .inner;
                if response.clicked() {
                    chosen = Some(picked);
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
                    chosen = Some(Picked::Scene(source));
                }
            }
        });
    if let Some((url, transfer)) = fetching {
        // Where the user looks after picking: under the list.
        let text = format!("fetching {url}: {}", transfer.describe());
        ui.add(egui::ProgressBar::new(transfer.fraction().unwrap_or(0.0)).text(text));
    }
    if let Some(description) = current.and_then(description_of) {
        // The first sentence; the whole line on hover.
        let first = description.split(';').next().unwrap_or_default();
        ui.label(RichText::new(first).small().weak())
            .on_hover_text(description);
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
                    chosen = Some(Picked::Scene(source));
                }
            }
        });
    }
    chosen
}

/// The description of scene `source` when it is one of `scenes/`:
/// embedded, or fetched from beside the page.
fn description_of(source: &SceneSource) -> Option<&'static str> {
    match source {
        SceneSource::Bundled(name) => bundled::find(name).map(|s| s.description),
        SceneSource::Written { name, .. } => bundled::site_scene_at(name).map(|s| s.description),
        SceneSource::File(_) => None,
    }
}
