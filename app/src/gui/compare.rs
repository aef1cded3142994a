//! Compare mode: a second settings set B renders the same scene from the
//! same camera beside A, shown side by side, split by a divider, flipped, or
//! as a difference heat map, with the numbers that say what B costs and
//! changes (time, rays, speed ratio, MSE, PSNR, FLIP). With a cost view
//! on, the difference and the numbers are of the view's values instead
//! (A - B signed; means, ratio, mean |A - B|). B may instead be an image
//! from disk ([`super::reference`]).

use std::sync::Arc;
use std::sync::mpsc::{Receiver, channel};

use egui::{Color32, ColorImage, RichText, TextureHandle, TextureOptions, Ui};
use image::RgbImage;
use tracer::camera::CameraPose;
use tracer::metrics::{self, Palette};
use tracer::render::{JobState, RenderSettings, Snapshot, View};

use crate::measure::compare::{Heatmap, Metrics, measure};
use crate::measure::describe::side_labels;
use crate::measure::value_difference::{ValueDifference, ValueStats, diverging_colour};
use crate::measure::view_image::format_number;

use super::engine::{Activity, Engine, LoadedScene, Version};
use super::live_image::LiveImage;
use super::reference::{PendingReference, ReferenceImage};
use super::state::Controls;
use super::view_select::colour_bar;

/// How the two renders are shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompareView {
    SideBySide,
    /// A left of a draggable divider, B right of it.
    Split,
    /// A, or B while the flip key is held.
    Flip,
    /// |A - B| as a heat map (A - B of the values with a view on).
    Difference,
}

impl CompareView {
    pub const ALL: [CompareView; 4] = [
        CompareView::SideBySide,
        CompareView::Split,
        CompareView::Flip,
        CompareView::Difference,
    ];

    pub fn label(self) -> &'static str {
        match self {
            CompareView::SideBySide => "Side by side",
            CompareView::Split => "Split",
            CompareView::Flip => "Flip",
            CompareView::Difference => "Difference",
        }
    }
}

/// The versions of A and B and the view a values' difference is of.
type ValuesKey = (Version, Version, View);

/// The B side and how the comparison is shown.
pub struct Compare {
    /// Renders B.
    pub engine: Engine,
    pub controls: Controls,
    pub image: LiveImage,
    pub view: CompareView,
    /// Divider of the split view, as a fraction of the image width.
    pub split: f32,
    /// Amplification of the difference heat map.
    pub gain: f32,
    /// Whether the side panel edits B (else A).
    pub editing_b: bool,
    difference: Option<TextureHandle>,
    /// What the difference map was made from: the images' versions, its
    /// gain, and the view whose values it shows (`None`: the images).
    difference_of: Option<(Version, Version, f32, Option<View>)>,
    /// The values' difference while a view is on, and what it is of.
    values: Option<(ValuesKey, ValueDifference)>,
    /// Metrics of the last pair of finished images, and the versions they
    /// belong to; FLIP runs on its own thread.
    metrics: Option<Result<Metrics, String>>,
    metrics_of: Option<(Version, Version)>,
    pending: Option<Receiver<Result<Metrics, String>>>,
    /// The image B shows instead of its render, when one was chosen.
    reference: Option<ReferenceImage>,
    /// Counts changes of the reference (or its fit), as B's version.
    reference_changes: u64,
    picking: Option<PendingReference>,
    /// Why the last image picked could not be read.
    picking_error: Option<String>,
}

impl Compare {
    /// B starts as a copy of A, on A's scene. `wake` and `wake_now` as for
    /// [`Engine::with_wakes`]: B's last pass shows at once, like A's.
    pub fn new(
        wake: Arc<dyn Fn() + Send + Sync>,
        wake_now: Arc<dyn Fn() + Send + Sync>,
        controls: &Controls,
        scene: Option<&LoadedScene>,
    ) -> Self {
        let mut engine = Engine::with_wakes(wake, wake_now);
        if let Some(scene) = scene {
            engine.show(scene.clone());
        }
        Self {
            engine,
            controls: controls.clone(),
            image: LiveImage::new("render B"),
            view: CompareView::SideBySide,
            split: 0.5,
            gain: 8.0,
            editing_b: true,
            difference: None,
            difference_of: None,
            values: None,
            metrics: None,
            metrics_of: None,
            pending: None,
            reference: None,
            reference_changes: 0,
            picking: None,
            picking_error: None,
        }
    }

