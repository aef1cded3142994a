//! Adaptive sampling: which pixels take more samples in a pass, how many,
//! and in which order of their strata.
//!
//! A pixel's error is estimated from its samples: those of its last pass
//! against those before it (two halves, as Cycles compares two
//! interleaved half-buffers), pooled with its neighbours' estimates; the
//! error it may keep grows with what its samples cost in intersection
//! tests. Its samples are a pure function of (seed, pixel, sample index),
//! and which pixels refine is decided between passes over the whole film
//! (the tests a sample makes are as deterministic as its value): so the
//! image never depends on the thread count or on when a viewer looked.

mod order;
mod refinement;

use std::ops::Range;

use rayon::prelude::*;

use crate::stats::{AdaptiveStats, RenderStats};

use super::strategy::{PassEnd, SamplingStrategy, TileSamples};
use super::{AdaptiveSampling, Budget, Film, Tile};

pub use order::RoundOrder;
pub use refinement::Refinement;

/// Adaptive sampling as a render's strategy: each pass refines the pixels
/// the last decision left active, from their sample count to
/// `next_count`; between passes [`Refinement::decide`] chooses the next
/// ones, cut to a sample budget when there is one. Done once no pixel is
/// active, or the budget is spent.
#[derive(Debug, Clone)]
pub struct Adaptive {
    settings: AdaptiveSampling,
    refinement: Refinement,
    /// A sample budget's last pass is under way (or done).
    samples_spent: bool,
}

impl Adaptive {
    /// The strategy for these adaptive settings, before its first pass.
    pub fn new(settings: AdaptiveSampling) -> Self {
        Self {
            settings,
            refinement: Refinement::default(),
            samples_spent: false,
        }
    }
}

impl SamplingStrategy for Adaptive {
    fn film(&self, width: u32, height: u32) -> Film {
        Film::with_error_estimate(width, height)
    }

    fn passes_target(&self) -> u32 {
        passes(&self.settings)
    }

    fn tile_samples(&self, _: u32, tile: &Tile, film: &Film) -> Option<TileSamples> {
        let plan = plan(film, tile, &self.settings);
        (!plan.iter().all(Range::is_empty)).then_some(TileSamples::Each(plan))
    }

    /// Always: whether a neighbour's noise brings a tile back is decided
    /// after the pass, so its bytes are made each time it takes samples.
    fn may_be_last(&self, _: u32) -> bool {
        true
    }

    fn end_pass(
        &mut self,
        pass: u32,
        film: &mut Film,
        stats: &mut RenderStats,
        budget_spent: bool,
    ) -> PassEnd {
        let a = &self.settings;
        let out_of_budget = self.samples_spent || budget_spent;
        let mut active = self.refinement.decide(film, a);
        if let (Some(Budget::Samples(total)), false) = (a.budget, out_of_budget) {
            (active, self.samples_spent) = within_budget(film, active, a, total);
        }
        film.set_active(active);
        let summary = summary(film);
        stats.adaptive = Some(summary);
        // Ended by its budget, a render leaves its pixels still above the
        // threshold active: a viewer shows where the budget ran out.
        if summary.active_pixels == 0 || out_of_budget {
            // Done before the most passes it might have taken.
            stats.passes_target = pass + 1;
            PassEnd::Done
        } else {
            // A pixel a neighbour brings back is a pass behind the
            // schedule: at least one more.
            stats.passes_target = stats.passes_target.max(pass + 2);
            PassEnd::More
        }
    }
}

/// Whether a pixel with `samples` samples, error `error` and relative
/// cost `cost` (see [`Refinement::relative_cost`]) takes more on its own
/// account: always below the minimum, never at the maximum, else while
/// the error is not below [`threshold_at`] (so a threshold of 0 refines
/// every pixel to the maximum).
pub(crate) fn is_active(samples: u32, error: f32, cost: f32, a: &AdaptiveSampling) -> bool {
    samples < a.min_spp || (samples < a.max_spp && error >= threshold_at(samples, cost, a))
}

