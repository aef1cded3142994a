//! The image area: banners, compare mode's header, the image (or both
//! sides as the comparison's layout shows them), what is drawn over it,
//! and the status line with the readout of the pixel under the cursor.

use egui::{Rect, Ui, pos2};
use tracer::render::JobState;
use tracer::scene::edit::Edit;

use super::banners;
use crate::gui::comparison::{CompareLayout, Comparison};
use crate::gui::image::viewport::{self, Layers, Placement, SplitWith, ViewportResponse};
use crate::gui::image::{pixel_views, ray_paths};
use crate::gui::observer::{self, Observer, ObserverLayout};
use crate::gui::sides::{Activity, Side, SideId, Sides};
use crate::gui::windows::ToolsAndOverlays;
use crate::reports::render_stats::sample_progress;

/// Hold it to see B in the compare mode's flip view.
const FLIP_KEY: egui::Key = egui::Key::X;
/// Height of the status line under the image.
const STATUS_HEIGHT: f32 = 22.0;

/// What the image area shows and edits.
pub(crate) struct CentralView<'a> {
    pub(crate) sides: &'a Sides,
    pub(crate) comparison: &'a mut Comparison,
    pub(crate) placement: &'a mut Placement,
    pub(crate) tools: &'a mut ToolsAndOverlays,
    pub(crate) error: &'a mut Option<String>,
    /// The camera moves: the status line says the image is a preview.
    pub(crate) moving: bool,
    pub(crate) observer: &'a mut Observer,
}

/// What the user did in the image area.
pub(crate) struct CentralOutcome {
    /// Gestures, hover and the camera drag over the image.
    pub(crate) viewport: ViewportResponse,
    /// Sides whose brute-force banner's "Switch to BVH" was clicked.
    pub(crate) switch_to_bvh: Vec<SideId>,
    /// Edits of side A dragged in the observer view.
    pub(crate) observer_edits: Vec<Edit>,
}

pub(crate) fn show(ui: &mut Ui, view: CentralView<'_>) -> CentralOutcome {
    let CentralView {
        sides,
        comparison,
        placement,
        tools,
        error,
        moving,
        observer,
    } = view;
    banners::error(ui, error);
    let switch_to_bvh = sides
        .each()
        .filter(|side| side.id == SideId::A || comparison.reference().is_none())
        .filter(|side| brute_force_banner(ui, side))
        .map(|side| side.id)
        .collect();
    let a = &sides.a;
    if let Some(b) = &sides.b {
        super::comparison::header(ui, comparison, a, b);
    }
    let size = a
        .image
        .shown()
        .map_or([0, 0], |s| [s.width as usize, s.height as usize]);
    let full = a.settings().map_or_else(
        || a.image.shown().map_or([1, 1], |s| [s.width, s.height]),
        |s| [s.width, s.height],
    );
    let mut area = ui.available_rect_before_wrap();
    area.max.y -= STATUS_HEIGHT;
    let (main_area, observer_area) = match (observer.on, observer.layout) {
        (false, _) => (Some(area), None),
        (true, ObserverLayout::Instead) => (None, Some(area)),
        (true, ObserverLayout::Beside) => {
            let middle = area.center().x;
            (
                Some(Rect::from_min_max(area.min, pos2(middle - 2.0, area.max.y))),
                Some(Rect::from_min_max(pos2(middle + 2.0, area.min.y), area.max)),
            )
        }
    };
    let flip_held = ui.input(|i| i.key_down(FLIP_KEY));
    let response = match main_area {
        Some(main_area) => {
            ui.scope_builder(egui::UiBuilder::new().max_rect(main_area), |ui| {
                let images = Images {
                    placement,
                    size,
                    full,
                };
                match &sides.b {
                    None => images.show(ui, &a.image.layers(), None),
                    Some(b) => images.compared(ui, comparison, a, b, flip_held),
                }
            })
            .inner
        }
        None => ViewportResponse::default(),
    };
    let observer_edits = match observer_area {
        Some(area) => {
            let edits_a = sides.editing == SideId::A;
            show_observer(ui, area, observer, a, tools, edits_a)
        }
        None => Vec::new(),
    };
    if let Some(rect) = response.image_rect {
        let (visits, step) = (tools.inspector.eye_visits(), tools.inspector.step);
        tools.overlay.paint(ui, &a.engine, rect, visits, step);
        tools.active.paint(ui, &a.engine, rect);
        tools.editor.paint_outline(ui, &sides.active().engine, rect);
        tools.inspector.paths_drawn = match tools.inspector.tree(0) {
            Some(Ok(tree)) => ray_paths::paint(ui, tree, &a.engine, rect),
            _ => 0,
        };
    }
    if let Some(pixel) = response.hovered_pixel
        && ui.input(|i| i.pointer.primary_clicked())
    {
        tools.inspector.pin(pixel);
        if tools.editor.open {
            tools.editor.pick_at = Some(pixel);
        }
    }
    // The hovered pixel's readout at the right, the status line in what is
    // left: each cut short with an ellipsis when the image area is narrow
    // (beside the Lessons panel) rather than drawn over the other.
    ui.horizontal(|ui| {
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            if let Some(readout) = pixel_readout(a, tools, response.hovered_pixel) {
                ui.add(egui::Label::new(egui::RichText::new(readout).monospace()).truncate());
            }
            ui.with_layout(egui::Layout::left_to_right(egui::Align::Center), |ui| {
                let status = status_line(a, moving || response.dragging_camera);
                ui.add(egui::Label::new(status).truncate());
            });
        });
    });
    CentralOutcome {
        viewport: response,
        switch_to_bvh,
        observer_edits,
    }
}