    /// Makes `reference` side B (or a render again with `None`).
    pub fn set_reference(&mut self, reference: Option<ReferenceImage>) {
        self.reference = reference;
        self.reference_changes += 1;
        self.forget_results();
    }

    /// Makes the image at `path` side B; why it cannot be read shows under
    /// the reference controls.
    pub fn open_reference(&mut self, path: &std::path::Path, encoding: tracer::render::Encoding) {
        match ReferenceImage::open(path, encoding) {
            Ok(reference) => {
                self.picking_error = None;
                self.set_reference(Some(reference));
            }
            Err(message) => self.picking_error = Some(message),
        }
    }

    /// Whether the reference image is resized to A's size.
    pub fn set_fit(&mut self, fit: bool) {
        if let Some(reference) = &mut self.reference {
            reference.fit = fit;
            self.reference_changes += 1;
            self.forget_results();
        }
    }

    /// The image B shows instead of a render, if any.
    pub fn reference(&self) -> Option<&ReferenceImage> {
        self.reference.as_ref()
    }

    /// B's version: its render's, or the reference image's.
    fn b_version(&self) -> Version {
        match self.reference {
            Some(_) => (u64::MAX, self.reference_changes),
            None => self.engine.version(),
        }
    }

    /// B's textures at A's `size`, bottom first: the reference image, or
    /// B's render over its backdrop.
    pub fn b_layers(&mut self, ctx: &egui::Context, size: (u32, u32)) -> Vec<TextureHandle> {
        match &mut self.reference {
            Some(reference) => vec![reference.texture(ctx, size)],
            None => self.image.layers().textures.into_iter().cloned().collect(),
        }
    }

    /// Whether B's textures cover its image with opaque pixels: a finished
    /// first pass (or backdrop) of its render; a reference image may have
    /// transparent pixels of its own.
    pub fn b_is_opaque(&self) -> bool {
        self.reference.is_none() && self.image.is_opaque()
    }

    /// "Compare with image..." and, once B is an image, its fit and the way
    /// back to a render; `encoding` is A's, for EXR files.
    pub fn reference_controls(&mut self, ui: &mut Ui, encoding: tracer::render::Encoding) {
        if let Some(picking) = &self.picking
            && let Some(outcome) = picking.poll()
        {
            self.picking = None;
            self.picking_error = None;
            match outcome {
                Some(Ok(reference)) => self.set_reference(Some(reference)),
                Some(Err(message)) => self.picking_error = Some(message),
                None => {
                    self.picking_error = Some(
                        "no image picked (cancelled, or no file dialog on this desktop)".into(),
                    )
                }
            }
        }
        ui.horizontal(|ui| {
            let button = ui
                .add_enabled(
                    self.picking.is_none(),
                    egui::Button::new("Compare with image..."),
                )
                .on_hover_text(
                    "B shows a PNG, JPEG or EXR (another renderer's output) instead of a render",
                );
            if button.clicked() {
                self.picking = PendingReference::pick(encoding, ui.ctx().clone());
            }
            if let Some(reference) = &self.reference {
                let mut fit = reference.fit;
                let hint = "Resize the image to the render's size instead of refusing a mismatch";
                if ui
                    .checkbox(&mut fit, "Fit to A's size")
                    .on_hover_text(hint)
                    .changed()
                {
                    self.set_fit(fit);
                }
                if ui.button("Render B again").clicked() {
                    self.set_reference(None);
                }
            }
        });
        if let Some(error) = &self.picking_error {
            ui.colored_label(Color32::LIGHT_RED, error);
        }
    }

    /// A opened another scene: B follows.
    pub fn show_scene(&mut self, scene: &LoadedScene) {
        self.engine.show(scene.clone());
        self.image.forget();
        self.forget_results();
    }

