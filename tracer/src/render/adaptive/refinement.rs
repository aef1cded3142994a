//! The decision between an adaptive render's passes: which pixels refine,
//! from their pooled errors priced by what their samples cost.

use glam::Vec2;
use rayon::prelude::*;

use super::super::Film;
use super::super::estimate::variance_estimate;
use super::{AdaptiveSampling, is_active, threshold_at};

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
    /// (`Refinement::relative_cost`); `None` before the first decision
    /// past the minimum.
    pub fn mean_per_sample(&self) -> Option<f32> {
        self.mean_per_sample
    }

    /// Which pixels of `film` the next pass refines, row-major: those
    /// active on their own account (`is_active` with their
    /// [`Refinement::pooled_errors`] and `Refinement::relative_cost`),
    /// and those whose samples still vary enough (`variance_estimate`
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

    /// Each pixel's error (row-major) as
    /// [`error_estimate`](crate::render::estimate::error_estimate) gives it,
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
    pub(crate) fn relative_cost(&self, i: usize) -> f32 {
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
        self.pool(film, &changed, a);
        changed
    }

    /// Pools the errors of the rows in `changed` over each pixel's
    /// neighbours (see [`Refinement::pooled_errors`]) and marks which are
    /// at or above their thresholds.
    fn pool(&mut self, film: &Film, changed: &[bool], a: &AdaptiveSampling) {
        let width = film.width().max(1) as usize;
        let samples = film.sample_counts();
        let own = |i: usize| film.errors().get(i).copied().unwrap_or(f32::INFINITY);
        let contributions = &self.contributions;
        for_rows(width, changed, &mut self.pooled, |y, row| {
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
        for_pixels(width, changed, &mut noisy, |i| {
            let error = self.pooled[i];
            u8::from(
                error.is_finite() && error >= threshold_at(samples[i], self.relative_cost(i), a),
            )
        });
        self.noisy = noisy;
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