/// The observer's image in `area`, the figure over it, and its gestures
/// (which move the observer's camera, unless the editor takes them: then
/// they are edits of A, returned).
fn show_observer(
    ui: &mut Ui,
    area: Rect,
    observer: &mut Observer,
    a: &Side,
    tools: &mut ToolsAndOverlays,
    edits_a: bool,
) -> Vec<Edit> {
    let size = observer
        .image
        .shown()
        .map_or([0, 0], |s| [s.width as usize, s.height as usize]);
    let full = [size[0].max(1) as u32, size[1].max(1) as u32];
    let mut response = ui
        .scope_builder(egui::UiBuilder::new().max_rect(area), |ui| {
            let layers = observer.image.layers();
            let mut placement = observer.placement;
            let response =
                viewport::show_named(ui, "Observer", &mut placement, &layers, None, size, full);
            observer.placement = placement;
            response
        })
        .inner;
    let edits = tools
        .editor
        .observer_input(ui, &mut response, observer, a, edits_a);
    observer.take(&response, area);
    observer.segments_drawn = match response.image_rect {
        Some(rect) => {
            let painted =
                observer::paint(ui, rect, observer, a, &tools.overlay, tools.inspector.step);
            tools.editor.paint_in_observer(ui, observer, a, rect);
            painted
        }
        None => 0,
    };
    edits
}

/// The slow-render banner of a side that runs brute force over a large
/// scene; true when its button asks for the BVH.
fn brute_force_banner(ui: &mut Ui, side: &Side) -> bool {
    let (Some(scene), Some(settings)) = (side.engine.scene(), side.engine.settings()) else {
        return false;
    };
    let prefix = match side.id {
        SideId::A => "",
        SideId::B => "B: ",
    };
    banners::brute_force(ui, prefix, settings, &scene.world.counts)
}

/// The image (or images) in the available space: shown at `size` pixels
/// standing for a render of `full` pixels.
struct Images<'a> {
    placement: &'a mut Placement,
    size: [usize; 2],
    full: [u32; 2],
}

