//! Sampling strategies: which samples each pass takes, and when a render
//! is done. The render loop runs any of them unchanged: uniform N x N
//! ([`Uniform`]) and adaptive sampling ([`super::adaptive::Adaptive`]) are
//! two, and a caller may bring its own ([`super::RenderJob::start_with`]).

use std::ops::Range;

use crate::stats::RenderStats;

use super::{Film, RenderSettings, Tile};

/// The samples a tile takes in one pass.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TileSamples {
    /// Every pixel takes its sample number `n` (from 0): a uniform pass,
    /// rendered a row of eye rays at a time.
    Every(u32),
    /// Pixel `i` of the tile (row-major) takes the samples `ranges[i]`,
    /// none where the range is empty.
    Each(Vec<Range<u32>>),
}

/// Where a render stands after a pass, as its strategy decided.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PassEnd {
    /// Another pass follows.
    More,
    /// The render is done: the pass just ended was its last.
    Done,
}

/// Decides which samples a render takes, pass by pass. The loop asks
/// [`SamplingStrategy::tile_samples`] for each tile of a pass (from any
/// render thread, with the film as the last pass left it), records what
/// the tiles rendered, then calls [`SamplingStrategy::end_pass`] once,
/// between passes, where the strategy may look at the whole film.
///
/// A strategy decides from the film alone, never from time or threads,
/// so its image is a function of the settings.
pub trait SamplingStrategy: Send + Sync {
    /// The film the render records into: [`Film::new`], or
    /// [`Film::with_error_estimate`] for a strategy that reads each
    /// pixel's error.
    fn film(&self, width: u32, height: u32) -> Film;

    /// The passes the render expects to take, for a viewer's progress
    /// before the first pass ends (each [`SamplingStrategy::end_pass`]
    /// may move it).
    fn passes_target(&self) -> u32;

    /// The samples of `tile` in pass `pass` (from 0); `None` when the
    /// tile takes none.
    fn tile_samples(&self, pass: u32, tile: &Tile, film: &Film) -> Option<TileSamples>;

    /// Whether a tile's samples in pass `pass` may be its last: the
    /// finished image ([`super::JobOptions::finished_image`]) takes the
    /// tile's bytes then.
    fn may_be_last(&self, pass: u32) -> bool;

    /// Decides, after pass `pass` and before the next, what the next pass
    /// samples, and records where the render stands in `stats`
    /// (`passes_target`, `adaptive`). `budget_spent`: the driver's budget
    /// ran out, so this pass is the last whatever the strategy says.
    fn end_pass(
        &mut self,
        pass: u32,
        film: &mut Film,
        stats: &mut RenderStats,
        budget_spent: bool,
    ) -> PassEnd;
}

/// Uniform sampling: every pixel takes one sample a pass, the pass's
/// stratum, until N x N passes (or forever when refining).
#[derive(Debug, Clone)]
pub struct Uniform {
    target: u32,
    refine: bool,
}

impl Uniform {
    /// The passes of `settings`' samples per pixel, refining past them
    /// when they keep refining.
    pub fn new(settings: &RenderSettings) -> Self {
        Self {
            target: settings.samples_per_pixel().max(1),
            refine: settings.keep_refining,
        }
    }
}

impl SamplingStrategy for Uniform {
    fn film(&self, width: u32, height: u32) -> Film {
        Film::new(width, height)
    }

    fn passes_target(&self) -> u32 {
        self.target
    }

    fn tile_samples(&self, pass: u32, _: &Tile, _: &Film) -> Option<TileSamples> {
        Some(TileSamples::Every(pass))
    }

    fn may_be_last(&self, pass: u32) -> bool {
        pass + 1 == self.target && !self.refine
    }

    fn end_pass(&mut self, pass: u32, _: &mut Film, _: &mut RenderStats, spent: bool) -> PassEnd {
        if spent || (pass + 1 >= self.target && !self.refine) {
            PassEnd::Done
        } else {
            PassEnd::More
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(samples: u32, keep_refining: bool) -> RenderSettings {
        RenderSettings {
            antialiasing: true,
            samples,
            keep_refining,
            ..RenderSettings::default()
        }
    }

    #[test]
    fn uniform_ends_after_n_squared_passes_unless_refining() {
        let film = &mut Film::new(1, 1);
        let stats = &mut RenderStats::default();
        let mut uniform = Uniform::new(&settings(3, false));
        assert_eq!(uniform.passes_target(), 9);
        assert_eq!(uniform.end_pass(7, film, stats, false), PassEnd::More);
        assert_eq!(uniform.end_pass(8, film, stats, false), PassEnd::Done);
        assert!(!uniform.may_be_last(7) && uniform.may_be_last(8));
        let mut refining = Uniform::new(&settings(3, true));
        assert_eq!(refining.end_pass(8, film, stats, false), PassEnd::More);
        assert_eq!(refining.end_pass(40, film, stats, true), PassEnd::Done);
        assert!(!refining.may_be_last(8));
    }

    #[test]
    fn a_uniform_pass_takes_its_own_sample_in_every_tile() {
        let tile = Tile {
            x: 0,
            y: 0,
            width: 2,
            height: 2,
        };
        let uniform = Uniform::new(&settings(2, false));
        let film = Film::new(2, 2);
        assert_eq!(
            uniform.tile_samples(3, &tile, &film),
            Some(TileSamples::Every(3))
        );
    }
}
