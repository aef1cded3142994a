//! What is measured of the two sides: the difference map and MSE, PSNR
//! and FLIP of a finished pair (FLIP on a thread of its own), or with a
//! cost view on the difference of the view's values.

use std::sync::mpsc::{Receiver, channel};

use egui::{ColorImage, TextureHandle, TextureOptions};
use image::RgbImage;
use tracer::metrics;
use tracer::render::{JobState, Snapshot, View};

use crate::gui::platform::{target, waker};
use crate::measure::ab::{Heatmap, Metrics, measure};
use crate::measure::value_difference::ValueDifference;

use super::{CompareLayout, Comparison, ValuesKey};
use crate::gui::sides::{Activity, Engine, Side};

impl Comparison {
    /// Refreshes the difference map and the metrics when either side
    /// changed: of the values of `view` when it is a cost view (and B a
    /// render), else of the images. Call once the sides' images are
    /// uploaded.
    pub(crate) fn refresh(&mut self, ctx: &egui::Context, a: &Side, b: &Side, view: Option<View>) {
        let (engine_a, image_a) = (&a.engine, &a.image);
        let versions = (engine_a.version(), self.b_version(b));
        let value_view = view.filter(|v| v.is_scalar() && self.reference.is_none());
        if let Some(view) = value_view {
            self.refresh_values(ctx, engine_a, &b.engine, (versions.0, versions.1, view));
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
            let b_done =
                self.reference.is_some() || (is_done(&b.engine) && b.image.is_current(&b.engine));
            let redraw_difference = self.layout == CompareLayout::Difference
                && self.difference_of != Some((versions.0, versions.1, self.gain, None));
            let measure_now = b_done
                && is_done(engine_a)
                && image_a.is_current(engine_a)
                && self.metrics_of != Some(versions);
            if redraw_difference || measure_now {
                match self.b_image(b, (sa.width, sa.height)) {
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
                                rgb(sa).and_then(|a| measure_in_background(a, sb, waker(ctx)));
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
    fn refresh_values(&mut self, ctx: &egui::Context, a: &Engine, b: &Engine, key: ValuesKey) {
        self.metrics = None;
        self.metrics_of = None;
        self.pending = None;
        let (version_a, version_b, view) = key;
        if self.values.as_ref().is_none_or(|(of, _)| *of != key)
            && let (Some(a), Some(b)) = (a.view_values(view), b.view_values(view))
        {
            self.values = ValueDifference::of(&a, &b).map(|d| (key, d));
        }
        let shown = (version_a, version_b, self.gain, Some(view));
        if self.layout == CompareLayout::Difference
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

    /// B's image at A's `size`: the reference (or why it does not fit) or
    /// B's render.
    fn b_image(&mut self, b: &Side, size: (u32, u32)) -> Option<Result<RgbImage, String>> {
        match &mut self.reference {
            Some(reference) => Some(reference.at_size(size).clone().map(|r| r.image)),
            None => b.image.shown().and_then(rgb).map(Ok),
        }
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
    wake: impl Fn() + Send + 'static,
) -> Option<Receiver<Result<Metrics, String>>> {
    let (tx, rx) = channel();
    target::spawn("compare-metrics", move || {
        let result = measure(&a, &b, Heatmap::Absolute)
            .map(|(metrics, _)| metrics)
            .map_err(|e| format!("{e:#}"));
        let _ = tx.send(result);
        wake();
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

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use tracer::render::{Encoding, RenderSettings};

    use super::*;
    use crate::gui::comparison::ReferenceImage;
    use crate::gui::platform::clock::Clock;
    use crate::gui::platform::frame_meter::ProgressPace;
    use crate::gui::sides::{Controls, RepaintWakers, Sides};
    use crate::load::SceneSource;

    fn wait_until(done: impl FnMut() -> bool) {
        tracer::waiting::wait_until("the sides", done);
    }

    /// Sides whose A is a finished 32 x 24 render of a bundled scene,
    /// shown, and B on the same scene.
    fn rendered_a(ctx: &egui::Context) -> Sides {
        let mut sides = Sides::new(
            Controls::default(),
            RepaintWakers::of(ctx, &ProgressPace::default()),
            Clock::stopped(),
        );
        let a = &mut sides.a;
        a.engine.load(SceneSource::Bundled("balls_low".into()));
        wait_until(|| a.engine.poll_load().is_some());
        let settings = RenderSettings {
            width: 32,
            height: 24,
            ..RenderSettings::from_scene(&a.engine.scene().unwrap().scene)
        };
        a.engine.render(&settings).unwrap();
        wait_until(|| is_done(&a.engine));
        a.image
            .refresh(ctx, &a.engine, Encoding::Linear, Duration::ZERO);
        assert!(a.image.is_current(&a.engine));
        sides.toggle_b();
        sides
    }

    /// B as an image: the metrics are those of A against that image, and
    /// a size mismatch is reported until the image is fitted.
    #[test]
    fn a_reference_image_is_measured_against_a() {
        let ctx = egui::Context::default();
        let sides = rendered_a(&ctx);
        let (side_a, side_b) = (&sides.a, sides.b.as_ref().unwrap());
        let a = side_a.image.shown().unwrap().to_image().unwrap();
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

        let mut compare = Comparison::default();
        let measured = |compare: &mut Comparison| {
            wait_until(|| {
                compare.refresh(&ctx, side_a, side_b, None);
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
        assert_eq!(compare.b_layers(&ctx, side_b, (32, 24)).len(), 1);

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