    fn forget_results(&mut self) {
        self.metrics = None;
        self.metrics_of = None;
        self.pending = None;
        self.difference_of = None;
        self.values = None;
    }

    /// B's render settings, seen from the shared camera.
    pub fn settings(&self, camera: Option<CameraPose>, moving: bool) -> Option<RenderSettings> {
        let scene = self.engine.scene()?;
        Some(self.controls.render_settings(&scene.scene, camera, moving))
    }

    /// Keeps B rendering what its controls say (nothing while B is an
    /// image).
    pub fn sync(&mut self, camera: Option<CameraPose>, moving: bool) -> Result<(), String> {
        if self.reference.is_some() {
            return Ok(());
        }
        match self.settings(camera, moving) {
            Some(settings) => self.engine.render(&settings),
            None => Ok(()),
        }
    }

    /// Uploads B's image, and refreshes the difference map and the metrics
    /// when either side changed: of the values of `view` when it is a cost
    /// view (and B a render), else of the images.
    pub fn refresh(
        &mut self,
        ctx: &egui::Context,
        a: (&Engine, &LiveImage),
        interval: std::time::Duration,
        view: Option<View>,
    ) {
        self.image
            .refresh(ctx, &self.engine, self.controls.encoding(), interval);
        let (engine_a, image_a) = a;
        let versions = (engine_a.version(), self.b_version());
        let value_view = view.filter(|v| v.is_scalar() && self.reference.is_none());
        if let Some(view) = value_view {
            self.refresh_values(ctx, engine_a, (versions.0, versions.1, view));
            return;
        }
        self.values = None;
        if self.metrics_of.is_some_and(|of| of != versions) {
            // A side changed: the metrics no longer describe what is shown.
            self.metrics = None;
            self.metrics_of = None;
            self.pending = None;
        }
        if let Some(sa) = image_a.shown() {
            let b_done = self.reference.is_some()
                || (is_done(&self.engine) && self.image.is_current(&self.engine));
            let redraw_difference = self.view == CompareView::Difference
                && self.difference_of != Some((versions.0, versions.1, self.gain, None));
            let measure_now = b_done
                && is_done(engine_a)
                && image_a.is_current(engine_a)
                && self.metrics_of != Some(versions);
            if redraw_difference || measure_now {
                match self.b_image((sa.width, sa.height)) {
                    Some(Ok(sb)) => {
                        if redraw_difference && let Some(a) = rgb(sa) {
                            self.difference =
                                difference_texture(ctx, &a, &sb, self.gain, self.difference.take());
                            self.difference_of = Some((versions.0, versions.1, self.gain, None));
                        }
                        if measure_now {
                            self.metrics_of = Some(versions);
                            self.metrics = None;
                            self.pending =
                                rgb(sa).and_then(|a| measure_in_background(a, sb, ctx.clone()));
                        }
                    }
                    Some(Err(message)) => {
                        self.metrics_of = Some(versions);
                        self.metrics = Some(Err(message));
                    }
                    None => {}
                }
            }
        }
        if let Some(rx) = &self.pending
            && let Ok(result) = rx.try_recv()
        {
            self.metrics = Some(result);
            self.pending = None;
        }
    }

    /// The values' difference of `key`'s view, computed again when a side
    /// changed, and its map while the difference view shows. Image metrics
    /// of heat-map colours would mean nothing: none are computed.
    fn refresh_values(&mut self, ctx: &egui::Context, a: &Engine, key: ValuesKey) {
        self.metrics = None;
        self.metrics_of = None;
        self.pending = None;
        let (version_a, version_b, view) = key;
        if self.values.as_ref().is_none_or(|(of, _)| *of != key)
            && let (Some(a), Some(b)) = (a.view_values(view), self.engine.view_values(view))
        {
            self.values = ValueDifference::of(&a, &b).map(|d| (key, d));
        }
        let shown = (version_a, version_b, self.gain, Some(view));
        if self.view == CompareView::Difference
            && self.difference_of != Some(shown)
            && let Some((of, d)) = &self.values
            && *of == key
        {
            let size = a.settings().map(|s| [s.width as usize, s.height as usize]);
            // A's settings may already be of the next render's size.
            if let Some(size) = size.filter(|[w, h]| w * h == d.values.len()) {
                let image = ColorImage::from_rgba_unmultiplied(size, &d.rgba8());
                self.difference = Some(upload(ctx, image, self.difference.take()));
                self.difference_of = Some(shown);
            }
        }
    }

