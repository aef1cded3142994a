//! The error estimates against their formulas computed another way.

use glam::Vec3A;

use crate::render::estimate::{Spread, display_value, error_estimate, variance_estimate};

/// A film's spread of `earlier` then `last` samples (display values).
fn spread(earlier: &[Vec3A], last: &[Vec3A]) -> (u32, Spread) {
    let (sum, squares) = earlier
        .iter()
        .chain(last)
        .fold(Default::default(), |(s, q): (Vec3A, Vec3A), &v| {
            (s + v, q + v * v)
        });
    let earlier_sum = earlier.iter().sum();
    let n = (earlier.len() + last.len()) as u32;
    (
        n,
        Spread {
            sum,
            squares,
            earlier: earlier_sum,
            earlier_samples: earlier.len() as u32,
        },
    )
}

#[test]
fn error_is_the_halves_mean_difference_scaled_by_their_sizes() {
    // Two samples then six: per channel, means 0.5 | 0.2, 0.25 | 0.25,
    // 0.1 | 0.7, differences 0.3, 0, -0.6 (mean square 0.15); scale
    // sqrt(2 * 6) / 8.
    let earlier = [Vec3A::new(0.4, 0.5, 0.2), Vec3A::new(0.6, 0.0, 0.0)];
    let last = [Vec3A::new(0.2, 0.25, 0.7); 6];
    let (n, s) = spread(&earlier, &last);
    let want = 0.15f32.sqrt() * 12f32.sqrt() / 8.0;
    assert!(
        (error_estimate(n, &s) - want).abs() < 1e-6,
        "{} {want}",
        error_estimate(n, &s)
    );
    // Either half empty: nothing to compare yet.
    assert_eq!(error_estimate(6, &spread(&[], &last).1), f32::INFINITY);
    assert_eq!(error_estimate(2, &spread(&earlier, &[]).1), f32::INFINITY);
}

#[test]
fn variance_is_the_channels_unbiased_variance_over_n() {
    let samples = [
        Vec3A::new(0.0, 0.5, 0.2),
        Vec3A::new(1.0, 0.5, 0.6),
        Vec3A::new(0.5, 0.5, 0.1),
    ];
    for n in 2..=3 {
        let (n, s) = spread(&samples[..n as usize], &[]);
        // Two passes over the samples: their mean, then the squares about it.
        let mean = s.sum / n as f32;
        let deviations: Vec3A = samples[..n as usize]
            .iter()
            .map(|&v| (v - mean) * (v - mean))
            .sum();
        let want = (deviations.element_sum() / (n - 1) as f32 / 3.0 / n as f32).sqrt();
        assert!(
            (variance_estimate(n, &s) - want).abs() < 1e-6,
            "n = {n}: {} {want}",
            variance_estimate(n, &s)
        );
    }
    assert_eq!(
        variance_estimate(1, &spread(&samples[..1], &[]).1),
        f32::INFINITY
    );
    assert_eq!(variance_estimate(0, &Spread::default()), f32::INFINITY);
}

#[test]
fn display_values_are_clamped_with_nan_as_zero() {
    let v = display_value(Vec3A::new(-1.0, 0.25, 3.0));
    assert_eq!(v, Vec3A::new(0.0, 0.25, 1.0));
    assert_eq!(display_value(Vec3A::splat(f32::NAN)), Vec3A::ZERO);
}
