//! The two sides of the window: A always, B in compare mode. Both are the
//! same [`Side`] (an engine, the image on screen, the controls and this
//! frame's settings), so everything two-sided is written once over
//! [`Sides::each_mut`]. This is the window's interface to the renderer:
//! settings go into an engine, frames and statistics come out.

mod controls;
mod engine;
mod history;
mod live_image;

use std::sync::Arc;

use tracer::camera::CameraPose;
use tracer::render::{Budget, RenderSettings, Sampling, View, ViewHeatmap};
use tracer::scene::edit::{Edit, Effect};

pub use controls::Controls;
pub use engine::{Activity, Engine, Version, Wake};
pub(crate) use history::History;
pub(crate) use live_image::LiveImage;

use super::platform::clock::Clock;
use super::platform::frame_meter::ProgressPace;
use super::platform::{paced_waker, waker};
use crate::load::Loaded;

/// Which side.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SideId {
    A,
    B,
}

impl SideId {
    pub(crate) fn name(self) -> &'static str {
        match self {
            SideId::A => "A",
            SideId::B => "B",
        }
    }
}

/// How render threads wake the window: at the progress pace, or at once
/// for a render's last pass.
#[derive(Clone)]
pub(crate) struct RepaintWakers {
    paced: Wake,
    now: Wake,
}

impl RepaintWakers {
    /// An engine that wakes the window so.
    pub(crate) fn engine(&self) -> Engine {
        Engine::with_wakes(self.paced.clone(), self.now.clone())
    }

    /// Wakers that redraw `ctx` at `pace` (and at once for last passes).
    pub(crate) fn of(ctx: &egui::Context, pace: &ProgressPace) -> Self {
        Self {
            paced: Arc::new(paced_waker(ctx, pace)),
            now: Arc::new(waker(ctx)),
        }
    }
}

/// One side: what it renders with and what it shows.
pub struct Side {
    pub(crate) id: SideId,
    pub engine: Engine,
    pub(crate) image: LiveImage,
    pub controls: Controls,
    /// The edits of this side's scene.
    pub(crate) history: History,
    /// This frame's settings, made once per frame by [`Side::plan`].
    plan: Option<Plan>,
}

/// A side's render settings for one frame.
struct Plan {
    /// At full resolution: what the side is set to render.
    target: RenderSettings,
    /// What the engine renders now: the target, or its preview while the
    /// camera moves.
    rendered: RenderSettings,
}

impl Side {
    fn new(id: SideId, controls: Controls, wakes: &RepaintWakers, clock: &Clock) -> Self {
        Self {
            id,
            engine: wakes.engine(),
            image: LiveImage::new(match id {
                SideId::A => "render A",
                SideId::B => "render B",
            }),
            controls,
            history: History::new(clock.clone()),
            plan: None,
        }
    }

    /// Applies `edit` to this side's scene, renders again (keeping the
    /// structure unless the edit moved shapes, refitting it around shapes
    /// moved in place) and records it for undo.
    /// A refused edit changes nothing and says why.
    pub(crate) fn edit(&mut self, edit: Edit) -> Result<Effect, String> {
        let inverse = self.apply(&edit)?;
        self.history.push(edit.clone(), inverse);
        Ok(edit.kind())
    }

    /// Undoes the last step; `None` when there is none.
    pub(crate) fn undo(&mut self) -> Result<Option<Effect>, String> {
        let step = self.history.undo();
        self.replay(step, true)
    }

    /// Redoes the last undone step; `None` when there is none.
    pub(crate) fn redo(&mut self) -> Result<Option<Effect>, String> {
        let step = self.history.redo();
        self.replay(step, false)
    }

    /// Applies the `step` the history gave for an undo (or a redo), and
    /// tells the history when the scene refused it.
    fn replay(&mut self, step: Option<Edit>, undo: bool) -> Result<Option<Effect>, String> {
        let Some(edit) = step else {
            return Ok(None);
        };
        match self.apply(&edit) {
            Ok(_) => Ok(Some(edit.kind())),
            Err(why) => {
                self.history.refused(undo);
                Err(why)
            }
        }
    }

    /// `edit` on a copy of the scene and world, which then replace them;
    /// returns its inverse. An edit of the camera renders through the
    /// scene's lens again (the lens the scene's view owns, depth of field
    /// on when it is open), as the command line's `--set` does.
    fn apply(&mut self, edit: &Edit) -> Result<Edit, String> {
        let loaded = self.engine.scene().ok_or("there is no scene to edit")?;
        let mut scene = loaded.scene.clone();
        let inverse = edit.apply(&mut scene).map_err(|e| e.to_string())?;
        let mut world = (*loaded.world).clone();
        let shapes = world.update_shapes(&scene, edit);
        if edit.kind() == Effect::Camera {
            self.controls.render.follow_scene_lens(&scene.view);
        }
        // Field by field: `..loaded.clone()` would copy the whole scene
        // document a second time only to drop it.
        let edited = Loaded {
            source: loaded.source.clone(),
            scene,
            world: Arc::new(world),
            load_time: loaded.load_time,
        };
        self.engine.edit_scene(edited, shapes);
        Ok(inverse)
    }

    /// Makes this frame's settings from the controls, the scene and the
    /// shared `camera`, previews while the camera is `moving`.
    pub(crate) fn plan(&mut self, camera: Option<CameraPose>, moving: bool) {
        self.plan = self.engine.scene().map(|scene| Plan {
            target: self.controls.render_settings(&scene.scene, camera, false),
            rendered: self.controls.render_settings(&scene.scene, camera, moving),
        });
    }

