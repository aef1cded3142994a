//! The image view: fit or zoom with crisp pixels, pan, the pixel under the
//! cursor, and camera gestures that it reports to the app rather than acting
//! on itself.

use egui::{Color32, Pos2, Rect, Sense, TextureHandle, Vec2, pos2, vec2};

/// How the image is scaled.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Zoom {
    /// As large as the view allows.
    Fit,
    /// Screen pixels per image pixel.
    Scale(f32),
}

/// A camera gesture made over the image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Gesture {
    /// Left drag: turn around `at` (radians).
    Orbit { yaw: f32, pitch: f32 },
    /// Shift + left drag or middle drag: slide the camera (fractions of the
    /// distance to `at`).
    Pan { dx: f32, dy: f32 },
    /// Ctrl + wheel or pinch: move towards `at` (factor < 1) or away.
    Dolly(f32),
}

/// Zoom and pan of the view; never restarts the render.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Placement {
    pub(crate) zoom: Zoom,
    /// Offset of the image centre from the view centre, in points.
    pub(crate) offset: Vec2,
}

impl Default for Placement {
    fn default() -> Self {
        Self {
            zoom: Zoom::Fit,
            offset: Vec2::ZERO,
        }
    }
}

/// What happened over the image this frame.
#[derive(Debug, Default)]
pub(crate) struct ViewportResponse {
    pub(crate) gestures: Vec<Gesture>,
    /// True while a camera drag is in progress.
    pub(crate) dragging_camera: bool,
    /// The image pixel under the cursor, in the displayed image's pixels.
    pub(crate) hovered_pixel: Option<(u32, u32)>,
    /// Where the (first) image is drawn on screen, for overlays.
    pub(crate) image_rect: Option<Rect>,
}

impl ViewportResponse {
    /// What happened over either of two views showing the same camera.
    pub(crate) fn merge(mut self, other: ViewportResponse) -> ViewportResponse {
        self.gestures.extend(other.gestures);
        self.dragging_camera |= other.dragging_camera;
        self.hovered_pixel = self.hovered_pixel.or(other.hovered_pixel);
        self.image_rect = self.image_rect.or(other.image_rect);
        self
    }
}

/// The textures a view stacks, bottom first, each stretched over the image.
pub(crate) struct Layers<'a> {
    pub(crate) textures: Vec<&'a TextureHandle>,
    /// Whether together they cover the image with opaque pixels (no hole
    /// of a first pass shows through). Then the view's background is
    /// painted only around the image: on a software rasterizer every
    /// fragment of every frame costs, and under the image it was a third
    /// of a progress frame's (llvmpipe, 1280 x 820).
    pub(crate) opaque: bool,
}

/// A second image drawn right of a draggable divider (the compare mode's
/// split view).
pub(crate) struct SplitWith<'a> {
    pub(crate) texture: &'a TextureHandle,
    /// Where the divider is, as a fraction of the image width.
    pub(crate) at: &'a mut f32,
}

/// Shows `layers` (the top one an image of `image_size` pixels standing for
/// a render of `full_size`) in the available space, and `split`'s image
/// right of its divider.
pub(crate) fn show(
    ui: &mut egui::Ui,
    view: &mut Placement,
    layers: &Layers<'_>,
    split: Option<SplitWith<'_>>,
    image_size: [usize; 2],
    full_size: [u32; 2],
) -> ViewportResponse {
    show_named(ui, "Render", view, layers, split, image_size, full_size)
}