    /// The values' difference and statistics while a cost view is on.
    pub fn value_difference(&self) -> Option<(View, &ValueDifference)> {
        self.values.as_ref().map(|((_, _, view), d)| (*view, d))
    }

    /// B's image at A's `size`: the reference (or why it does not fit) or
    /// B's render.
    fn b_image(&mut self, size: (u32, u32)) -> Option<Result<RgbImage, String>> {
        match &mut self.reference {
            Some(reference) => Some(reference.at_size(size).clone().map(|r| r.image)),
            None => self.image.shown().and_then(rgb).map(Ok),
        }
    }

    /// The difference heat map, once made.
    pub fn difference(&self) -> Option<&TextureHandle> {
        self.difference.as_ref()
    }

    /// The image metrics of the finished pair, if computed.
    pub fn metrics(&self) -> Option<&Result<Metrics, String>> {
        self.metrics.as_ref()
    }

    /// Whether the metrics are being computed.
    pub fn is_measuring(&self) -> bool {
        self.pending.is_some()
    }
}

fn is_done(engine: &Engine) -> bool {
    engine.activity() == Activity::Job(JobState::Done)
}

fn rgb(snapshot: &Snapshot) -> Option<RgbImage> {
    snapshot.to_image()
}

/// MSE, PSNR and FLIP of the two images on a thread of their own (FLIP
/// takes a noticeable fraction of a second on a large image).
fn measure_in_background(
    a: RgbImage,
    b: RgbImage,
    ctx: egui::Context,
) -> Option<Receiver<Result<Metrics, String>>> {
    let (tx, rx) = channel();
    std::thread::Builder::new()
        .name("compare-metrics".into())
        .spawn(move || {
            let result = measure(&a, &b, Heatmap::Absolute)
                .map(|(metrics, _)| metrics)
                .map_err(|e| format!("{e:#}"));
            let _ = tx.send(result);
            ctx.request_repaint();
        })
        .ok()?;
    Some(rx)
}

/// |A - B| amplified by `gain`, as a texture (reusing `texture`).
fn difference_texture(
    ctx: &egui::Context,
    a: &RgbImage,
    b: &RgbImage,
    gain: f32,
    texture: Option<TextureHandle>,
) -> Option<TextureHandle> {
    let map = metrics::diff_heatmap(a, b, gain).ok()?;
    let image = ColorImage::from_rgb([map.width() as usize, map.height() as usize], map.as_raw());
    Some(upload(ctx, image, texture))
}

/// `image` as the difference texture (reusing `texture`).
fn upload(ctx: &egui::Context, image: ColorImage, texture: Option<TextureHandle>) -> TextureHandle {
    let options = TextureOptions::NEAREST;
    match texture {
        Some(mut texture) => {
            texture.set(image, options);
            texture
        }
        None => ctx.load_texture("difference", image, options),
    }
}

/// The labels of A and B: what differs, side by side.
pub fn labels(a: &RenderSettings, b: &RenderSettings) -> (String, String) {
    let (a, b) = side_labels(a, b);
    (format!("A: {a}"), format!("B: {b}"))
}