    /// Switches the controls to adaptive sampling (with anti-aliasing
    /// unless depth of field spreads the samples), as compare mode's B
    /// at A's cost is.
    pub(crate) fn make_adaptive(&mut self) {
        let render = &mut self.controls.render;
        render.antialiasing |= !render.depth_of_field;
        render.sample_adaptively(|_| {});
    }

    /// Stops this frame's plan, when adaptive, at `budget` (the cost of
    /// A's finished render).
    pub(crate) fn limit(&mut self, budget: Budget) {
        let Some(plan) = &mut self.plan else {
            return;
        };
        for settings in [&mut plan.target, &mut plan.rendered] {
            if let Sampling::Adaptive(a) = &mut settings.sampling {
                a.budget = Some(budget);
            }
        }
    }

    /// The full-resolution settings of this frame, once there is a scene:
    /// what the labels, the benchmark matrix and the studies use.
    pub fn settings(&self) -> Option<&RenderSettings> {
        self.plan.as_ref().map(|p| &p.target)
    }

    /// Keeps the engine rendering this frame's settings (a new job only
    /// when they changed), measuring views when `views` is on.
    pub(crate) fn render(&mut self, views: bool) -> Result<(), String> {
        self.engine.set_views(views);
        match &self.plan {
            Some(plan) => self.engine.render(&plan.rendered),
            None => Ok(()),
        }
    }

    /// Throws the samples away and renders this frame's settings again.
    pub(crate) fn restart(&mut self) -> Result<(), String> {
        match &self.plan {
            Some(plan) => self.engine.restart(&plan.rendered),
            None => Ok(()),
        }
    }

    /// Uploads the engine's image at most every `interval`, as the shaded
    /// image or as `view`.
    pub(crate) fn refresh(
        &mut self,
        ctx: &egui::Context,
        interval: std::time::Duration,
        view: Option<(View, ViewHeatmap)>,
    ) {
        self.image.set_view(view);
        self.image
            .refresh(ctx, &self.engine, self.controls.encoding(), interval);
    }
}

/// Side A, side B while comparing, and which one the panel edits.
pub(crate) struct Sides {
    pub(crate) a: Side,
    pub(crate) b: Option<Side>,
    /// The side the panel and the feature keys change (B only while it
    /// exists).
    pub(crate) editing: SideId,
    /// Opening a scene adopts its settings; restoring the last session
    /// keeps the saved ones.
    pub(crate) adopt_loaded_scene: bool,
    wakes: RepaintWakers,
    /// Times the merging of edits into undo steps.
    clock: Clock,
}

impl Sides {
    /// Side A alone, with `controls`.
    pub(crate) fn new(controls: Controls, wakes: RepaintWakers, clock: Clock) -> Self {
        Self {
            a: Side::new(SideId::A, controls, &wakes, &clock),
            b: None,
            editing: SideId::A,
            adopt_loaded_scene: true,
            wakes,
            clock,
        }
    }

    /// A, then B while comparing.
    pub(crate) fn each(&self) -> impl Iterator<Item = &Side> {
        std::iter::once(&self.a).chain(&self.b)
    }

    /// A, then B while comparing.
    pub(crate) fn each_mut(&mut self) -> impl Iterator<Item = &mut Side> {
        std::iter::once(&mut self.a).chain(&mut self.b)
    }

    /// The side the panel edits.
    pub(crate) fn active(&self) -> &Side {
        match (&self.b, self.editing) {
            (Some(b), SideId::B) => b,
            _ => &self.a,
        }
    }

    /// The side the panel edits.
    pub(crate) fn active_mut(&mut self) -> &mut Side {
        match (&mut self.b, self.editing) {
            (Some(b), SideId::B) => b,
            _ => &mut self.a,
        }
    }

    /// Turns compare mode on (B starts as a copy of A's controls on A's
    /// scene, and is the side edited) or off.
    pub(crate) fn toggle_b(&mut self) {
        if self.b.take().is_some() {
            self.editing = SideId::A;
            return;
        }
        let mut b = Side::new(SideId::B, self.a.controls.clone(), &self.wakes, &self.clock);
        if let Some(scene) = self.a.engine.scene() {
            b.engine.show(scene.clone());
        }
        b.history = self.a.history.clone();
        b.engine.set_paused(self.a.engine.is_paused());
        self.b = Some(b);
        self.editing = SideId::B;
    }

    /// Exchanges A and B, renders and all, so nothing renders again; false
    /// without B.
    pub(crate) fn swap(&mut self) -> bool {
        let Some(b) = &mut self.b else {
            return false;
        };
        std::mem::swap(&mut self.a, b);
        (self.a.id, b.id) = (SideId::A, SideId::B);
        true
    }

    /// Gives B the controls of A, and A's scene with its edits; false
    /// without B.
    pub(crate) fn copy_a_to_b(&mut self) -> bool {
        let Some(b) = &mut self.b else {
            return false;
        };
        b.controls = self.a.controls.clone();
        if let Some(scene) = self.a.engine.scene() {
            b.engine.show(scene.clone());
        }
        b.history = self.a.history.clone();
        true
    }

    /// A opened `scene`: B shows it too, and neither has edits.
    pub(crate) fn follow_scene(&mut self, scene: &Loaded) {
        self.a.history.reset();
        if let Some(b) = &mut self.b {
            b.engine.show(scene.clone());
            b.image.forget();
            b.history.reset();
        }
    }
}
