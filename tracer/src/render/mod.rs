//! Rendering: settings in, images and statistics out. A [`RenderJob`] runs
//! progressive passes in the background; [`render`] is the one-shot form,
//! the same passes run to completion, so both give the same bits.

pub mod adaptive;
mod control;
pub mod driver;
pub mod estimate;
mod film;
mod job;
mod outputs;
mod passes;
mod plan;
mod ray_tree;
mod settings;
mod slices;
pub mod strategy;
#[cfg(test)]
mod tests;
mod trace;
mod view;
pub mod vocabulary;

use std::sync::Arc;

pub use film::{Film, Tile, rgba_to_rgb_image};
pub use job::{Finished, JobOptions, JobState, RenderError, RenderJob, Snapshot};
pub use passes::PassListener;
pub(crate) use plan::PlannedSamples;
pub use plan::{RenderPlan, TILE_SIZE};
pub use ray_tree::{Occluder, Outcome, RayNode, RayTree, SurfaceRecord};
pub use settings::{
    AdaptiveSampling, Budget, Encoding, LensOverride, MAX_DEPTH, MAX_GRID_MULTIPLIER,
    MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES, RenderSettings, Sampling, SettingsError,
};
pub use slices::{run_slices, slices_pending};
pub use trace::{RayKind, ShadowSample, SurfaceHit, TraceRecorder, Tracer};
pub use view::{
    HEAT_PALETTE, HeatScale, NO_VALUE, View, ViewFilm, ViewHeatmap, ViewSummary, ViewTotals,
};

use crate::accel::SceneIndex;
use crate::stats::RenderStats;
use crate::world::World;

/// Renders the whole image and waits for it: the progressive passes run to
/// the target with `threads` workers (`None`: every core).
pub fn render(
    world: Arc<World>,
    index: Arc<SceneIndex>,
    settings: RenderSettings,
    threads: Option<usize>,
) -> Result<(Film, RenderStats), RenderError> {
    let (film, _, stats) = render_job(world, index, settings, threads, false)?;
    Ok((film, stats))
}

/// [`render`] that also measures the views (cost and what each pixel
/// saw): the same image, and its [`ViewFilm`].
pub fn render_with_views(
    world: Arc<World>,
    index: Arc<SceneIndex>,
    settings: RenderSettings,
    threads: Option<usize>,
) -> Result<(Film, ViewFilm, RenderStats), RenderError> {
    let (film, views, stats) = render_job(world, index, settings, threads, true)?;
    let views = views.ok_or_else(|| RenderError::Panicked("no views were measured".into()))?;
    Ok((film, views, stats))
}

fn render_job(
    world: Arc<World>,
    index: Arc<SceneIndex>,
    settings: RenderSettings,
    threads: Option<usize>,
    views: bool,
) -> Result<(Film, Option<ViewFilm>, RenderStats), RenderError> {
    let job = RenderJob::start(
        world,
        Some(index),
        settings,
        JobOptions {
            threads,
            views,
            ..JobOptions::default()
        },
    )?;
    let (film, views, stats, state) = job.wait_with_views();
    match state {
        JobState::Failed(message) => Err(RenderError::Panicked(message)),
        _ => Ok((film, views, stats)),
    }
}