/// The error a pixel with `samples` samples may keep when its samples
/// cost `cost` times the film's average (see
/// [`Refinement::relative_cost`]): the noise threshold at the minimum and
/// the average cost, growing in proportion to the samples times the
/// cost. Doubling a pixel's samples divides its error e by about sqrt 2
/// and costs its samples again, n c.
/// Priced by squared error (removing e^2 / 2), a pass is worth it while
/// e >= T sqrt(n c); but what a viewer (and FLIP) sees of small errors
/// grows about as e itself, not e^2 (faint noise that flips a smooth
/// floor's pixels by a level shows). Priced by the error (removing about
/// 0.3 e), a pass is worth it while e >= T n c: the many faintly noisy
/// pixels still at the minimum refine before the few hard ones double
/// again. At uniform 4 x 4's MSE and FLIP this needed 0.75 of uniform's
/// intersection tests on soft_shadows instead of 0.83, 0.59 instead of
/// 0.62 on balls_medium.
///
/// Held to one threshold, the few pixels that never settle (edges of
/// reflections, penumbrae) took most of the render for little of its
/// error; priced by samples only, reflections and refractions, which
/// cost several times a floor pixel's tests per sample, refined as often
/// as the floor (docs/PERFORMANCE.md measures the rules).
pub(crate) fn threshold_at(samples: u32, cost: f32, a: &AdaptiveSampling) -> f32 {
    let samples = samples.max(a.min_spp) as f32 / a.min_spp.max(1) as f32;
    a.noise_threshold * samples * cost
}

/// The sample count an active pixel with `samples` samples reaches in the
/// next pass: doubling (1, 2, 4, ...) up to the minimum, then doubling up
/// to the maximum. Equal halves give the error estimate its two halves,
/// and each half of a power of two samples in Sobol's order is a net of
/// its own; and few passes keep their overhead small (the pass barrier,
/// the decision over the whole film).
pub(crate) fn next_count(samples: u32, a: &AdaptiveSampling) -> u32 {
    let next = if samples < a.min_spp {
        (2 * samples).clamp(1, a.min_spp)
    } else {
        2 * samples
    };
    next.min(a.max_spp)
}

/// Points of the brightest light a sample takes with soft shadows while
/// its pixel has fewer than twice the minimum samples (see
/// [`light_points`]).
const EARLY_LIGHT_POINTS: u32 = 4;

/// The points of a light whose power (the sum of its colour's channels)
/// is `power` that a pixel's early samples take each, when the brightest
/// light's is `brightest`: 4 (`EARLY_LIGHT_POINTS`) in proportion to the
/// power, at least 1. A light's noise grows with its power, and points
/// in proportion to it minimise the summed variance for their cost: on
/// soft_shadows the fill light, a third of the area light's power, takes
/// 1 where the area light takes 4 (every light at 4, adaptive took 65-79%
/// of uniform 4 x 4's time to reach its error; so, 50-61%).
pub(crate) fn early_light_points(power: f32, brightest: f32) -> u32 {
    let share = if brightest > 0.0 {
        power / brightest
    } else {
        1.0
    };
    // A NaN share (an infinite power) becomes 0 and so 1 point.
    ((EARLY_LIGHT_POINTS as f32 * share).round() as u32).clamp(1, EARLY_LIGHT_POINTS)
}

/// The indices of its pixel's light sequence (see
/// [`SampleStream::next_light_points`]) that the `rank`-th sample of a
/// pixel takes for a light whose early samples take `early` points each
/// ([`early_light_points`]): `early` while the pixel has fewer than twice
/// the minimum samples, one after, each sample's following the last's.
///
/// Most pixels stop at the minimum or one pass after it, a quarter or
/// half of uniform N x N's samples. With one light point a sample, the
/// lit floor and walls of soft_shadows were left faintly noisy there, a
/// level off in many pixels; FLIP counts that, so the threshold search
/// refined nearly every pixel and adaptive took 81-91% of uniform 4 x 4's
/// time. With 4 points of the brightest light, a pixel at the minimum
/// averages as many light points as uniform N x N (N^2 / 4 samples, at
/// least 4) and, its samples' indices an aligned prefix of the sequence,
/// as well spread; the points' shadow rays count in the pixel's
/// intersection tests, so in its cost, as any ray's.
///
/// [`SampleStream::next_light_points`]: crate::sampling::SampleStream::next_light_points
pub(crate) fn light_points(rank: u32, early: u32, a: &AdaptiveSampling) -> Range<u32> {
    let until = 2 * a.min_spp;
    let first = rank.min(until) * early + rank.saturating_sub(until);
    let count = if rank < until { early } else { 1 };
    first..first + count
}

