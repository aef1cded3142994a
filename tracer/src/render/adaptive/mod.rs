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

use std::ops::Range;

use glam::{Vec2, Vec3A};
use rayon::prelude::*;

use crate::sampling::{sobol_second, stratum_order};
use crate::stats::AdaptiveStats;

use super::film::Spread;
use super::{AdaptiveSampling, Film, Tile};

/// The error of a pixel's mean, in display units (clamped to 0..1), from
/// the difference between the mean of its last pass's samples and the
/// mean of those before: with `a` and `b` samples in the two halves and
/// `n = a + b`, the difference's variance is the mean's times n^2 / (a b)
/// (4 for equal halves), whatever makes the samples vary. Unlike the
/// samples' variance over n, it sees stratification: a pixel split by an
/// edge whose stratified halves agree has converged, though its samples
/// vary as much as ever (uniform 4 x 4's edge pixels are far better than
/// the variance says, and adaptive sampling refined them to its maximum).
/// The root mean square over the channels; infinite before two passes.
pub fn error_estimate(n: u32, spread: &Spread) -> f32 {
    let (a, b) = (
        spread.earlier_samples,
        n.saturating_sub(spread.earlier_samples),
    );
    if a == 0 || b == 0 {
        return f32::INFINITY;
    }
    let difference = spread.earlier / a as f32 - (spread.sum - spread.earlier) / b as f32;
    let scale = (a as f32 * b as f32).sqrt() / n as f32;
    ((difference * difference).element_sum() / 3.0).sqrt() * scale
}

/// The standard error of a pixel's mean if its samples were independent:
/// the channels' mean unbiased variance over `n`, in display units.
/// Stratified samples do better, so it only says whether a pixel *may*
/// still be noisy; infinite before two samples.
pub fn variance_estimate(n: u32, spread: &Spread) -> f32 {
    if n < 2 {
        return f32::INFINITY;
    }
    let n = n as f32;
    let variance = ((spread.squares - spread.sum * spread.sum / n) / (n - 1.0)).max(Vec3A::ZERO);
    (variance.element_sum() / 3.0 / n).sqrt()
}

/// A sample's value as the image shows it, for the error estimate: linear,
/// clamped to 0..1 (a NaN counts as 0, as the encodings write it).
#[inline]
pub(super) fn display_value(v: Vec3A) -> Vec3A {
    v.max(Vec3A::ZERO).min(Vec3A::ONE)
}