/// [`show`] for an image named `name` for screen readers (and for tests
/// that look for it): "Render", "Observer".
pub(crate) fn show_named(
    ui: &mut egui::Ui,
    name: &str,
    view: &mut Placement,
    layers: &Layers<'_>,
    split: Option<SplitWith<'_>>,
    image_size: [usize; 2],
    full_size: [u32; 2],
) -> ViewportResponse {
    let rect = ui.available_rect_before_wrap();
    let response = ui.allocate_rect(rect, Sense::click_and_drag());
    response.widget_info(|| egui::WidgetInfo::labeled(egui::accesskit::Role::Image, true, name));
    let mut out = ViewportResponse::default();

    // The displayed size follows the full-resolution render, so a preview
    // at a quarter of the resolution fills the same area.
    let full = vec2(full_size[0].max(1) as f32, full_size[1].max(1) as f32);
    let pixels_per_point = ui.ctx().pixels_per_point();
    let scale = match view.zoom {
        Zoom::Fit => (rect.width() / full.x)
            .min(rect.height() / full.y)
            .max(1e-3),
        Zoom::Scale(s) => s / pixels_per_point,
    };
    let image_rect = Rect::from_center_size(rect.center() + view.offset, full * scale);

    let background = if layers.opaque {
        margins(rect, image_rect)
    } else {
        vec![rect]
    };
    for area in background {
        ui.painter().rect_filled(area, 0.0, Color32::from_gray(24));
    }
    let whole = Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0));
    for texture in &layers.textures {
        ui.painter()
            .with_clip_rect(rect)
            .image(texture.id(), image_rect, whole, Color32::WHITE);
    }
    if let Some(split) = split {
        let x = image_rect.min.x + image_rect.width() * *split.at;
        let right = Rect::from_min_max(pos2(x, rect.min.y), rect.max);
        let painter = ui.painter().with_clip_rect(rect.intersect(right));
        painter.image(split.texture.id(), image_rect, whole, Color32::WHITE);
        let top = pos2(x, image_rect.min.y.max(rect.min.y));
        let bottom = pos2(x, image_rect.max.y.min(rect.max.y));
        ui.painter()
            .with_clip_rect(rect)
            .line_segment([top, bottom], (2.0, Color32::WHITE));
        // Created after the view's own response, so it wins the drag.
        let handle = Rect::from_min_max(top - vec2(6.0, 0.0), bottom + vec2(6.0, 0.0));
        let divider = ui
            .interact(handle, response.id.with("split"), Sense::drag())
            .on_hover_cursor(egui::CursorIcon::ResizeHorizontal);
        if divider.dragged()
            && let Some(p) = divider.interact_pointer_pos()
        {
            *split.at = ((p.x - image_rect.min.x) / image_rect.width().max(1.0)).clamp(0.0, 1.0);
        }
    }

    // Mouse wheel: zoom around the cursor; Ctrl + wheel: dolly.
    if response.hovered() {
        let (scroll, zoom_delta, modifiers) =
            ui.input(|i| (i.smooth_scroll_delta, i.zoom_delta(), i.modifiers));
        if zoom_delta != 1.0 {
            out.gestures.push(Gesture::Dolly(1.0 / zoom_delta));
        } else if scroll.y != 0.0 && !modifiers.any() {
            let factor = (scroll.y * 0.002).exp();
            let new_scale = (scale * factor).clamp(0.02, 64.0);
            if let Some(pointer) = response.hover_pos() {
                // Keep the image point under the cursor where it is.
                let from_centre = pointer - (rect.center() + view.offset);
                view.offset += from_centre - from_centre * (new_scale / scale);
            }
            view.zoom = Zoom::Scale(new_scale * pixels_per_point);
        }
    }

    // Drags: left orbits, shift+left or middle pans the camera, right pans
    // the view.
    let delta = response.drag_delta();
    let shift = ui.input(|i| i.modifiers.shift);
    if response.dragged_by(egui::PointerButton::Secondary) {
        view.offset += delta;
    } else if response.dragged_by(egui::PointerButton::Middle)
        || (response.dragged_by(egui::PointerButton::Primary) && shift)
    {
        out.dragging_camera = true;
        if delta != Vec2::ZERO {
            out.gestures.push(Gesture::Pan {
                dx: -delta.x / image_rect.width().max(1.0),
                dy: delta.y / image_rect.height().max(1.0),
            });
        }
    } else if response.dragged_by(egui::PointerButton::Primary) {
        out.dragging_camera = true;
        if delta != Vec2::ZERO {
            out.gestures.push(Gesture::Orbit {
                yaw: -delta.x * 0.01,
                pitch: delta.y * 0.01,
            });
        }
    }

    if let Some(pointer) = response.hover_pos() {
        out.hovered_pixel = pixel_at(pointer, image_rect, image_size);
    }
    out.image_rect = Some(image_rect);
    out
}

