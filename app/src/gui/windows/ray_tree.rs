//! The ray-tree inspector, docked under the image: click a pixel to pin it; its sample's
//! tree of rays is recorded again whenever the settings change, so a user
//! toggles soft shadows or the grid and watches the tree change. In compare
//! mode the same pixel is inspected on A and B.

use egui::Ui;
use tracer::accel::Visit;
use tracer::render::{RayTree, RenderSettings};

use crate::figures::overlay::VisitStep;
use crate::gui::sides::Side;
use crate::reports::ray_tree::{
    self, describe_node, describe_visit, headline, step_tally, triple, visits_heading,
};

/// The pinned pixel and its trees (A, and B while comparing).
#[derive(Default)]
pub struct Inspector {
    pub pinned: Option<(u32, u32)>,
    /// Which of the pixel's samples.
    pub(crate) sample: u32,
    trees: [Option<Inspected>; 2],
    /// Ray paths drawn over the image in the last frame.
    pub paths_drawn: usize,
    /// How far through side A's eye ray walk the structure overlay and the
    /// observer draw it; a new pixel's walk is shown at the same step.
    pub(crate) step: VisitStep,
}

/// A tree and what it was recorded for.
struct Inspected {
    /// The settings, the world (its address: an edit makes another), the
    /// pixel and the sample.
    of: (RenderSettings, usize, (u32, u32), u32),
    tree: Result<RayTree, String>,
    /// The scene's primitives: what brute force tests for every ray.
    primitives: usize,
}

impl Inspector {
    /// Pins `pixel`: the panel opens on its tree.
    pub(crate) fn pin(&mut self, pixel: (u32, u32)) {
        self.pinned = Some(pixel);
    }

    /// The recorded tree of side A (0) or B (1).
    pub fn tree(&self, side: usize) -> Option<&Result<RayTree, String>> {
        self.trees.get(side)?.as_ref().map(|t| &t.tree)
    }

    /// The cells or nodes side A's eye ray visited (empty without a tree),
    /// for the structure overlay.
    pub fn eye_visits(&self) -> &[Visit] {
        match self.tree(0) {
            Some(Ok(tree)) => &tree.eye_visits,
            _ => &[],
        }
    }

    /// Records the trees again for what changed: the pixel, the sample or
    /// a side's settings. Recording one sample takes microseconds, so it
    /// runs on the UI thread. A side's full-resolution settings, not its
    /// engine's: while the camera moves the engine renders a small
    /// preview, and the tree follows the camera at the pixel pinned.
    pub(crate) fn update(&mut self, a: &Side, b: Option<&Side>) {
        let Some(pixel) = self.pinned else {
            self.trees = [None, None];
            return;
        };
        for (index, side) in [Some(a), b].into_iter().enumerate() {
            let slot = &mut self.trees[index];
            let (Some(side), Some(settings), Some(scene)) = (
                side,
                side.and_then(Side::settings),
                side.and_then(|s| s.engine.scene()),
            ) else {
                *slot = None;
                continue;
            };
            let engine = &side.engine;
            let world = std::sync::Arc::as_ptr(&scene.world) as usize;
            let of = (settings.clone(), world, pixel, self.sample);
            if slot.as_ref().is_some_and(|s| s.of == of) {
                continue;
            }
            let tree =
                ray_tree::inspect(&scene.world, engine.index(), settings, pixel, self.sample)
                    .map_err(|e| format!("{e:#}"));
            let primitives = scene.world.shapes.len();
            *slot = Some(Inspected {
                of,
                tree,
                primitives,
            });
        }
    }