/// Whether a pixel with `samples` samples, error `error` and relative
/// cost `cost` (see [`Refinement::relative_cost`]) takes more on its own
/// account: always below the minimum, never at the maximum, else while
/// the error is not below [`threshold_at`] (so a threshold of 0 refines
/// every pixel to the maximum).
pub fn is_active(samples: u32, error: f32, cost: f32, a: &AdaptiveSampling) -> bool {
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
pub fn threshold_at(samples: u32, cost: f32, a: &AdaptiveSampling) -> f32 {
    let samples = samples.max(a.min_spp) as f32 / a.min_spp.max(1) as f32;
    a.noise_threshold * samples * cost
}

/// What a sample costs besides its intersection tests (the eye ray, the
/// shading), as a share of the film's mean tests per sample: a sample of
/// the sky, which tests nothing, is not free.
const SAMPLE_OVERHEAD: f32 = 0.5;

/// How much more a pixel's own error weighs than each neighbour's in
/// [`Refinement::pooled_errors`].
const OWN_WEIGHT: f32 = 4.0;

/// The decision between an adaptive render's passes, and what it measured
/// of each pixel, kept from one pass to the next. A pixel's cost changes
/// only when it takes samples, its pooled error and whether it is noisy
/// only when a neighbour does, and whether a pixel refines only when its
/// neighbours' noise does: each decision re-measures the rows where its
/// last decision refined a pixel (the pass may have sampled fewer, cut by
/// a budget, never more) and the rows next to them; elsewhere no pixel
/// refines, as at the last decision. Measured over the whole film on one
/// thread, each decision at 512 x 512 took 13-24 ms, as long as a late
/// pass's samples; and late passes, each refining a few edges, are many.
///
/// Meant for one film from its first pass to its last.
#[derive(Debug, Default, Clone)]
pub struct Refinement {
    /// Row-major and empty before the first measure: each pixel's
    /// intersection tests per sample, its error pooled with its
    /// neighbours', and whether that error is at or above its threshold
    /// (1) or not (0).
    per_sample: Vec<f32>,
    pooled: Vec<f32>,
    noisy: Vec<u8>,
    /// What a pixel brings to its neighbours' pooled errors: its squared
    /// error times its samples, and 1 (a count), where it has an
    /// estimate; zero where not. One vector, so one window sum pools both.
    contributions: Vec<Vec2>,
    /// The rows where the last decision refined a pixel; empty before it.
    refining_rows: Vec<bool>,
    /// The film's mean tests per sample over its pixels, from the first
    /// measure (every pixel at the minimum): a pixel's cost is relative
    /// to it. Fixed, so a pass leaves the thresholds of the pixels far
    /// from its samples, and so their decisions, as they were.
    mean_per_sample: Option<f32>,
}

impl Refinement {
    /// A refinement whose costs are relative to a mean already measured
    /// (another's [`Refinement::mean_per_sample`]), and that has measured
    /// nothing else: its first decision measures and decides every row,
    /// what a render's decisions, which re-measure only what changed,
    /// must agree with.
    pub fn relative_to(mean_per_sample: f32) -> Self {
        Self {
            mean_per_sample: Some(mean_per_sample),
            ..Self::default()
        }
    }

    /// The film's mean tests per sample that costs are relative to
    /// ([`Refinement::relative_cost`]); `None` before the first decision
    /// past the minimum.
    pub fn mean_per_sample(&self) -> Option<f32> {
        self.mean_per_sample
    }

    /// Which pixels of `film` the next pass refines, row-major: those
    /// active on their own account ([`is_active`] with their
    /// [`Refinement::pooled_errors`] and [`Refinement::relative_cost`]),
    /// and those whose samples still vary enough ([`variance_estimate`]
    /// at or above their threshold) next to a pixel whose error is above
    /// its own. Two halves of a few samples can agree by chance on an
    /// edge; its neighbours along the edge rarely all do (the window
    /// Cycles widens its active pixels by).
    pub fn decide(&mut self, film: &Film, a: &AdaptiveSampling) -> Vec<bool> {
        let samples = film.sample_counts();
        // Below the minimum every pixel refines, whatever its error.
        if samples.iter().all(|&n| n < a.min_spp) {
            return vec![true; samples.len()];
        }
        let changed = self.measure(film, a);
        let (width, errors) = (film.width().max(1) as usize, &self.pooled);
        let mut active = vec![false; samples.len()];
        for_rows(width, &near(&changed, 1), &mut active, |y, row| {
            let noisy_near = window_sums(&self.noisy, width, y);
            for (x, active) in row.iter_mut().enumerate() {
                let i = y * width + x;
                let (n, cost) = (samples[i], self.relative_cost(i));
                // The spread last: few pixels get past the neighbours.
                *active = is_active(n, errors[i], cost, a)
                    || (n < a.max_spp
                        && noisy_near[x] > 0
                        && film.spreads().get(i).is_some_and(|spread| {
                            variance_estimate(n, spread) >= threshold_at(n, cost, a)
                        }));
            }
        });
        self.refining_rows = active
            .chunks(width)
            .map(|row| row.contains(&true))
            .collect();
        active
    }

    /// Each pixel's error (row-major) as [`error_estimate`] gives it,
    /// pooled over its 3 x 3 neighbourhood: the mean of the squared
    /// errors, its own weighing four times a neighbour's, a neighbour's
    /// scaled to the pixel's sample count (as 1 / n). Two halves of 2
    /// samples are one draw of the error: a pixel split by an edge may
    /// find its halves equal or far apart by chance, while its neighbours
    /// along the edge see much the same edge (Cycles filters its error
    /// estimate too). Infinite where the pixel's own is (before two
    /// passes); neighbours without an estimate are left out.
    pub fn pooled_errors(&self) -> &[f32] {
        &self.pooled
    }

    /// Pixel `i`'s (row-major) cost per sample relative to the film's:
    /// its intersection tests per sample plus what a sample costs besides
    /// them (half the film's mean tests per sample), over the film's mean
    /// of that ([`Refinement::mean_per_sample`]). 1 when nothing was
    /// tested.
    pub fn relative_cost(&self, i: usize) -> f32 {
        let mean = self.mean_per_sample.unwrap_or(0.0);
        if mean <= 0.0 {
            return 1.0;
        }
        let overhead = SAMPLE_OVERHEAD * mean;
        (self.per_sample[i] + overhead) / (mean + overhead)
    }

    /// Brings the measures up to date with `film`: re-measures the rows
    /// where the last decision refined a pixel (every row the first
    /// time), and pools the errors of those rows and their neighbours.
    /// Returns the rows whose pooled errors it measured.
    fn measure(&mut self, film: &Film, a: &AdaptiveSampling) -> Vec<bool> {
        let (width, height) = (film.width().max(1) as usize, film.height() as usize);
        let (samples, tests) = (film.sample_counts(), film.tests());
        let first = self.per_sample.len() != samples.len();
        if first {
            self.per_sample = vec![0.0; samples.len()];
            self.pooled = vec![f32::INFINITY; samples.len()];
            self.noisy = vec![0; samples.len()];
            self.contributions = vec![Vec2::ZERO; samples.len()];
        }
        let sampled = if first || self.refining_rows.len() != height {
            vec![true; height]
        } else {
            std::mem::take(&mut self.refining_rows)
        };
        let own = |i: usize| film.errors().get(i).copied().unwrap_or(f32::INFINITY);
        for_pixels(width, &sampled, &mut self.per_sample, |i| {
            tests.get(i).copied().unwrap_or(0) as f32 / samples[i].max(1) as f32
        });
        for_pixels(width, &sampled, &mut self.contributions, |i| {
            let error = own(i);
            if error.is_finite() {
                Vec2::new(error * error * samples[i] as f32, 1.0)
            } else {
                Vec2::ZERO
            }
        });
        if self.mean_per_sample.is_none() {
            // Row by row, the rows' sums added in order: the same bits
            // whatever the threads.
            let rows: Vec<f64> = self
                .per_sample
                .par_chunks(width)
                .map(|row| row.iter().map(|&c| f64::from(c)).sum())
                .collect();
            let pixels = self.per_sample.len().max(1) as f64;
            self.mean_per_sample = Some((rows.iter().sum::<f64>() / pixels) as f32);
        }
        let changed = near(&sampled, 1);
        let contributions = &self.contributions;
        for_rows(width, &changed, &mut self.pooled, |y, row| {
            let sums = window_sums(contributions, width, y);
            for (x, pooled) in row.iter_mut().enumerate() {
                let i = y * width + x;
                let error = own(i);
                // The pixel's own counts OWN_WEIGHT times: once in the
                // window, the rest here.
                let extra = OWN_WEIGHT - 1.0;
                *pooled = if error.is_finite() {
                    let weight = (sums[x].y + extra) * samples[i] as f32;
                    ((sums[x].x + extra * contributions[i].x) / weight).sqrt()
                } else {
                    error
                };
            }
        });
        let mut noisy = std::mem::take(&mut self.noisy);
        for_pixels(width, &changed, &mut noisy, |i| {
            let error = self.pooled[i];
            u8::from(
                error.is_finite() && error >= threshold_at(samples[i], self.relative_cost(i), a),
            )
        });
        self.noisy = noisy;
        changed
    }
}

/// The rows within `distance` of a row of `rows`.
fn near(rows: &[bool], distance: usize) -> Vec<bool> {
    (0..rows.len())
        .map(|y| {
            rows[y.saturating_sub(distance)..(y + distance + 1).min(rows.len())].contains(&true)
        })
        .collect()
}

/// Sets `values` in the rows where `rows` is true (`width` values a row)
/// with `fill(y, row)`, a row at a time on the render's threads. Each row
/// depends only on what `fill` reads, so the result is the same whatever
/// the threads.
fn for_rows<T: Send>(
    width: usize,
    rows: &[bool],
    values: &mut [T],
    fill: impl Fn(usize, &mut [T]) + Sync,
) {
    values
        .par_chunks_mut(width)
        .enumerate()
        .filter(|(y, _)| rows[*y])
        .for_each(|(y, row)| fill(y, row));
}

/// [`for_rows`] pixel by pixel: `values[i] = value(i)`, `i` row-major.
fn for_pixels<T: Send>(
    width: usize,
    rows: &[bool],
    values: &mut [T],
    value: impl Fn(usize) -> T + Sync,
) {
    for_rows(width, rows, values, |y, row| {
        for (x, v) in row.iter_mut().enumerate() {
            *v = value(y * width + x);
        }
    });
}

/// The sums of `values` (row-major, `width` a row) over the 3 x 3 window
/// of each pixel of row `y`, within the film: the rows added column by
/// column, then each column to its neighbours. Six additions a pixel, in
/// loops the compiler vectorises: a loop over each pixel's window, with
/// a test of each neighbour, took pooling 5% of an adaptive render.
fn window_sums<T>(values: &[T], width: usize, y: usize) -> Vec<T>
where
    T: Copy + Default + std::ops::Add<Output = T>,
{
    let height = values.len() / width.max(1);
    let mut columns = vec![T::default(); width];
    for row in y.saturating_sub(1)..(y + 2).min(height) {
        for (sum, &v) in columns.iter_mut().zip(&values[row * width..][..width]) {
            *sum = *sum + v;
        }
    }
    (0..width)
        .map(|x| {
            let left = if x > 0 { columns[x - 1] } else { T::default() };
            let right = columns.get(x + 1).copied().unwrap_or_default();
            left + columns[x] + right
        })
        .collect()
}

/// The sample count an active pixel with `samples` samples reaches in the
/// next pass: doubling (1, 2, 4, ...) up to the minimum, then doubling up
/// to the maximum. Equal halves give the error estimate its two halves,
/// and each half of a power of two samples in Sobol's order is a net of
/// its own; and few passes keep their overhead small (the pass barrier,
/// the decision over the whole film).
pub fn next_count(samples: u32, a: &AdaptiveSampling) -> u32 {
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
pub fn early_light_points(power: f32, brightest: f32) -> u32 {
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
pub fn light_points(rank: u32, early: u32, a: &AdaptiveSampling) -> Range<u32> {
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
        samples = next_count(samples, a);
        passes += 1;
    }
    passes
}

/// The order in which a pixel's adaptive samples visit its `m * m` strata,
/// as the uniform passes whose samples they take (see [`stratum_order`]):
/// the first two dimensions of Sobol's sequence, a (0, 2)-sequence in base
/// 2, so each prefix of 2^j samples falls once in every box of area 2^-j
/// the pixel splits into by halvings: the first 8 of an 8 x 8 round take
/// every column of strata once, every row once, and each of the 2 x 4 and
/// 4 x 2 blocks once. The uniform order's short prefixes lie on diagonals
/// of the pixel, a Morton walk's in two columns: an adaptive pixel that
/// stops after a prefix missed the edges between them (glass at 256 x 256:
/// MSE 1.6 against uniform 4 x 4's 1.2 at the same 16 samples per pixel).
/// When `m` is a power of two each pixel's points are also shifted by
/// its own random digits (a XOR, which keeps every prefix's strata), so
/// neighbouring pixels that stop early do not share one pattern. A whole
/// round takes the same samples as a round of uniform passes.
pub struct RoundOrder {
    m: u32,
    /// Bits of a coordinate when `m` is a power of two.
    bits: Option<u32>,
    pass_of_stratum: Vec<u32>,
    /// Other sides: the unshifted order, points outside the strata left
    /// out.
    table: Vec<u32>,
}

impl RoundOrder {
    pub fn new(m: u32) -> Self {
        let m = m.max(1);
        let uniform = stratum_order(m);
        let mut pass_of_stratum = vec![0; uniform.len()];
        for (pass, &stratum) in uniform.iter().enumerate() {
            pass_of_stratum[stratum as usize] = pass as u32;
        }
        let bits = m.next_power_of_two().trailing_zeros();
        let table = if m.is_power_of_two() {
            Vec::new()
        } else {
            (0..1u32 << (2 * bits))
                .filter_map(|k| {
                    let (x, y) = sobol_point(k, bits);
                    (x < m && y < m).then(|| pass_of_stratum[(y * m + x) as usize])
                })
                .collect()
        };
        Self {
            m,
            bits: m.is_power_of_two().then_some(bits),
            pass_of_stratum,
            table,
        }
    }

    /// Samples in a round: `m * m`.
    pub fn len(&self) -> u32 {
        self.m * self.m
    }

    /// Never: a round has at least one sample.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The uniform pass (within a round) whose sample the `k`-th sample of
    /// a round takes, in a pixel whose random digits are `shift`.
    pub fn pass(&self, k: u32, shift: u32) -> u32 {
        match self.bits {
            Some(bits) => {
                let (x, y) = sobol_point(k, bits);
                let mask = (1u32 << bits) - 1;
                let (x, y) = (x ^ (shift & mask), y ^ ((shift >> 16) & mask));
                self.pass_of_stratum[(y * self.m + x) as usize]
            }
            None => self.table[k as usize],
        }
    }
}

/// Point `k` of Sobol's first two dimensions on a grid of `2^bits` cells
/// a side.
fn sobol_point(k: u32, bits: u32) -> (u32, u32) {
    if bits == 0 {
        return (0, 0);
    }
    let shift = u32::BITS - bits;
    (k.reverse_bits() >> shift, sobol_second(k) >> shift)
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
pub fn within_budget(
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
mod tests {
    use super::*;

    fn settings(threshold: f32, min_spp: u32, max_spp: u32) -> AdaptiveSampling {
        AdaptiveSampling {
            noise_threshold: threshold,
            min_spp,
            max_spp,
            budget: None,
        }
    }

    /// What a film knows of a pixel whose passes gave it `earlier`, then
    /// `last`.
    fn spread(earlier: &[f32], last: &[f32]) -> (u32, Spread) {
        let mut spread = Spread::default();
        for (k, &v) in earlier.iter().chain(last).enumerate() {
            if k == earlier.len() {
                spread.earlier = spread.sum;
                spread.earlier_samples = k as u32;
            }
            let v = display_value(Vec3A::splat(v));
            spread.sum += v;
            spread.squares += v * v;
        }
        ((earlier.len() + last.len()) as u32, spread)
    }

    fn estimate(earlier: &[f32], last: &[f32]) -> f32 {
        let (n, spread) = spread(earlier, last);
        error_estimate(n, &spread)
    }

    #[test]
    fn a_constant_pixel_stops_after_the_minimum() {
        let a = settings(0.01, 8, 64);
        // Zero but for the halves' rounding.
        let error = estimate(&[0.4; 4], &[0.4; 4]);
        assert!(error < 1e-6, "{error}");
        assert!(
            is_active(4, estimate(&[0.4; 2], &[0.4; 2]), 1.0, &a),
            "below the minimum"
        );
        assert!(!is_active(8, error, 1.0, &a));
        // Bright beyond the display's range is as constant as it shows.
        assert_eq!(estimate(&[1.5, 3.0], &[1.0, 2.0]), 0.0);
    }

    #[test]
    fn a_pixel_split_by_an_edge_keeps_refining_until_its_halves_agree() {
        let a = settings(0.01, 8, 64);
        // A quarter of the pixel is a bright object: the first 8 samples
        // see it once, the next 8 three times.
        let first = [0.9, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1];
        let last = [0.9, 0.1, 0.9, 0.1, 0.9, 0.1, 0.1, 0.1];
        let error = estimate(&first, &last);
        // The means differ by 0.2, halves of 8: 0.2 / 2.
        assert!((error - 0.1).abs() < 1e-6, "{error}");
        assert!(is_active(16, error, 1.0, &a));
        assert!(!is_active(64, error, 1.0, &a), "the maximum ends it");
        assert!(!is_active(16, error, 1.0, &settings(0.2, 8, 64)));
        // The error a pixel may keep grows in proportion to its samples:
        // 0.1 keeps refining at 16 against 0.08 (twice 0.04), not at 32
        // (0.16).
        assert!(is_active(16, error, 1.0, &settings(0.04, 8, 64)));
        assert!(!is_active(32, error, 1.0, &settings(0.04, 8, 64)));
        assert_eq!(
            threshold_at(4, 1.0, &settings(0.03, 8, 64)),
            0.03,
            "below the minimum"
        );
        // And to what its samples cost: at 16 a pixel whose samples cost
        // 4 times the average may keep 0.32, one whose cost a quarter of
        // it 0.02.
        assert!(!is_active(16, error, 4.0, &settings(0.04, 8, 64)));
        assert!(is_active(16, error, 0.25, &settings(0.04, 8, 64)));
        // Stratified halves that each see the quarter twice agree: the
        // mean has converged though the samples vary as much as ever.
        let even = [0.9, 0.1, 0.1, 0.1, 0.9, 0.1, 0.1, 0.1];
        assert_eq!(estimate(&even, &even), 0.0);
        let (n, spread) = spread(&even, &even);
        assert!(variance_estimate(n, &spread) > 0.08);
        // Unequal halves weigh the difference by sqrt(a b) / n.
        let unequal = estimate(&[0.5, 0.5], &[0.2; 6]);
        assert!(
            (unequal - 0.3 * 12f32.sqrt() / 8.0).abs() < 1e-6,
            "{unequal}"
        );
    }

    #[test]
    fn one_pass_says_nothing_and_threshold_zero_refines_to_the_maximum() {
        let a = settings(0.5, 1, 16);
        assert!(estimate(&[], &[0.3]).is_infinite());
        assert!(estimate(&[], &[0.3, 0.3]).is_infinite());
        assert!(is_active(1, estimate(&[], &[0.3]), 1.0, &a));
        let zero = settings(0.0, 1, 16);
        assert!(is_active(15, 0.0, 1.0, &zero));
        assert!(!is_active(16, 0.0, 1.0, &zero));
    }

    #[test]
    fn the_schedule_doubles_to_the_minimum_then_to_the_maximum() {
        let a = settings(0.01, 4, 64);
        let mut counts = vec![0];
        while *counts.last().unwrap() < a.max_spp {
            counts.push(next_count(*counts.last().unwrap(), &a));
        }
        assert_eq!(counts, [0, 1, 2, 4, 8, 16, 32, 64]);
        assert_eq!(passes(&a), 7);
        assert_eq!(passes(&settings(0.0, 1, 1)), 1);
        // A minimum or maximum that is not a power of two is met exactly.
        assert_eq!(next_count(4, &settings(0.0, 6, 9)), 6);
        assert_eq!(next_count(6, &settings(0.0, 6, 9)), 9);
    }

    #[test]
    fn early_samples_take_a_prefix_of_light_points_in_proportion_to_power() {
        assert_eq!(early_light_points(3.0, 3.0), 4);
        assert_eq!(early_light_points(0.8, 2.4), 1, "a third of the power");
        assert_eq!(early_light_points(1.5, 3.0), 2);
        assert_eq!(early_light_points(0.0, 3.0), 1, "at least one");
        assert_eq!(early_light_points(0.0, 0.0), 4, "all dark: all alike");
        assert_eq!(early_light_points(f32::INFINITY, f32::INFINITY), 1);
        let a = settings(0.01, 4, 64);
        for early in [1, 2, 4] {
            let ranges: Vec<Range<u32>> = (0..64).map(|k| light_points(k, early, &a)).collect();
            // Each sample's points follow the last's, with no gap.
            assert_eq!(ranges[0].start, 0);
            for pair in ranges.windows(2) {
                assert_eq!(pair[0].end, pair[1].start, "{early}: {pair:?}");
            }
            // The minimum's samples take the first 4 early points, twice
            // the minimum's twice as many; later samples one each.
            assert_eq!(ranges[3].end, 4 * early);
            assert_eq!(ranges[7].end, 8 * early);
            assert!(ranges[8..].iter().all(|r| r.len() == 1));
        }
    }

    /// A film of `width` x 1 pixels whose passes gave each pixel
    /// `earlier[i]`, then `last[i]`.
    fn film(pixels: &[(&[f32], &[f32])]) -> Film {
        let mut film = Film::with_error_estimate(pixels.len() as u32, 1);
        for pass in 0..2 {
            let halves: Vec<&[f32]> = pixels
                .iter()
                .map(|p| if pass == 0 { p.0 } else { p.1 })
                .collect();
            add_pass(&mut film, &halves);
        }
        film
    }

    /// Gives each pixel of `film` (row-major) its samples in `pass`.
    fn add_pass(film: &mut Film, pass: &[&[f32]]) {
        let tile = Tile {
            x: 0,
            y: 0,
            width: film.width(),
            height: film.height(),
        };
        let counts: Vec<u32> = pass.iter().map(|h| h.len() as u32).collect();
        let values: Vec<Vec3A> = pass
            .iter()
            .flat_map(|h| h.iter().map(|&v| Vec3A::splat(v)))
            .collect();
        // Synthetic samples cost nothing.
        film.add_samples(&tile, &counts, &values, &vec![0; counts.len()]);
    }

    /// A column of three pixels: an edge A above a flat pixel B above a
    /// pixel C whose samples vary but whose halves agree. Only A refines
    /// after the minimum, and its error grows: B, two rows from C and
    /// never sampled again, becomes noisy through A, and C refines for
    /// B's sake. A decision that re-pooled only the rows sampled, or
    /// decided only the rows it re-pooled, would leave both stopped; one
    /// that took the rows to re-measure from the film's active pixels
    /// would stop A when a budget cut it from a pass.
    #[test]
    fn a_pass_changes_decisions_two_rows_away_as_a_fresh_decision_does() {
        let a = settings(0.05, 4, 64);
        let mut film = Film::with_error_estimate(1, 3);
        add_pass(&mut film, &[&[0.5], &[0.3], &[0.9]]);
        add_pass(&mut film, &[&[0.5], &[0.3], &[0.1]]);
        add_pass(&mut film, &[&[0.7, 0.7], &[0.3, 0.3], &[0.1, 0.9]]);
        let mut refinement = Refinement::default();
        let first = refinement.decide(&film, &a);
        assert_eq!(first, [true, false, false]);
        // A budget that cut every pixel from the pass: nothing changed,
        // and A is still above the threshold.
        film.set_active(vec![false; 3]);
        assert_eq!(refinement.decide(&film, &a), first);
        film.set_active(first);
        add_pass(&mut film, &[&[0.0; 4], &[], &[]]);
        let second = refinement.decide(&film, &a);
        assert_eq!(second, [true, true, true]);
        let mean = refinement.mean_per_sample().expect("measured");
        assert_eq!(Refinement::relative_to(mean).decide(&film, &a), second);
    }

    #[test]
    fn a_varying_pixel_next_to_a_noisy_one_refines_too() {
        let a = settings(0.05, 8, 64);
        let edge: (&[f32], &[f32]) = (&[0.9, 0.1, 0.1, 0.1], &[0.9, 0.9, 0.9, 0.1]);
        let lucky: (&[f32], &[f32]) = (&[0.9, 0.1, 0.1, 0.1], &[0.9, 0.1, 0.1, 0.1]);
        let flat: (&[f32], &[f32]) = (&[0.3; 4], &[0.3; 4]);
        let active = Refinement::default().decide(&film(&[edge, lucky, flat, lucky]), &a);
        // The edge on its own account, its lucky neighbour for it; the
        // flat pixel never, the lucky pixel beside it alone stops.
        assert_eq!(active, [true, true, false, false]);
    }

    #[test]
    fn a_round_takes_every_uniform_pass_once_with_stratified_prefixes() {
        for m in [1, 2, 3, 4, 5, 8, 12, 16] {
            let round = RoundOrder::new(m);
            let mut sorted: Vec<u32> = (0..round.len())
                .map(|k| round.pass(k, 0x0007_0009))
                .collect();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..m * m).collect::<Vec<_>>(), "m = {m}");
        }
        // Back to strata: each prefix of 2^j samples of an 8 x 8 round
        // falls once in every box of area 2^-j (columns, rows, blocks),
        // whatever the pixel's random digits.
        let uniform = stratum_order(8);
        let order = RoundOrder::new(8);
        for shift in [0, 0x0005_0003, 0xdead_beef] {
            let strata: Vec<(u32, u32)> = (0..64)
                .map(|k| order.pass(k, shift))
                .map(|p| (uniform[p as usize] % 8, uniform[p as usize] / 8))
                .collect();
            for j in 0..=6u32 {
                let prefix = &strata[..1 << j];
                for a in 0..=j {
                    // Boxes 8 / 2^a strata wide, 8 / 2^(j - a) tall.
                    let (across, down) = (1u32 << a, 1u32 << (j - a));
                    if across > 8 || down > 8 {
                        continue;
                    }
                    let mut boxes: Vec<u32> = prefix
                        .iter()
                        .map(|&(x, y)| (y * down / 8) * across + x * across / 8)
                        .collect();
                    boxes.sort_unstable();
                    assert_eq!(
                        boxes,
                        (0..1 << j).collect::<Vec<_>>(),
                        "shift {shift:x}, prefix {}: {across} x {down} boxes",
                        1 << j
                    );
                }
            }
        }
        let pattern = |shift| (0..8).map(|k| order.pass(k, shift)).collect::<Vec<_>>();
        assert_ne!(pattern(1), pattern(0x0002_0000), "pixels differ");
    }
}
