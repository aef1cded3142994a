//! What the side panel edits for one side: the render settings as one
//! value, and the few choices that are the window's own (the image's scale
//! relative to the scene, the display's encoding, the structure `g`
//! returns to). Saved between sessions with side A.

use serde::{Deserialize, Serialize};
use tracer::accel::AccelKind;
use tracer::camera::CameraPose;
use tracer::render::{Encoding, RenderSettings};
use tracer::scene::Scene;

/// One side's controls. Rendering settings restart the render when they
/// change; `srgb` only changes the display.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Controls {
    /// The render settings the panel edits. Their size and camera are
    /// replaced when a frame is planned ([`Controls::render_settings`]):
    /// the scene's resolution times `resolution_scale`, the view's camera.
    pub render: RenderSettings,
    /// Image size as a fraction of the scene's resolution.
    pub resolution_scale: f32,
    /// Display and save with the sRGB curve instead of linear values.
    pub(crate) srgb: bool,
    /// The structure `g` switches back to when the grid is turned off.
    pub(crate) accel_without_grid: AccelKind,
}

impl Default for Controls {
    fn default() -> Self {
        Self {
            render: RenderSettings::default(),
            resolution_scale: 1.0,
            srgb: false,
            accel_without_grid: AccelKind::Bvh,
        }
    }
}

impl Controls {
    /// Adopts what a newly opened scene asks for (see
    /// [`RenderSettings::adopt_scene`]); everything else keeps the user's
    /// choice.
    pub(crate) fn adopt_scene(&mut self, scene: &Scene) {
        self.render.adopt_scene(scene);
        self.set_accel(self.render.accel);
    }

    /// Turns the uniform grid on, or back to the previous structure.
    pub(crate) fn toggle_grid(&mut self) {
        if self.render.accel == AccelKind::Grid {
            self.render.accel = self.accel_without_grid;
        } else {
            self.set_accel(AccelKind::Grid);
        }
    }

    /// Selects a structure, remembering it for [`Controls::toggle_grid`]
    /// unless it is the grid.
    pub(crate) fn set_accel(&mut self, accel: AccelKind) {
        if accel != AccelKind::Grid {
            self.accel_without_grid = accel;
        } else if self.render.accel != AccelKind::Grid {
            self.accel_without_grid = self.render.accel;
        }
        self.render.accel = accel;
    }

    pub fn encoding(&self) -> Encoding {
        if self.srgb {
            Encoding::Srgb
        } else {
            Encoding::Linear
        }
    }

    /// The render settings for `scene` seen from `camera`. A preview (while
    /// the camera moves) renders a quarter of the resolution with one
    /// sample per pixel, so the view follows the mouse.
    pub(crate) fn render_settings(
        &self,
        scene: &Scene,
        camera: Option<CameraPose>,
        preview: bool,
    ) -> RenderSettings {
        let scale = if preview {
            self.resolution_scale * 0.25
        } else {
            self.resolution_scale
        };
        let size = |n: u32| ((n as f32 * scale).round() as u32).max(1);
        let render = &self.render;
        RenderSettings {
            width: size(scene.view.width),
            height: size(scene.view.height),
            antialiasing: render.antialiasing && !preview,
            soft_shadows: render.soft_shadows && !preview,
            depth_of_field: render.depth_of_field && !preview,
            keep_refining: render.keep_refining && !preview,
            camera,
            ..render.clone()
        }
    }

    /// `change` applied to the render settings these controls make for a
    /// scene `scene_width` pixels wide: so a setting is changed in one
    /// place (a study parameter's `apply`) for the command line and the
    /// window alike. A changed width becomes the resolution scale.
    pub(crate) fn change_settings(
        &mut self,
        scene_width: u32,
        change: impl FnOnce(&mut RenderSettings),
    ) {
        let scene_width = scene_width.max(1);
        let width = ((scene_width as f32 * self.resolution_scale).round() as u32).max(1);
        let mut changed = RenderSettings {
            width,
            ..self.render.clone()
        };
        change(&mut changed);
        // Only a changed size moves the scale: the round trip through whole
        // pixels would otherwise nudge it.
        if changed.width != width {
            self.resolution_scale = changed.width as f32 / scene_width as f32;
        }
        let accel = changed.accel;
        self.render = changed;
        self.set_accel(accel);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(text: &str) -> Scene {
        tracer::scene::parse_scene(text, None, &tracer::scene::Limits::default()).unwrap()
    }

    #[test]
    fn a_scene_sets_what_it_asks_for_and_keeps_the_rest() {
        let mut controls = Controls {
            resolution_scale: 0.5,
            ..Controls::default()
        };
        controls.render.soft_shadows = true;
        controls.render.ambient = 0.3;
        let grid = scene("accel 1\nspp 3\nv\nfrom 0 0 5\nat 0 0 0\nresolution 40 20\ns 0 0 0 1\n");
        controls.adopt_scene(&grid);
        let s = controls.render_settings(&grid, None, false);
        assert_eq!((s.width, s.height), (20, 10));
        assert_eq!(
            (s.accel, s.antialiasing, s.samples),
            (AccelKind::Grid, true, 3)
        );
        assert!(
            s.soft_shadows && s.ambient == 0.3,
            "the user's choices stay"
        );
        // The grid's `g` goes back to the BVH, the default before it.
        controls.toggle_grid();
        assert_eq!(controls.render.accel, AccelKind::Bvh);
        let preview = controls.render_settings(&grid, None, true);
        assert_eq!((preview.width, preview.antialiasing), (5, false));
    }

    #[test]
    fn the_grid_key_returns_to_the_structure_before_it() {
        let mut controls = Controls::default();
        controls.set_accel(AccelKind::None);
        controls.toggle_grid();
        assert_eq!(controls.render.accel, AccelKind::Grid);
        controls.toggle_grid();
        assert_eq!(controls.render.accel, AccelKind::None);
        // Choosing the grid from the list remembers what it replaced.
        controls.set_accel(AccelKind::Grid);
        controls.toggle_grid();
        assert_eq!(controls.render.accel, AccelKind::None);
    }

    #[test]
    fn a_changed_width_becomes_the_scale_and_nothing_else_moves_it() {
        let mut controls = Controls {
            resolution_scale: 0.3719,
            ..Controls::default()
        };
        controls.change_settings(200, |s| s.grid_multiplier = 2.5);
        assert_eq!(controls.render.grid_multiplier, 2.5);
        assert_eq!(controls.resolution_scale, 0.3719);
        controls.change_settings(200, |s| s.width = 50);
        assert_eq!(controls.resolution_scale, 0.25);
        controls.change_settings(200, |s| s.accel = AccelKind::Grid);
        controls.toggle_grid();
        assert_eq!(controls.render.accel, AccelKind::Bvh);
    }
}
