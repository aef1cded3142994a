//! A pixel's error estimated from its own samples: what adaptive sampling
//! decides from, kept by the film as samples arrive. Apart from both, so
//! the film records it without knowing the strategy that reads it.

use glam::Vec3A;

/// A pixel's samples as adaptive sampling sees them: display values
/// (linear, clamped to 0..1, as the image shows them).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Spread {
    /// Sum of the display values.
    pub sum: Vec3A,
    /// Sum of their squares.
    pub squares: Vec3A,
    /// The display sum before the pixel's last pass: the pass's samples
    /// are one half of the pixel's, those before it the other.
    pub earlier: Vec3A,
    /// The sample count behind `earlier`.
    pub earlier_samples: u32,
}

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
pub(crate) fn variance_estimate(n: u32, spread: &Spread) -> f32 {
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
pub(crate) fn display_value(v: Vec3A) -> Vec3A {
    v.max(Vec3A::ZERO).min(Vec3A::ONE)
}
