//! The observer view: side A's scene seen from a free camera outside it,
//! rendered by its own engine (small, one sample, with per-pixel depth so
//! lines behind surfaces draw faint), with the scene camera, the lights,
//! the structure and the pinned pixels' rays drawn in 3D ([`paint`]).
//! Moving the observer never touches the sides' renders.

mod animation;
mod paint;

use std::sync::Arc;

use tracer::camera::{Camera, CameraPose};
use tracer::render::{JobState, RayTree, RenderSettings, View};
use tracer::world::World;

use crate::figures::observer::{self, PixelPattern, RayFilter};
use crate::figures::projection::DepthMap;
use crate::reports::ray_tree;

use super::image::viewport::{Gesture, Placement, ViewportResponse};
use super::sides::{Activity, Engine, LiveImage, RepaintWakers, Side, Version};

pub(crate) use animation::Animation;
pub(crate) use paint::paint;

/// Where the observer view goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ObserverLayout {
    /// Beside the camera's image.
    Beside,
    /// Instead of it.
    Instead,
}

/// Pixel patterns at most: a grid finer than this many pixels is thinned.
const MAX_PATTERN_PIXELS: usize = 256;

/// The observer's state.
pub struct Observer {
    pub on: bool,
    pub(crate) layout: ObserverLayout,
    /// Width of the observer's render in pixels; its height follows the
    /// view's shape.
    pub(crate) resolution: u32,
    /// More pixels whose rays are drawn beside the pinned one.
    pub(crate) pattern: Option<PixelPattern>,
    pub animation: Animation,
    /// Which recorded rays are drawn.
    pub filter: RayFilter,
    /// Fade each ray by its share of the pixel, so the rays that make the
    /// colour stand out.
    pub(crate) fade: bool,
    /// Zoom and pan of the observer's image.
    pub(crate) placement: Placement,
    /// `None` until framed on the scene (and after a reset).
    pose: Option<CameraPose>,
    engine: Engine,
    pub image: LiveImage,
    /// Height over width of the area the view last had.
    aspect: f32,
    dragging: bool,
    /// The settings the observer renders with, planned each frame.
    settings: Option<RenderSettings>,
    /// Distances of the observer's last finished render, and its version.
    depth: Option<(Version, CameraPose, DepthMap)>,
    /// The trees drawn, A's (side 0) and B's (side 1), and what they were
    /// recorded for.
    trees: Vec<(u8, RayTree)>,
    trees_of: Option<TreesKey>,
    /// Segments painted in the last frame, for tests and the panel.
    pub segments_drawn: usize,
}

/// What the trees were recorded for: each side's settings and world (its
/// address: an edit makes another), the pixels and the sample.
type TreesKey = (Vec<(RenderSettings, usize)>, Vec<(u32, u32)>, u32);

impl Observer {
    pub(crate) fn new(wakes: &RepaintWakers) -> Self {
        let mut engine = wakes.engine();
        // The observer renders in the time the sides leave: it never slows
        // the render it explains.
        engine.set_idle_priority(true);
        Self {
            on: false,
            layout: ObserverLayout::Beside,
            resolution: 400,
            pattern: None,
            animation: Animation::default(),
            filter: RayFilter::default(),
            fade: false,
            placement: Placement::default(),
            pose: None,
            engine,
            image: LiveImage::new("observer"),
            aspect: 0.75,
            dragging: false,
            settings: None,
            depth: None,
            trees: Vec::new(),
            trees_of: None,
            segments_drawn: 0,
        }
    }

    /// The observer's camera, once framed.
    pub fn pose(&self) -> Option<CameraPose> {
        self.pose
    }

    /// Back to the framing on the scene and its camera.
    pub(crate) fn reset_camera(&mut self) {
        self.pose = None;
        self.placement = Placement::default();
    }

    /// The observer's camera at its current pose and its render's size:
    /// what the figure is drawn and a press is read through, following a
    /// move before the image catches up.
    pub fn camera(&self, world: &World) -> Option<Camera> {
        let settings = RenderSettings {
            camera: Some(self.pose?),
            ..self.engine.settings()?.clone()
        };
        settings.render_camera(&world.view).ok()
    }

    /// The observer's engine (what it renders; picks read its pixels).
    pub fn engine(&self) -> &Engine {
        &self.engine
    }

    /// Keeps the observer rendering side A's scene from its camera, framed
    /// on first use; nothing while the view is off.
    pub(crate) fn sync(&mut self, a: &Side) -> Result<(), String> {
        if !self.on {
            return Ok(());
        }
        let Some(scene) = a.engine.scene() else {
            return Ok(());
        };
        let same_scene = self
            .engine
            .scene()
            .is_some_and(|s| Arc::ptr_eq(&s.world, &scene.world));
        if !same_scene {
            // An edit of the same file keeps where the observer stands.
            let same_file = self
                .engine
                .scene()
                .is_some_and(|s| s.source == scene.source);
            self.engine.show(scene.clone());
            self.depth = None;
            if !same_file {
                self.image.forget();
                self.pose = None;
            }
        }
        let Some(target) = a.settings() else {
            return Ok(());
        };
        let pose = match self.pose {
            Some(pose) => pose,
            None => {
                let camera = target
                    .render_camera(&scene.world.view)
                    .map_err(|e| e.to_string())?;
                *self.pose.insert(observer::framing(
                    &scene.world,
                    &camera,
                    scene.world.view.angle,
                    self.aspect,
                ))
            }
        };
        // A's structure serves when it is the one the observer's view is
        // traced with; otherwise the observer's engine keeps its own.
        if let Some(index) = a.engine.index()
            && index.matches(observer::VIEW_ACCEL, target.grid_multiplier)
        {
            self.engine.share_index(index);
        }
        let width = if self.dragging {
            (self.resolution / 2).max(32)
        } else {
            self.resolution.max(32)
        };
        let height = ((width as f32 * self.aspect).round() as u32).max(16);
        let settings = observer::render_settings(target, pose, width, height);
        self.engine.set_views(true);
        let moved = self.engine.settings().map(|s| s.camera) != Some(settings.camera);
        let result = if moved || self.may_render_beside(a) {
            self.engine.render(&settings)
        } else {
            Ok(())
        };
        self.settings = Some(settings);
        result
    }

