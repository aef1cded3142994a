//! What tests read and set beyond what a user sees or clicks, in one
//! place: the window's own code never calls these.

use std::path::{Path, PathBuf};
use std::time::Duration;

use tracer::render::Snapshot;
use tracer::scene::edit::{Edit, Effect};

use super::WorkbenchApp;
use super::saving::FileDialog;
use crate::gui::Clock;
use crate::gui::comparison::Comparison;
use crate::gui::editor::Editor;
use crate::gui::image::active_overlay::ActiveOverlay;
use crate::gui::image::pixel_views::PixelViews;
use crate::gui::image::structure_overlay::StructureOverlay;
use crate::gui::image::viewport::Zoom;
use crate::gui::lessons::Lessons;
use crate::gui::observer::Observer;
use crate::gui::sides::{Controls, Engine, Side};
use crate::gui::windows::benchmark::BenchWindow;
use crate::gui::windows::ray_tree::Inspector;
use crate::gui::windows::report::ReportExport;
use crate::gui::windows::studies::StudiesWindow;

impl WorkbenchApp {
    /// Side A's engine: what the renderer was asked.
    pub fn engine(&self) -> &Engine {
        &self.sides.a.engine
    }

    /// Side B, while comparing.
    pub fn side_b(&self) -> Option<&Side> {
        self.sides.b.as_ref()
    }

    /// Side A's controls.
    pub fn controls(&self) -> &Controls {
        &self.sides.a.controls
    }

    /// Side A's controls, as the side panel edits them.
    pub fn controls_mut(&mut self) -> &mut Controls {
        &mut self.sides.a.controls
    }

    /// The comparison, while comparing.
    pub fn comparison(&self) -> Option<&Comparison> {
        self.sides.b.as_ref().map(|_| &self.comparison)
    }

    /// The observer view.
    pub fn observer(&self) -> &Observer {
        &self.observer
    }

    /// The Lessons panel: the lesson, step, verdict and progress.
    pub fn lessons(&self) -> &Lessons {
        &self.lessons
    }

    /// The Lessons panel, as typing in it changes it.
    pub fn lessons_mut(&mut self) -> &mut Lessons {
        &mut self.lessons
    }

    /// The observer also draws the rays of row `y`'s pixels, as its
    /// panel's "More pixels" does.
    pub fn observer_pattern_row(&mut self, y: u32) {
        self.observer.pattern = Some(crate::figures::observer::PixelPattern::Row(y));
    }

    /// The per-pixel view the images show.
    pub fn views(&self) -> &PixelViews {
        &self.tools.views
    }

    /// The ray-tree inspector.
    pub fn inspector(&self) -> &Inspector {
        &self.tools.inspector
    }

    /// Pins `pixel` in the inspector, as a click on it does.
    pub fn inspect(&mut self, pixel: (u32, u32)) {
        self.tools.inspector.pin(pixel);
    }

    /// The structure overlay.
    pub fn overlay(&self) -> &StructureOverlay {
        &self.tools.overlay
    }

    /// The overlay of adaptive sampling's active pixels.
    pub fn active_overlay(&self) -> &ActiveOverlay {
        &self.tools.active
    }

    /// Export report...'s state: its progress and what it last did.
    pub fn report_export(&self) -> &ReportExport {
        &self.tools.report
    }

    /// Export report... with `path` chosen in its file dialog.
    pub fn export_report_to(&mut self, path: PathBuf) {
        self.tools.report.choose(path);
    }

    /// The benchmark matrix window.
    pub fn benchmark(&self) -> &BenchWindow {
        &self.tools.bench
    }

    /// The Studies window.
    pub fn studies(&self) -> &StudiesWindow {
        &self.tools.studies
    }

    /// The error shown in the window, if any.
    pub fn error(&self) -> Option<&str> {
        self.messages.error.as_deref()
    }

    /// Side A's render on screen, once there is one.
    pub fn shown(&self) -> Option<&Snapshot> {
        self.sides.a.image.shown()
    }

    /// Whether the screen shows side A's latest image (uploads are
    /// throttled, so it may lag a little behind).
    pub fn is_display_current(&self) -> bool {
        self.sides.a.image.is_current(&self.sides.a.engine)
    }

    /// Whether the scene list's counting has started.
    pub fn is_catalog_started(&self) -> bool {
        self.scene_list.catalog.is_started()
    }

    /// Whether the scene list has the object count of every bundled scene.
    pub fn is_catalog_complete(&self) -> bool {
        self.scene_list.catalog.is_complete()
    }

    /// The image's zoom: screen pixels per image pixel, `None` when it
    /// fits the view.
    pub fn zoom_scale(&self) -> Option<f32> {
        match self.navigation.placement.zoom {
            Zoom::Fit => None,
            Zoom::Scale(scale) => Some(scale),
        }
    }

    /// Answers the window's file dialogs (Open, Save PNG, Save EXR, Save
    /// scene) with `dialog` instead of the desktop's.
    pub fn answer_file_dialogs_with(&mut self, dialog: std::sync::Arc<dyn FileDialog>) {
        self.dialogs.dialog = dialog;
    }

    /// Counts the scene list at normal priority: a test waiting for the
    /// counts must not depend on an idle thread getting a core.
    pub fn count_scenes_at_normal_priority(&mut self) {
        self.scene_list.catalog.lowest_priority = false;
    }

    /// The clock the window times itself by (a test's stopped clock moves
    /// only when the test moves it).
    pub fn clock(&self) -> &Clock {
        &self.clock
    }

    /// How long after opening the scene list is counted even while the
    /// first render runs (3 s unless a test says otherwise).
    pub fn set_catalog_delay(&mut self, delay: Duration) {
        self.scene_list.delay = delay;
    }

    /// Side A's next renders pause themselves once `tiles` tiles are in:
    /// a first pass held half done, on any machine.
    pub fn pause_renders_after_tiles(&mut self, tiles: Option<u64>) {
        self.sides.a.engine.pause_after_tiles(tiles);
    }

    /// Files opened recently, newest first.
    pub fn recent_files(&self) -> &[PathBuf] {
        &self.session.recent
    }

    /// Shows or hides the statistics panel, as Tab does.
    pub fn set_statistics_shown(&mut self, shown: bool) {
        self.session.show_stats = shown;
    }

    /// Side B shows the image at `path`, as "Compare with image..." does
    /// with the file picked; an unreadable file is reported in the window.
    pub fn compare_with_image(&mut self, path: &Path) {
        if self.sides.b.is_some() {
            let encoding = self.sides.a.controls.encoding();
            self.comparison.open_reference(path, encoding);
        }
    }

    /// The scene editor: its selection and what waits on unsaved edits.
    pub fn editor(&self) -> &Editor {
        &self.tools.editor
    }

    /// The scene editor, as its window changes it.
    pub fn editor_mut(&mut self) -> &mut Editor {
        &mut self.tools.editor
    }

    /// Applies `edit` to the edited side's scene, as the editor window
    /// does with a field changed.
    pub fn edit(&mut self, edit: Edit) -> Result<Effect, String> {
        self.sides.active_mut().edit(edit)
    }

    /// Writes the edited side's scene to `path`, as Save scene does with
    /// the file picked.
    pub fn save_scene_to(&mut self, path: &Path) -> anyhow::Result<()> {
        let side = self.sides.editing;
        let (save, _) = self
            .scene_to_save(side)
            .ok_or_else(|| anyhow::anyhow!("no scene"))?;
        save.write(path)?;
        self.scene_saved(side, path, save.state);
        Ok(())
    }

    /// The window's title as last sent.
    pub fn title(&self) -> &str {
        &self.title
    }
}
