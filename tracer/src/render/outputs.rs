//! What a render records, pass by pass: the film, the views when asked
//! for, and the finished image's bytes when asked for; and what a tile
//! rendered in one pass, as it is recorded. Views and image-only output
//! are choices of what is recorded, not of how the loop runs.

use glam::Vec3A;

use crate::stats::{AdaptiveStats, Counters, RenderStats};

use super::film::encode_values;
use super::strategy::{SamplingStrategy, TileSamples};
use super::view::{ViewFilm, ViewSample};
use super::{Encoding, Film, PlannedSamples, RenderPlan, RenderSettings, Tile};

/// What a job has made so far, behind the job's one lock.
pub(super) struct Outputs {
    pub film: Film,
    pub views: Option<ViewFilm>,
    /// The finished image's encoding and bytes, row-major RGB
    /// ([`super::JobOptions::finished_image`]).
    pub finished: Option<(Encoding, Vec<u8>)>,
    pub stats: RenderStats,
}

/// Which outputs a render records.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Recording {
    /// Measure the views (what each sample cost and saw).
    pub views: bool,
    /// Make the finished image's 8-bit RGB in this encoding.
    pub finished_image: Option<Encoding>,
    /// Only the finished image: tiles' values go straight into it and the
    /// film gets no sample (see [`super::JobOptions::image_only`]).
    pub image_only: bool,
}

impl Outputs {
    /// Nothing recorded yet, sized for `settings`, with the film
    /// `strategy` reads.
    pub(super) fn new(
        settings: &RenderSettings,
        strategy: &dyn SamplingStrategy,
        recording: Recording,
    ) -> Self {
        let (width, height) = (settings.width, settings.height);
        let pixels = width as usize * height as usize;
        Self {
            film: strategy.film(width, height),
            views: recording.views.then(|| ViewFilm::new(width, height)),
            finished: recording
                .finished_image
                .map(|encoding| (encoding, vec![0; pixels * 3])),
            stats: RenderStats {
                width,
                height,
                passes_target: strategy.passes_target(),
                // Every pixel active, nothing known yet: a viewer lays
                // its rows out once, from the start.
                adaptive: settings.adaptive().map(|_| AdaptiveStats {
                    pixels: pixels as u64,
                    active_pixels: pixels as u64,
                    error: f32::INFINITY,
                    ..AdaptiveStats::default()
                }),
                ..RenderStats::default()
            },
        }
    }

    /// Writes the outputs' zeros into their pages before the first tile
    /// (see [`Film::prefault`]): done while the structure builds.
    pub(super) fn prefault(&mut self, recording: Recording) {
        if !recording.image_only {
            self.film.prefault();
        }
        if let Some((_, bytes)) = &mut self.finished {
            bytes.fill(0);
        }
    }

    /// Records what `tile` rendered in a pass: into the film (or straight
    /// into the finished image with `image_only`), the views, and, when
    /// the pass `may_be_last` for the tile, the finished image's bytes.
    pub(super) fn record(&mut self, tile: &Tile, batch: TileBatch, may_be_last: bool) {
        let width = self.film.width();
        match (batch.bytes, &mut self.finished) {
            (Some(bytes), Some((_, image))) => tile.copy_rgb_into(width, &bytes, image),
            _ => {
                match &batch.counts {
                    Counts::One => self.film.add_tile(tile, &batch.values),
                    Counts::Each(counts) => {
                        self.film
                            .add_samples(tile, counts, &batch.values, &batch.tests)
                    }
                }
                if let (true, Some((encoding, bytes))) = (may_be_last, &mut self.finished) {
                    self.film.resolve_tile(tile, *encoding, bytes);
                }
            }
        }
        if let (Some(film), Some(views)) = (&mut self.views, &batch.views) {
            match &batch.counts {
                Counts::One => film.add_tile(tile, views),
                Counts::Each(counts) => film.add_samples(tile, counts, views),
            }
        }
        self.stats.counters += batch.counters;
    }
}

/// How many samples each pixel of a tile took in a pass.
pub(super) enum Counts {
    /// One each.
    One,
    /// `counts[i]` for pixel `i` (row-major).
    Each(Vec<u32>),
}

/// What a tile rendered in one pass, ready to record.
pub(super) struct TileBatch {
    pub counts: Counts,
    /// The samples' values, pixel after pixel.
    pub values: Vec<Vec3A>,
    /// Each pixel's intersection tests ([`Counts::Each`] only).
    pub tests: Vec<u64>,
    pub views: Option<Vec<ViewSample>>,
    /// With image-only output, the values as the finished image's bytes,
    /// made before the lock is taken: only their copy waits for the other
    /// threads.
    pub bytes: Option<Vec<u8>>,
    pub counters: Counters,
}

impl TileBatch {
    /// Renders `samples` of `tile` on `plan`, recording what `recording`
    /// asks for (image-only bytes only for one sample a pixel).
    pub(super) fn render(
        plan: &RenderPlan,
        tile: &Tile,
        samples: TileSamples,
        recording: Recording,
    ) -> Self {
        let mut counters = Counters::default();
        let mut batch = match samples {
            TileSamples::Every(n) if recording.views => {
                let (values, views) = plan.render_tile_with_views(n, tile, &mut counters);
                Self::one_each(values, Some(views))
            }
            TileSamples::Every(n) => Self::one_each(plan.render_tile(n, tile, &mut counters), None),
            TileSamples::Each(ranges) => {
                let PlannedSamples {
                    values,
                    tests,
                    views,
                } = plan.render_samples(tile, &ranges, recording.views, &mut counters);
                Self {
                    counts: Counts::Each(ranges.iter().map(|r| r.len() as u32).collect()),
                    values,
                    tests,
                    views,
                    bytes: None,
                    counters: Counters::default(),
                }
            }
        };
        if let (true, Counts::One, Some(encoding)) = (
            recording.image_only,
            &batch.counts,
            recording.finished_image,
        ) {
            batch.bytes = Some(encode_values(&batch.values, encoding));
        }
        batch.counters = counters;
        batch
    }

    fn one_each(values: Vec<Vec3A>, views: Option<Vec<ViewSample>>) -> Self {
        Self {
            counts: Counts::One,
            values,
            tests: Vec::new(),
            views,
            bytes: None,
            counters: Counters::default(),
        }
    }
}