    /// Whether the observer may render now beside side A's render: once A
    /// is done, or, while the observer shows nothing yet, once A's first
    /// pass is in. A move of the observer renders at once (the user asked
    /// for it); otherwise it waits, so it never slows the render it shows.
    fn may_render_beside(&self, a: &Side) -> bool {
        let engine = &a.engine;
        let rendering = matches!(
            engine.activity(),
            Activity::Job(JobState::Building | JobState::Rendering)
        ) && !engine.is_complete();
        if !rendering {
            return true;
        }
        self.image.shown().is_none() && a.image.shown().is_some_and(|s| s.stats.passes_done >= 1)
    }

    /// Uploads the observer's image at the progress pace, and keeps the
    /// distances of its finished render.
    pub(crate) fn refresh(&mut self, ctx: &egui::Context, a: &Side, interval: std::time::Duration) {
        if !self.on {
            return;
        }
        self.engine.collect_retired();
        self.image
            .refresh(ctx, &self.engine, a.controls.encoding(), interval);
        let done = self.engine.activity() == Activity::Job(JobState::Done);
        let version = self.engine.version();
        let (Some(settings), Some(pose)) = (self.engine.settings(), settings_pose(&self.engine))
        else {
            return;
        };
        if done && self.depth.as_ref().is_none_or(|(v, ..)| *v != version) {
            self.depth = self
                .engine
                .view_values(View::Distance)
                .and_then(|d| DepthMap::new(settings.width, settings.height, d))
                .map(|d| (version, pose, d));
        }
    }

    /// The depth map of a finished render from the current pose, if any:
    /// while the observer moves, lines are drawn without hiding.
    fn depth(&self) -> Option<&DepthMap> {
        let (_, pose, depth) = self.depth.as_ref()?;
        (Some(*pose) == self.pose).then_some(depth)
    }

    /// Takes what happened over the observer's image: gestures move its
    /// camera (never the sides'), and the area's shape sizes its render.
    pub(crate) fn take(&mut self, response: &ViewportResponse, area: egui::Rect) {
        self.dragging = response.dragging_camera;
        if area.width() > 1.0 {
            self.aspect = (area.height() / area.width()).clamp(0.2, 5.0);
        }
        let Some(mut pose) = self.pose else {
            return;
        };
        for gesture in &response.gestures {
            pose = match *gesture {
                Gesture::Orbit { yaw, pitch } => pose.orbit(yaw, pitch),
                Gesture::Pan { dx, dy } => pose.pan(dx, dy),
                Gesture::Dolly(factor) => pose.dolly(factor),
            };
        }
        self.pose = Some(pose);
    }

    /// Records the trees to draw: side A's (and B's) of the pinned pixel and
    /// the pattern's pixels, again when a side's settings or the pixels
    /// change. A tree takes microseconds, so this runs on the UI thread.
    pub(crate) fn record(&mut self, sides: &[&Side], pinned: Option<(u32, u32)>, sample: u32) {
        if !self.on {
            return;
        }
        let settings: Vec<(RenderSettings, usize)> = sides
            .iter()
            .filter_map(|s| {
                let world = Arc::as_ptr(&s.engine.scene()?.world) as usize;
                Some((s.engine.settings()?.clone(), world))
            })
            .collect();
        let mut pixels: Vec<(u32, u32)> = pinned.into_iter().collect();
        if let (Some(pattern), Some((first, _))) = (self.pattern, settings.first())
            && let Ok(more) = pattern.pixels(first.width, first.height)
        {
            let step = more.len().div_ceil(MAX_PATTERN_PIXELS).max(1);
            pixels.extend(
                more.into_iter()
                    .step_by(step)
                    .filter(|p| Some(*p) != pinned),
            );
        }
        let key = (settings, pixels, sample);
        if self.trees_of.as_ref() == Some(&key) {
            return;
        }
        self.trees.clear();
        for (side, engine_side) in sides.iter().enumerate() {
            let (Some(scene), Some(settings)) =
                (engine_side.engine.scene(), engine_side.engine.settings())
            else {
                continue;
            };
            for &pixel in &key.1 {
                if let Ok(tree) = ray_tree::inspect(
                    &scene.world,
                    engine_side.engine.index(),
                    settings,
                    pixel,
                    sample,
                ) {
                    self.trees.push((side as u8, tree));
                }
            }
        }
        self.trees_of = Some(key);
    }

    /// How many generations the animation runs through: every bounce of
    /// the trees drawn, then their shadow rays.
    pub fn phases(&self) -> u32 {
        self.trees
            .iter()
            .flat_map(|(_, t)| t.nodes.iter().map(|n| n.depth))
            .max()
            .map_or(1, |deepest| deepest + 2)
    }

    /// The trees drawn: (side, tree).
    pub fn trees(&self) -> &[(u8, RayTree)] {
        &self.trees
    }
}

/// The pose an engine renders from (its settings' camera).
fn settings_pose(engine: &Engine) -> Option<CameraPose> {
    engine.settings()?.camera
}
