//! What the window remembers across restarts (eframe persistence), kept
//! apart from runtime handles. Every field has a default, so an old or
//! partial saved state still loads.

use std::path::PathBuf;

use serde::{Deserialize, Serialize};
use tracer::accel::AccelKind;
use tracer::camera::CameraPose;
use tracer::render::{Encoding, RenderSettings};
use tracer::scene::Scene;

use crate::load::SceneSource;

/// The acceleration structure, as the window stores it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum AccelChoice {
    None,
    Grid,
    #[default]
    Bvh,
}

impl AccelChoice {
    pub const ALL: [AccelChoice; 3] = [AccelChoice::None, AccelChoice::Grid, AccelChoice::Bvh];

    pub fn label(self) -> &'static str {
        match self {
            AccelChoice::None => "None",
            AccelChoice::Grid => "Uniform grid",
            AccelChoice::Bvh => "BVH",
        }
    }
}

impl From<AccelChoice> for AccelKind {
    fn from(a: AccelChoice) -> Self {
        match a {
            AccelChoice::None => AccelKind::None,
            AccelChoice::Grid => AccelKind::Grid,
            AccelChoice::Bvh => AccelKind::Bvh,
        }
    }
}

impl From<AccelKind> for AccelChoice {
    fn from(a: AccelKind) -> Self {
        match a {
            AccelKind::None => AccelChoice::None,
            AccelKind::Grid => AccelChoice::Grid,
            AccelKind::Bvh => AccelChoice::Bvh,
        }
    }
}

/// Everything the side panel controls. Rendering settings restart the
/// render when they change; `srgb` only changes the display.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Controls {
    pub antialiasing: bool,
    /// N: N x N samples per pixel.
    pub samples: u32,
    pub soft_shadows: bool,
    pub light_size: f32,
    pub depth_of_field: bool,
    pub aperture: f32,
    pub focal: f32,
    pub accel: AccelChoice,
    /// The structure `g` switches back to when the grid is turned off.
    pub accel_without_grid: AccelChoice,
    pub grid_multiplier: f32,
    pub max_depth: u32,
    /// Image size as a fraction of the scene's resolution.
    pub resolution_scale: f32,
    pub ambient: f32,
    pub keep_refining: bool,
    pub srgb: bool,
}

impl Default for Controls {
    fn default() -> Self {
        let s = RenderSettings::default();
        Self {
            antialiasing: s.antialiasing,
            samples: s.samples,
            soft_shadows: s.soft_shadows,
            light_size: s.light_size,
            depth_of_field: s.depth_of_field,
            aperture: s.aperture,
            focal: s.focal,
            accel: s.accel.into(),
            accel_without_grid: AccelChoice::Bvh,
            grid_multiplier: s.grid_multiplier,
            max_depth: s.max_depth,
            resolution_scale: 1.0,
            ambient: s.ambient,
            keep_refining: s.keep_refining,
            srgb: false,
        }
    }
}

impl Controls {
    /// Adopts what a newly opened scene asks for (its `accel`, `spp`,
    /// `aperture` and `focal`, and a light size that suits its scale);
    /// everything else keeps the user's choice.
    pub fn adopt_scene(&mut self, scene: &Scene) {
        let s = RenderSettings::from_scene(scene);
        self.antialiasing = s.antialiasing;
        self.samples = s.samples;
        self.depth_of_field = s.depth_of_field;
        self.aperture = s.aperture;
        self.focal = s.focal;
        self.accel = s.accel.into();
        if self.accel != AccelChoice::Grid {
            self.accel_without_grid = self.accel;
        }
        self.light_size = s.light_size;
    }

    /// Turns the uniform grid on, or back to the previous structure.
    pub fn toggle_grid(&mut self) {
        if self.accel == AccelChoice::Grid {
            self.accel = self.accel_without_grid;
        } else {
            self.accel_without_grid = self.accel;
            self.accel = AccelChoice::Grid;
        }
    }

    /// Selects a structure from the acceleration choice.
    pub fn set_accel(&mut self, accel: AccelChoice) {
        self.accel = accel;
        if accel != AccelChoice::Grid {
            self.accel_without_grid = accel;
        }
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
    pub fn render_settings(
        &self,
        scene: &Scene,
        camera: Option<CameraPose>,
        preview: bool,
    ) -> RenderSettings {
        self.settings_over(RenderSettings::from_scene(scene), camera, preview)
    }

    /// [`Controls::render_settings`] over `base`, the scene's own settings.
    fn settings_over(
        &self,
        base: RenderSettings,
        camera: Option<CameraPose>,
        preview: bool,
    ) -> RenderSettings {
        let scale = if preview {
            self.resolution_scale * 0.25
        } else {
            self.resolution_scale
        };
        let size = |n: u32| ((n as f32 * scale).round() as u32).max(1);
        RenderSettings {
            width: size(base.width),
            height: size(base.height),
            max_depth: self.max_depth,
            ambient: self.ambient,
            antialiasing: self.antialiasing && !preview,
            samples: self.samples.max(1),
            soft_shadows: self.soft_shadows && !preview,
            light_size: self.light_size,
            depth_of_field: self.depth_of_field && !preview,
            aperture: self.aperture,
            focal: self.focal,
            accel: self.accel.into(),
            grid_multiplier: self.grid_multiplier,
            keep_refining: self.keep_refining && !preview,
            camera,
            ..base
        }
    }

    /// `change` applied to the render settings these controls make for a
    /// scene `scene_width` pixels wide, and the result taken back: so a
    /// setting is changed in one place (a study parameter's `apply`) for
    /// the command line and the window alike.
    pub fn change_settings(&mut self, scene_width: u32, change: impl FnOnce(&mut RenderSettings)) {
        let base = RenderSettings {
            width: scene_width.max(1),
            height: scene_width.max(1),
            ..RenderSettings::default()
        };
        let before = self.settings_over(base, None, false);
        let mut s = before.clone();
        change(&mut s);
        self.antialiasing = s.antialiasing;
        self.samples = s.samples;
        self.soft_shadows = s.soft_shadows;
        self.light_size = s.light_size;
        self.depth_of_field = s.depth_of_field;
        self.aperture = s.aperture;
        self.focal = s.focal;
        self.set_accel(s.accel.into());
        self.grid_multiplier = s.grid_multiplier;
        self.max_depth = s.max_depth;
        self.ambient = s.ambient;
        self.keep_refining = s.keep_refining;
        // Only a changed size moves the scale: the round trip through whole
        // pixels would otherwise nudge it.
        if s.width != before.width {
            self.resolution_scale = s.width as f32 / scene_width.max(1) as f32;
        }
    }
}

/// The window's persisted state.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Persisted {
    pub controls: Controls,
    pub last_scene: Option<SceneSource>,
    /// Files opened recently, newest first.
    pub recent: Vec<PathBuf>,
    pub show_stats: bool,
}

impl Default for Persisted {
    fn default() -> Self {
        Self {
            controls: Controls::default(),
            last_scene: None,
            recent: Vec::new(),
            show_stats: true,
        }
    }
}

/// How many recent files to remember.
const MAX_RECENT: usize = 8;

impl Persisted {
    /// Puts `path` first in the recent files.
    pub fn remember(&mut self, path: PathBuf) {
        self.recent.retain(|p| p != &path);
        self.recent.insert(0, path);
        self.recent.truncate(MAX_RECENT);
    }
}
