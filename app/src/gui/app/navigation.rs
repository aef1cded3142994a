//! Where the user looks from and at: the camera after orbit, pan and dolly
//! gestures (shared by both sides), the image's zoom and pan, and whether
//! the camera is moving, which makes the sides render previews.

use std::time::Duration;

use web_time::Instant;

use tracer::camera::CameraPose;
use tracer::scene::Scene;

use crate::gui::image::viewport::{Gesture, Placement, ViewportResponse, Zoom};

/// How long after the last wheel dolly the camera counts as moving.
const MOVE_SETTLE: Duration = Duration::from_millis(250);

/// The camera and the image's placement.
#[derive(Default)]
pub(crate) struct Navigation {
    /// The camera after the user moved it; `None` is the scene's own.
    pub(crate) camera: Option<CameraPose>,
    /// Zoom and pan of the image; never restarts the render.
    pub(crate) placement: Placement,
    dragging_camera: bool,
    moving_until: Option<Instant>,
    /// The image pixel under the cursor.
    pub(crate) hovered_pixel: Option<(u32, u32)>,
}

impl Navigation {
    /// Whether the camera moves: a drag under way, or a dolly just made.
    pub(crate) fn is_camera_moving(&self) -> bool {
        self.dragging_camera || self.moving_until.is_some_and(|t| Instant::now() < t)
    }

    /// Takes what happened over the image this frame: its gestures move
    /// the camera of `scene`.
    pub(crate) fn take(&mut self, response: &ViewportResponse, scene: Option<&Scene>) {
        self.dragging_camera = response.dragging_camera;
        self.hovered_pixel = response.hovered_pixel;
        let Some(scene) = scene else {
            return;
        };
        let mut pose = self.camera.unwrap_or_else(|| CameraPose::of(&scene.view));
        for gesture in &response.gestures {
            pose = match *gesture {
                Gesture::Orbit { yaw, pitch } => pose.orbit(yaw, pitch),
                Gesture::Pan { dx, dy } => pose.pan(dx, dy),
                Gesture::Dolly(factor) => {
                    self.moving_until = Some(Instant::now() + MOVE_SETTLE);
                    pose.dolly(factor)
                }
            };
        }
        if !response.gestures.is_empty() {
            self.camera = Some(pose);
        }
    }

    /// Asks for a frame when a dolly's preview is due to end.
    pub(crate) fn wake_when_settled(&mut self, ctx: &egui::Context) {
        if let Some(until) = self.moving_until {
            let now = Instant::now();
            if now < until {
                ctx.request_repaint_after(until - now);
            } else {
                self.moving_until = None;
            }
        }
    }

    /// A new scene: its own camera, the image fitted.
    pub(crate) fn reset(&mut self) {
        self.camera = None;
        self.placement = Placement::default();
    }

    /// The image scaled to fill the view.
    pub(crate) fn fit(&mut self) {
        self.placement = Placement::default();
    }

    /// One image pixel per screen pixel.
    pub(crate) fn actual_size(&mut self) {
        self.placement = Placement {
            zoom: Zoom::Scale(1.0),
            ..Placement::default()
        };
    }
}
