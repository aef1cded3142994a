//! The state a check is evaluated against: side A (and B in compare mode)
//! as scene and settings, the pinned pixel, the answer given. The window
//! builds it from its sides; `lesson check` builds it by applying a
//! lesson's actions. Either way the checks see the same thing.

use std::sync::Arc;

use anyhow::{Context, Result, anyhow};
use tracer::render::{RenderSettings, View};
use tracer::scene::Scene;
use tracer::world::World;

use crate::load::with_edits;

use super::actions::{Actions, Located, SettingsLine};

/// One side: its scene as edited, the world built from it, its settings.
#[derive(Debug, Clone)]
pub(crate) struct SideState {
    pub(crate) scene: Scene,
    pub(crate) world: Arc<World>,
    pub(crate) settings: RenderSettings,
}

/// Which side a check reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Which {
    #[default]
    A,
    B,
}

/// What the window shows, as far as a lesson sets it.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Layout {
    /// The image view (`None`: the shaded image).
    pub(crate) view: Option<View>,
    pub(crate) observer: bool,
}

/// Everything a check may look at.
#[derive(Debug, Clone)]
pub struct LessonState {
    pub(crate) a: SideState,
    /// Side B, in compare mode.
    pub(crate) b: Option<SideState>,
    /// The pinned pixel.
    pub(crate) pixel: Option<(u32, u32)>,
    /// The answer typed or picked for the current step.
    pub(crate) answer: Option<String>,
    pub(crate) layout: Layout,
}

impl LessonState {
    /// The lesson's scene with the settings it asks for, nothing pinned,
    /// no compare.
    pub(crate) fn new(scene: Scene, world: Arc<World>) -> Self {
        let settings = RenderSettings::from_scene(&scene);
        LessonState {
            a: SideState {
                scene,
                world,
                settings,
            },
            b: None,
            pixel: None,
            answer: None,
            layout: Layout::default(),
        }
    }

    /// Side `which`; an error naming compare mode when B is asked for
    /// without it.
    pub(crate) fn side(&self, which: Which) -> Result<&SideState, String> {
        match which {
            Which::A => Ok(&self.a),
            Which::B => self
                .b
                .as_ref()
                .ok_or_else(|| "compare mode is off: there is no side B".to_string()),
        }
    }

    /// Does what `actions` say: A's settings and edits, B from A with its
    /// flags, B's own edits, the pixel, the answer, the layout. An edit the
    /// scene refuses, or B's edits without compare mode, is an error naming
    /// the lesson file's line.
    pub(crate) fn apply(&mut self, actions: &Actions, file: &str) -> Result<()> {
        if let Some(flags) = &actions.settings {
            apply_flags(&mut self.a, flags, file)?;
        }
        edit_side(&mut self.a, &actions.edits, file)?;
        if let Some(flags) = &actions.compare {
            let mut b = self.a.clone();
            apply_flags(&mut b, flags, file)?;
            self.b = Some(b);
        }
        if let Some(first) = actions.compare_edits.first() {
            let Some(b) = &mut self.b else {
                return Err(anyhow!(
                    "{file}:{}:{}: `compare-edits` edits side B, but compare mode is off: \
                     add `compare` (for instance `compare = \"\"`)",
                    first.line,
                    first.column
                ));
            };
            edit_side(b, &actions.compare_edits, file)?;
        }
        if let Some(pixel) = actions.pixel {
            let settings = &self.a.settings;
            if pixel.0 >= settings.width || pixel.1 >= settings.height {
                return Err(anyhow!(
                    "{file}: pixel ({}, {}) is outside the {}x{} image",
                    pixel.0,
                    pixel.1,
                    settings.width,
                    settings.height
                ));
            }
            self.pixel = Some(pixel);
        }
        if let Some(answer) = &actions.answer {
            self.answer = Some(answer.clone());
        }
        if let Some(view) = actions.view {
            self.layout.view = (view != View::Shaded).then_some(view);
        }
        if let Some(observer) = actions.observer {
            self.layout.observer = observer;
        }
        Ok(())
    }
}

/// `lines` (`--set` edits, each from the lesson file) applied to `side`
/// in order; a refused one names its line.
fn edit_side(side: &mut SideState, lines: &[Located<String>], file: &str) -> Result<()> {
    for edit in lines {
        *side = edited(side, std::slice::from_ref(&edit.value))
            .with_context(|| format!("{file}:{}:{}", edit.line, edit.column))?;
    }
    Ok(())
}

/// `flags` over `side`: its settings, then its `--set` lines as edits.
fn apply_flags(side: &mut SideState, flags: &Located<SettingsLine>, file: &str) -> Result<()> {
    let at = || format!("{file}:{}:{}", flags.line, flags.column);
    flags.value.overrides.apply(&mut side.settings);
    side.settings
        .validate()
        .map_err(|e| anyhow!("{}: {e}", at()))?;
    if !flags.value.set.is_empty() {
        *side = edited(side, &flags.value.set).with_context(at)?;
    }
    Ok(())
}

/// `side` with `--set` edits applied to its scene, its world following.
/// An edit of the camera's lens is the lens the side renders with (the
/// user's override dropped, depth of field on when it is open), as in the
/// window.
fn edited(side: &SideState, lines: &[String]) -> Result<SideState> {
    let (scene, world, _) = with_edits(&side.scene, &side.world, lines)?;
    let mut settings = side.settings.clone();
    let (before, after) = (&side.scene.view, &scene.view);
    if before.lens() != after.lens() {
        settings.follow_scene_lens(after);
    }
    Ok(SideState {
        scene,
        world,
        settings,
    })
}