/// The numbers of both sides and their difference.
pub fn show_numbers(
    ui: &mut Ui,
    a: Option<&Snapshot>,
    compare: &Compare,
    labels: &(String, String),
) {
    // An image has no time or rays.
    let b = compare
        .image
        .shown()
        .filter(|_| compare.reference.is_none());
    egui::Grid::new("compare_numbers")
        .num_columns(3)
        .striped(true)
        .show(ui, |ui| {
            ui.label("");
            ui.strong("A");
            ui.strong("B");
            ui.end_row();
            let row = |ui: &mut Ui, name: &str, f: &dyn Fn(&Snapshot) -> String| {
                ui.label(name);
                ui.monospace(a.map_or_else(|| "–".into(), f));
                ui.monospace(b.map_or_else(|| "–".into(), f));
                ui.end_row();
            };
            row(ui, "Time", &|s| {
                format!("{:.3} s", s.stats.render_time.as_secs_f64())
            });
            row(ui, "Samples", &|s| {
                format!("{} / {}", s.stats.passes_done, s.stats.passes_target)
            });
            row(ui, "Rays", &|s| {
                crate::report::si(s.stats.counters.total_rays() as f64)
            });
            row(ui, "Rays per second", &|s| {
                crate::report::si(s.stats.rays_per_second())
            });
        });
    if let (Some(a), Some(b)) = (a, b) {
        let ratio = a.stats.render_time.as_secs_f64() / b.stats.render_time.as_secs_f64().max(1e-9);
        ui.label(format!(
            "Speed ratio A/B: {ratio:.2} (above 1: B is faster)"
        ));
    }
    ui.label(RichText::new(&labels.0).small());
    ui.label(RichText::new(&labels.1).small());
    ui.separator();
    if let Some((view, d)) = compare.value_difference() {
        show_value_stats(ui, view, &d.stats);
        return;
    }
    match compare.metrics() {
        Some(Ok(m)) => {
            egui::Grid::new("compare_metrics")
                .num_columns(2)
                .show(ui, |ui| {
                    ui.label("MSE");
                    ui.monospace(format!("{:.3}", m.mse));
                    ui.end_row();
                    ui.label("PSNR");
                    ui.monospace(if m.psnr.is_finite() {
                        format!("{:.2} dB", m.psnr)
                    } else {
                        "∞ (identical)".into()
                    });
                    ui.end_row();
                    ui.label("FLIP");
                    ui.monospace(format!("{:.4}", m.flip));
                    ui.end_row();
                });
        }
        Some(Err(e)) => {
            ui.colored_label(Color32::LIGHT_RED, e);
        }
        None if compare.is_measuring() => {
            ui.label("Measuring the difference…");
        }
        None => {
            ui.weak("MSE, PSNR and FLIP once both renders are done");
        }
    }
}

/// The view's statistics of both sides, in place of the image metrics.
fn show_value_stats(ui: &mut Ui, view: View, s: &ValueStats) {
    let unit = view.unit();
    let number = |v: f32| format!("{} {unit}", format_number(v));
    egui::Grid::new("compare_values")
        .num_columns(2)
        .show(ui, |ui| {
            let mut row = |name: &str, value: String| {
                ui.label(name);
                ui.monospace(value);
                ui.end_row();
            };
            row(&format!("Mean A ({})", view.name()), number(s.mean_a));
            row(&format!("Mean B ({})", view.name()), number(s.mean_b));
            row("Ratio A/B", format!("{:.3}", s.ratio));
            row("Mean |A − B|", number(s.mean_abs_difference));
            row("Max |A − B|", number(s.max_abs_difference));
        });
    ui.weak(format!(
        "over the {} pixels where both sides have a value",
        s.pixels
    ));
}

/// Under the difference view: the diverging legend of the values'
/// difference with its numbers, or the images' amplification and legend.
pub fn difference_controls(ui: &mut Ui, compare: &mut Compare) {
    if let Some((view, d)) = compare.value_difference() {
        let top = format!("{} {}", format_number(d.scale), view.unit());
        ui.horizontal(|ui| {
            ui.label(format!("−{top}"));
            colour_bar(ui, 160.0, 32, |t| diverging_colour(2.0 * t - 1.0));
            ui.label(format!("+{top}"));
            ui.weak("A − B: red where A is higher, blue where B is")
                .on_hover_text(format!(
                    "The difference of the {} values per pixel; the bar's ends are the \
                     99th percentile of |A − B|, larger differences take the end colours",
                    view.name()
                ));
        });
        return;
    }
    ui.horizontal(|ui| {
        ui.add(
            egui::Slider::new(&mut compare.gain, 1.0..=64.0)
                .logarithmic(true)
                .text("Amplification"),
        )
        .on_hover_text("Multiplies |A - B| before colouring, so small differences show");
        legend(ui, compare.gain);
    });
}