    /// The ray tree docked under the image while a pixel is pinned, so the
    /// image, the rays drawn over it, the tree and the observer show
    /// together; A's and B's trees side by side in compare mode.
    pub(crate) fn panel(&mut self, ui: &mut Ui, comparing: bool) {
        let Some((x, y)) = self.pinned else {
            return;
        };
        let mut close = false;
        egui::Panel::bottom("ray_tree")
            .resizable(true)
            .default_size(220.0)
            .show(ui, |ui| {
                ui.horizontal(|ui| {
                    ui.strong("Ray tree");
                    ui.label(format!("pixel ({x}, {y}), sample"));
                    ui.add(egui::DragValue::new(&mut self.sample).range(0..=4095));
                    ui.small("Click another pixel to inspect it; the tree follows every setting.");
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        close = ui.small_button("Close").clicked();
                    });
                });
                let sides = if comparing { 2 } else { 1 };
                ui.columns(sides, |columns| {
                    for (side, ui) in columns.iter_mut().enumerate() {
                        // Both ways: a long line scrolls inside its column
                        // instead of running over the other side's.
                        egui::ScrollArea::both()
                            .id_salt(("ray_tree", side))
                            .show(ui, |ui| {
                                if comparing {
                                    ui.strong(if side == 0 { "A" } else { "B" });
                                }
                                let step = (side == 0).then_some(&mut self.step);
                                match self.trees[side].as_ref().map(|t| (&t.tree, t.primitives)) {
                                    Some((Ok(tree), primitives)) => {
                                        show_tree(ui, tree, side, step, primitives)
                                    }
                                    Some((Err(e), _)) => {
                                        ui.colored_label(ui.visuals().error_fg_color, e);
                                    }
                                    None => {
                                        ui.label("waiting for the scene");
                                    }
                                }
                            });
                    }
                });
            });
        if close {
            self.pinned = None;
        }
    }
}

/// The tree as collapsible lines, children under their parents; hovering a
/// line shows the ray's origin, direction and weight. With a `step` (side
/// A's), the eye ray's walk can be stepped through, what it tested so far
/// beside brute force's `primitives`, the step's visit in bold in the list.
fn show_tree(
    ui: &mut Ui,
    tree: &RayTree,
    side: usize,
    step: Option<&mut VisitStep>,
    primitives: usize,
) {
    ui.label(headline(tree));
    for root in tree.children(None) {
        show_node(ui, tree, root, side);
    }
    let visits = &tree.eye_visits;
    let mut current = None;
    if let Some(step) = step
        && !visits.is_empty()
    {
        step_controls(ui, step, visits.len());
        ui.label(step_tally(tree, *step, primitives));
        current = step.current(visits.len());
    }
    egui::CollapsingHeader::new(visits_heading(visits))
        .id_salt(("visits", side))
        .show(ui, |ui| {
            ui.small("Drawn over the image with the structure overlay, yellow first, red last.");
            for (i, visit) in visits.iter().enumerate() {
                let line = describe_visit(visit);
                if current == Some(i) {
                    ui.strong(line);
                } else {
                    ui.label(line);
                }
            }
        });
}

/// All, or a step through the `n` visits: Home, back, next, End (named
/// apart from the Lessons panel's Back and Next).
fn step_controls(ui: &mut Ui, step: &mut VisitStep, n: usize) {
    let current = step.current(n);
    ui.horizontal(|ui| {
        ui.label("Walk:");
        if ui.selectable_label(current.is_none(), "All").clicked() {
            *step = VisitStep::All;
        }
        let not_first = current != Some(0);
        let not_last = current != Some(n - 1);
        if ui
            .add_enabled(not_first, egui::Button::new("Home"))
            .clicked()
        {
            *step = VisitStep::At(0);
        }
        if ui
            .add_enabled(not_first, egui::Button::new("Previous visit"))
            .clicked()
        {
            *step = step.back(n);
        }
        if ui
            .add_enabled(not_last, egui::Button::new("Next visit"))
            .clicked()
        {
            *step = step.next(n);
        }
        if ui.add_enabled(not_last, egui::Button::new("End")).clicked() {
            *step = VisitStep::At(n - 1);
        }
        ui.label(match step.current(n) {
            None => format!("all {n} visits"),
            Some(k) => format!("step {} of {n}", k + 1),
        })
        .on_hover_text(
            "The structure overlay and the observer draw the walk up to this visit, it in white.",
        );
    });
}

fn show_node(ui: &mut Ui, tree: &RayTree, index: usize, side: usize) {
    let node = &tree.nodes[index];
    let line = describe_node(node);
    let details = format!(
        "origin {}\ndirection {}\nweight {}\nradiance {}",
        triple(node.origin),
        triple(node.dir),
        triple(node.weight),
        triple(node.radiance)
    );
    let mut children = tree.children(Some(index)).peekable();
    if children.peek().is_none() {
        ui.label(line).on_hover_text(details);
        return;
    }
    egui::CollapsingHeader::new(line)
        .id_salt(("ray", side, index))
        .default_open(true)
        .show(ui, |ui| {
            for child in children {
                show_node(ui, tree, child, side);
            }
        })
        .header_response
        .on_hover_text(details);
}