/// The parts of `rect` outside `inner`: bands above and below it, and
/// left and right of it between those (none where `inner` reaches or
/// passes an edge).
fn margins(rect: Rect, inner: Rect) -> Vec<Rect> {
    let inner = inner.intersect(rect);
    if !inner.is_positive() {
        return vec![rect];
    }
    let bands = [
        Rect::from_x_y_ranges(rect.x_range(), rect.min.y..=inner.min.y),
        Rect::from_x_y_ranges(rect.x_range(), inner.max.y..=rect.max.y),
        Rect::from_x_y_ranges(rect.min.x..=inner.min.x, inner.y_range()),
        Rect::from_x_y_ranges(inner.max.x..=rect.max.x, inner.y_range()),
    ];
    bands.into_iter().filter(|b| b.is_positive()).collect()
}

/// The image pixel at screen point `p`, for an image of `size` pixels drawn
/// in `image_rect`.
fn pixel_at(p: Pos2, image_rect: Rect, size: [usize; 2]) -> Option<(u32, u32)> {
    if !image_rect.contains(p) || size[0] == 0 || size[1] == 0 {
        return None;
    }
    let u = (p.x - image_rect.min.x) / image_rect.width();
    let v = (p.y - image_rect.min.y) / image_rect.height();
    let x = ((u * size[0] as f32) as usize).min(size[0] - 1);
    let y = ((v * size[1] as f32) as usize).min(size[1] - 1);
    Some((x as u32, y as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_under_the_cursor() {
        let r = Rect::from_min_size(pos2(10.0, 20.0), vec2(200.0, 100.0));
        assert_eq!(pixel_at(pos2(10.0, 20.0), r, [64, 32]), Some((0, 0)));
        assert_eq!(pixel_at(pos2(209.9, 119.9), r, [64, 32]), Some((63, 31)));
        assert_eq!(pixel_at(pos2(110.0, 70.0), r, [64, 32]), Some((32, 16)));
        assert_eq!(pixel_at(pos2(5.0, 70.0), r, [64, 32]), None);
    }

    /// Whether `parts` and `inner` tile `rect`: areas add up and no two
    /// overlap.
    fn tiles(rect: Rect, inner: Rect, parts: &[Rect]) -> bool {
        let area = |r: &Rect| r.area();
        let mut all = parts.to_vec();
        all.push(inner.intersect(rect));
        let sum: f32 = all.iter().map(area).sum();
        let disjoint = all
            .iter()
            .enumerate()
            .all(|(i, a)| all[i + 1..].iter().all(|b| !a.intersect(*b).is_positive()));
        (sum - rect.area()).abs() < 1e-3 && disjoint
    }

    #[test]
    fn the_background_is_painted_around_the_image_only() {
        let view = Rect::from_min_size(pos2(0.0, 0.0), vec2(800.0, 600.0));
        let centred = Rect::from_center_size(view.center(), vec2(600.0, 600.0));
        let parts = margins(view, centred);
        assert_eq!(parts.len(), 2, "left and right of a full-height image");
        assert!(tiles(view, centred, &parts));

        let inside = Rect::from_min_size(pos2(100.5, 50.25), vec2(300.0, 200.0));
        let parts = margins(view, inside);
        assert_eq!(parts.len(), 4);
        assert!(tiles(view, inside, &parts));

        // Zoomed in past the view: nothing around it.
        let zoomed = view.expand(50.0).translate(vec2(20.0, 0.0));
        assert!(margins(view, zoomed).is_empty());
        // Panned out of the view: all of it.
        let away = inside.translate(vec2(2000.0, 0.0));
        assert_eq!(margins(view, away), vec![view]);
    }
}