/// A colour bar from 0 to `1 / gain` of the full range, for the difference
/// view.
fn legend(ui: &mut Ui, gain: f32) {
    ui.label("0");
    colour_bar(ui, 160.0, 32, |t| Palette::Heat.colour(t).0);
    ui.label(format!("{:.0}+ levels", 255.0 / gain.max(1e-3)));
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use tracer::render::Encoding;

    use super::*;
    use crate::load::SceneSource;

    fn wait_until(mut done: impl FnMut() -> bool) {
        let start = Instant::now();
        while !done() {
            assert!(start.elapsed() < Duration::from_secs(120), "gave up");
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// A finished 32 x 24 render of a bundled scene, shown.
    fn rendered_a(ctx: &egui::Context) -> (Engine, LiveImage) {
        let mut engine = Engine::new(Arc::new(|| {}));
        engine.load(SceneSource::Bundled("balls_low".into()));
        wait_until(|| engine.poll_load().is_some());
        let settings = RenderSettings {
            width: 32,
            height: 24,
            ..RenderSettings::from_scene(&engine.scene().unwrap().scene)
        };
        engine.render(&settings).unwrap();
        wait_until(|| is_done(&engine));
        let mut image = LiveImage::new("A");
        image.refresh(ctx, &engine, Encoding::Linear, Duration::ZERO);
        assert!(image.is_current(&engine));
        (engine, image)
    }

    /// B as an image: the metrics are those of A against that image, and
    /// a size mismatch is reported until the image is fitted.
    #[test]
    fn a_reference_image_is_measured_against_a() {
        let ctx = egui::Context::default();
        let (engine_a, image_a) = rendered_a(&ctx);
        let a = image_a.shown().unwrap().to_image().unwrap();
        // A with every red value 20 levels brighter (where there is room).
        let mut reference = a.clone();
        for p in reference.pixels_mut() {
            p.0[0] = p.0[0].saturating_add(20);
        }
        let squared: f64 = a
            .pixels()
            .zip(reference.pixels())
            .map(|(p, q)| (f64::from(q.0[0]) - f64::from(p.0[0])).powi(2))
            .sum();
        let expected_mse = squared / (3.0 * f64::from(a.width() * a.height()));

        let mut compare =
            Compare::new(Arc::new(|| {}), Arc::new(|| {}), &Controls::default(), None);
        let measured = |compare: &mut Compare| {
            wait_until(|| {
                compare.refresh(&ctx, (&engine_a, &image_a), Duration::ZERO, None);
                compare.metrics().is_some()
            });
            compare.metrics().cloned().unwrap()
        };
        let image = ReferenceImage::new("reference.png".into(), reference);
        assert_eq!(image.label(), "B: image reference.png");
        compare.set_reference(Some(image));
        let m = measured(&mut compare).unwrap();
        assert!(
            (m.mse - expected_mse).abs() < 1e-9,
            "{} vs {expected_mse}",
            m.mse
        );
        assert!(m.flip > 0.0);
        assert_eq!(compare.b_layers(&ctx, (32, 24)).len(), 1);

        // Another size: refused with both sizes, then fitted on request.
        let small = image::imageops::resize(&a, 16, 12, image::imageops::FilterType::Nearest);
        compare.set_reference(Some(ReferenceImage::new("small.png".into(), small)));
        let error = measured(&mut compare).unwrap_err();
        assert!(error.contains("16x12 but the render is 32x24"), "{error}");
        compare.set_fit(true);
        assert!(measured(&mut compare).is_ok());

        // Back to a render: nothing to show for B until it renders.
        compare.set_reference(None);
        assert!(compare.reference().is_none() && compare.metrics().is_none());
    }
}
