//! Rendering: settings in, images and statistics out. A [`RenderJob`] runs
//! progressive passes in the background; [`render`] is the one-shot form,
//! the same passes run to completion, so both give the same bits.

mod film;
mod frame;
mod job;
mod ray_tree;
mod settings;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_aa;
#[cfg(test)]
mod tests_lens;
#[cfg(test)]
mod tests_shadows;
mod trace;
mod view;

use std::sync::Arc;

pub use film::{Film, Tile, rgba_to_rgb_image};
pub use frame::{Frame, TILE_SIZE};
pub use job::{JobOptions, JobState, PassObserver, RenderError, RenderJob, Snapshot};
pub use ray_tree::{Occluder, Outcome, RayNode, RayTree, SurfaceRecord};
pub use settings::{
    Encoding, MAX_DEPTH, MAX_GRID_MULTIPLIER, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES,
    RenderSettings, SettingsError,
};
pub use trace::{NoRecord, RayKind, ShadowSample, SurfaceHit, TraceRecorder, Tracer};
pub use view::{
    EyeHit, HEAT_PALETTE, HeatScale, NO_VALUE, View, ViewFilm, ViewHeatmap, ViewRecorder,
    ViewSample, ViewSummary, object_colour,
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
    let job = RenderJob::start(
        world,
        Some(index),
        settings,
        JobOptions {
            threads,
            ..JobOptions::default()
        },
    )?;
    let (film, stats, state) = job.wait();
    match state {
        JobState::Failed(message) => Err(RenderError::Panicked(message)),
        _ => Ok((film, stats)),
    }
}
