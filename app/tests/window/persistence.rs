//! What the window remembers between sessions (eframe's storage, here in
//! memory): the controls, the last scene and the recent files; an older or
//! partial saved state loads what it has; a last scene deleted since opens
//! the bundled default with a notice instead of an empty window.

use std::collections::HashMap;
use std::path::PathBuf;
use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use tracer::accel::AccelKind;
use workbench::gui::WorkbenchApp;
use workbench::load::SceneSource;

use crate::harness::{WINDOW, wait_for, wait_for_scene, window};
use crate::support::scenes::spheres_on_a_floor;
use crate::support::{scratch, write};

/// eframe's storage as a map, as the native one is a file of such pairs.
#[derive(Default)]
pub struct MemoryStorage(HashMap<String, String>);

impl eframe::Storage for MemoryStorage {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0.get(key).cloned()
    }

    fn set_string(&mut self, key: &str, value: String) {
        self.0.insert(key.to_string(), value);
    }

    fn remove_string(&mut self, key: &str) {
        self.0.remove(key);
    }

    fn flush(&mut self) {}
}

/// The window as eframe starts it: with what `storage` holds, opening
/// `initial` (or, without one, what the storage says).
pub fn start(
    storage: Option<&MemoryStorage>,
    initial: Option<SceneSource>,
) -> Harness<'static, WorkbenchApp> {
    let storage = storage.map(|s| Box::new(MemoryStorage(s.0.clone())) as Box<dyn eframe::Storage>);
    window(Harness::builder().with_size(WINDOW), storage, initial)
}

/// What the engine of side A was last asked to render.
fn rendered(harness: &Harness<'static, WorkbenchApp>) -> tracer::render::RenderSettings {
    harness.state().engine().settings().cloned().unwrap()
}

#[test]
fn the_controls_the_last_scene_and_the_recent_files_survive_a_restart() {
    let dir = scratch("persist-restart");
    let small = spheres_on_a_floor(32, 24, "", "");
    let one = write(&dir, "one.p3f", &small);
    let two = write(&dir, "two.p3f", &small);
    let mut harness = start(None, Some(SceneSource::File(one.clone())));
    wait_for_scene(&mut harness);
    harness.state_mut().open(SceneSource::File(two.clone()));
    wait_for(&mut harness, "the second scene", |app| {
        app.engine()
            .scene()
            .is_some_and(|s| s.source == SceneSource::File(two.clone()))
    });
    wait_for_scene(&mut harness);
    // As a user sets them: anti-aliasing, soft shadows, the grid, the
    // statistics panel hidden.
    for key in [egui::Key::A, egui::Key::S, egui::Key::G, egui::Key::Tab] {
        harness.key_press(key);
        harness.run_steps(2);
    }
    let before = rendered(&harness);
    assert!(before.antialiasing && before.soft_shadows && before.accel == AccelKind::Grid);
    let mut storage = MemoryStorage::default();
    eframe::App::save(harness.state_mut(), &mut storage);

    let mut restarted = start(Some(&storage), None);
    wait_for_scene(&mut restarted);
    let app = restarted.state();
    assert_eq!(
        app.engine().scene().map(|s| s.source.clone()),
        Some(SceneSource::File(two.clone())),
        "the last scene opens"
    );
    let after = rendered(&restarted);
    assert_eq!(
        (after.antialiasing, after.soft_shadows, after.accel),
        (true, true, AccelKind::Grid),
        "the controls are the saved ones, not the scene's"
    );
    assert_eq!(app.recent_files(), [two, one]);
    assert!(
        restarted.query_by_label("Statistics").is_none(),
        "the statistics panel stays hidden"
    );
}

#[test]
fn an_older_saved_state_loads_what_it_has() {
    // The controls as the window saved them before they held the render
    // settings as one value: flat fields, some missing, one unknown.
    let mut storage = MemoryStorage::default();
    let saved = r#"(controls:(antialiasing:true,samples:3,accel:Grid,ambient:0.25,resolution_scale:0.125,gone:1),last_scene:Some(Bundled("balls_low")),recent:["/nowhere/old.p3f"])"#;
    eframe::Storage::set_string(&mut storage, eframe::APP_KEY, saved.into());
    let mut harness = start(Some(&storage), None);
    wait_for_scene(&mut harness);
    let settings = rendered(&harness);
    assert_eq!(
        (settings.antialiasing, settings.samples, settings.accel),
        (true, 3, AccelKind::Grid)
    );
    assert_eq!(settings.ambient, 0.25);
    assert_eq!(settings.width, 64, "balls_low at an eighth of 512");
    assert!(!settings.soft_shadows, "a missing field takes its default");
    assert_eq!(
        harness.state().recent_files(),
        [PathBuf::from("/nowhere/old.p3f")]
    );
    assert!(harness.query_by_label("Statistics").is_some());
}

#[test]
fn a_last_scene_deleted_since_opens_the_default_and_says_so() {
    let dir = scratch("persist-deleted");
    let gone = dir.join("gone.p3f");
    let mut storage = MemoryStorage::default();
    let saved = format!("(last_scene:Some(File({:?})))", gone.to_str().unwrap());
    eframe::Storage::set_string(&mut storage, eframe::APP_KEY, saved);
    let mut harness = start(Some(&storage), None);
    wait_for_scene(&mut harness);
    let shown = harness.state().engine().scene().map(|s| s.source.clone());
    assert_eq!(shown, Some(SceneSource::Bundled("showcase".into())));
    assert!(harness.state().error().is_none());
    let notice = format!("{} is gone", gone.display());
    assert!(
        harness.query_by_label_contains(&notice).is_some(),
        "a notice says why another scene opened"
    );
    // It fades after its five seconds, on the window's clock.
    harness.state().clock().advance(Duration::from_secs(4));
    harness.step();
    assert!(harness.query_by_label_contains(&notice).is_some());
    harness.state().clock().advance(Duration::from_secs(1));
    harness.step();
    assert!(harness.query_by_label_contains(&notice).is_none(), "faded");
}