impl Images<'_> {
    fn show(
        self,
        ui: &mut Ui,
        layers: &Layers<'_>,
        split: Option<SplitWith<'_>>,
    ) -> ViewportResponse {
        viewport::show(ui, self.placement, layers, split, self.size, self.full)
    }

    /// A and B as the comparison's layout shows them.
    fn compared(
        self,
        ui: &mut Ui,
        comparison: &mut Comparison,
        a: &Side,
        b: &Side,
        flip_held: bool,
    ) -> ViewportResponse {
        let size = (self.size[0] as u32, self.size[1] as u32);
        let b_textures = comparison.b_layers(ui.ctx(), b, size);
        let b_layers = Layers {
            textures: b_textures.iter().collect(),
            opaque: comparison.b_is_opaque(b),
        };
        match comparison.layout {
            CompareLayout::SideBySide => {
                let half = egui::vec2(ui.available_width() / 2.0 - 2.0, ui.available_height());
                let (placement, size, full) = (self.placement, self.size, self.full);
                ui.horizontal(|ui| {
                    let left = ui
                        .allocate_ui(half, |ui| {
                            viewport::show(ui, placement, &a.image.layers(), None, size, full)
                        })
                        .inner;
                    let right = ui
                        .allocate_ui(half, |ui| {
                            viewport::show(ui, placement, &b_layers, None, size, full)
                        })
                        .inner;
                    left.merge(right)
                })
                .inner
            }
            CompareLayout::Split => {
                let split = b_textures.last().map(|texture| SplitWith {
                    texture,
                    at: &mut comparison.split,
                });
                self.show(ui, &a.image.layers(), split)
            }
            CompareLayout::Flip => {
                let layers = if flip_held {
                    b_layers
                } else {
                    a.image.layers()
                };
                self.show(ui, &layers, None)
            }
            CompareLayout::Difference => {
                // A heat map of every pixel: opaque.
                let textures: Vec<_> = comparison.difference().into_iter().collect();
                let difference = Layers {
                    opaque: !textures.is_empty(),
                    textures,
                };
                self.show(ui, &difference, None)
            }
        }
    }
}

/// "512 x 512 · 4 / 16 spp · 1.20 s · rendering" (adaptive: "pass 7 / 11,
/// 36.0 spp mean" in the middle).
fn status_line(a: &Side, moving: bool) -> String {
    let mut parts = Vec::new();
    if let Some(s) = a.image.shown() {
        parts.push(format!(
            "{} x {} · {} · {:.2} s",
            s.width,
            s.height,
            sample_progress(&s.stats),
            s.stats.render_time.as_secs_f64()
        ));
    }
    let engine = &a.engine;
    let state = match engine.activity() {
        Activity::Idle => "no scene".to_string(),
        Activity::Loading {
            name,
            fraction: None,
        } => format!("loading {name}…"),
        Activity::Loading {
            name,
            fraction: Some(f),
        } => format!("loading {name}… {:.0}%", f * 100.0),
        Activity::Job(_) if moving => "preview (camera moving)".into(),
        Activity::Job(JobState::Building) => "building acceleration structure…".into(),
        Activity::Job(JobState::Rendering) if engine.is_paused() => "paused".into(),
        Activity::Job(JobState::Rendering) => "rendering".into(),
        Activity::Job(JobState::Done) => "done".into(),
        Activity::Job(JobState::Cancelled) => "cancelled".into(),
        Activity::Job(JobState::Failed(e)) => format!("failed: {e}"),
    };
    parts.push(state);
    if engine.scene().is_some_and(|s| s.source.is_bare_mesh()) {
        parts.push(tracer::scene::mesh_io::FRAMING_NOTE.into());
    }
    parts.join(" · ")
}

/// The pixel under the cursor: its colour, or the view's raw value.
fn pixel_readout(
    a: &Side,
    tools: &ToolsAndOverlays,
    hovered: Option<(u32, u32)>,
) -> Option<String> {
    let (x, y) = hovered?;
    let s = a.image.shown()?;
    let i = (y as usize * s.width as usize + x as usize) * 4;
    let p = s.rgba.get(i..i + 4)?;
    Some(if p[3] == 0 {
        format!("({x}, {y}) not rendered yet")
    } else if let Some(value) = pixel_views::readout(&a.engine, tools.views.view, x, y) {
        format!("({x}, {y}) {value}")
    } else {
        format!("({x}, {y}) rgb {} {} {}", p[0], p[1], p[2])
    })
}