/// Passes that take a pixel that never converges from no sample to the
/// maximum: what an adaptive render expects to run at most (a pixel that
/// stopped and that a neighbour brings back takes longer).
pub fn passes(a: &AdaptiveSampling) -> u32 {
    let mut samples = 0;
    let mut passes = 0;
    while samples < a.max_spp {
        let next = next_count(samples, a);
        // Valid settings (1 <= minimum <= maximum) make every pass add
        // samples: a count that stood still would loop here for ever.
        debug_assert!(next > samples, "next_count({samples}) is {next}");
        samples = next;
        passes += 1;
    }
    passes
}

/// The samples each pixel of `tile` (row-major) takes in the next pass:
/// from its count to [`next_count`] while active, none once done.
pub(super) fn plan(film: &Film, tile: &Tile, a: &AdaptiveSampling) -> Vec<Range<u32>> {
    let mut plan = Vec::with_capacity(tile.pixel_count());
    for y in tile.y..tile.y + tile.height {
        for x in tile.x..tile.x + tile.width {
            let samples = film.samples(x, y);
            plan.push(if film.is_active(x, y) {
                samples..next_count(samples, a)
            } else {
                samples..samples
            });
        }
    }
    plan
}

/// `active` cut to a sample budget of `total` samples: when the next
/// pass would take the film past it, only the pixels with the largest
/// error estimates whose samples fit refine (ties in row-major order),
/// and the flag says the budget is spent, so that pass is the last.
pub(crate) fn within_budget(
    film: &Film,
    mut active: Vec<bool>,
    a: &AdaptiveSampling,
    total: u64,
) -> (Vec<bool>, bool) {
    let width = film.width() as usize;
    let at = |i: usize| ((i % width) as u32, (i / width) as u32);
    let extra = |i: usize| {
        let (x, y) = at(i);
        let n = film.samples(x, y);
        u64::from(next_count(n, a) - n)
    };
    let taken: u64 = (0..active.len())
        .map(|i| u64::from(film.samples(at(i).0, at(i).1)))
        .sum();
    let mut refining: Vec<usize> = (0..active.len()).filter(|&i| active[i]).collect();
    if taken + refining.iter().map(|&i| extra(i)).sum::<u64>() <= total {
        return (active, false);
    }
    let error = |i: usize| film.error(at(i).0, at(i).1);
    // Stable: equal errors keep their row-major order.
    refining.sort_by(|&i, &j| error(j).total_cmp(&error(i)));
    let mut left = total.saturating_sub(taken);
    for i in refining {
        match left.checked_sub(extra(i)) {
            Some(rest) => left = rest,
            None => active[i] = false,
        }
    }
    (active, true)
}

/// Where an adaptive render stands: active pixels (as last decided),
/// samples taken and the root mean square of the pixels' estimated
/// errors.
pub fn summary(film: &Film) -> AdaptiveStats {
    let width = film.width().max(1) as usize;
    let (samples, errors, active) = (
        film.sample_counts(),
        film.errors(),
        film.active_pixels().unwrap_or_default(),
    );
    // A row at a time on the render's threads, the rows' sums added in
    // order: the same bits whatever the threads.
    let rows: Vec<RowSummary> = samples
        .par_chunks(width)
        .enumerate()
        .map(|(y, row)| {
            let mut sums = RowSummary::default();
            for (x, &n) in row.iter().enumerate() {
                let i = y * width + x;
                sums.samples += u64::from(n);
                sums.max_spp = sums.max_spp.max(n);
                sums.active += u64::from(active.get(i).copied().unwrap_or(false));
                let error = errors.get(i).copied().unwrap_or(f32::INFINITY);
                if error.is_finite() {
                    sums.squared_error += f64::from(error).powi(2);
                    sums.measured += 1;
                }
            }
            sums
        })
        .collect();
    let mut stats = AdaptiveStats {
        pixels: samples.len() as u64,
        ..AdaptiveStats::default()
    };
    let (mut squared_error, mut measured) = (0.0f64, 0u64);
    for row in rows {
        stats.samples += row.samples;
        stats.max_spp = stats.max_spp.max(row.max_spp);
        stats.active_pixels += row.active;
        squared_error += row.squared_error;
        measured += row.measured;
    }
    stats.error = if measured > 0 {
        (squared_error / measured as f64).sqrt() as f32
    } else {
        f32::INFINITY
    };
    stats
}

/// One row's share of [`summary`].
#[derive(Default)]
struct RowSummary {
    samples: u64,
    max_spp: u32,
    active: u64,
    squared_error: f64,
    measured: u64,
}

#[cfg(test)]
mod tests;
