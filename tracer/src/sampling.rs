//! Random numbers as a pure function of (pixel, sample, dimension, seed), so
//! an image never depends on thread count or scheduling, and the sample
//! patterns built on them: jittered strata, lens disks, light areas.

use glam::Vec2;

/// Where a random number is used: the pixel, the sample index within it and
/// the seed. Each call to [`SampleStream::next_1d`] moves to the next
/// dimension, so a path through the tracer draws its numbers in a fixed order.
#[derive(Debug, Clone, Copy)]
pub struct SampleStream {
    key: u64,
    dimension: u32,
}

impl SampleStream {
    /// The stream for `sample` of pixel `pixel` under `seed`.
    pub fn new(seed: u64, pixel: u32, sample: u32) -> Self {
        let key = mix64(seed ^ mix64(((pixel as u64) << 32) | sample as u64));
        Self { key, dimension: 0 }
    }

    /// The next number in `[0, 1)`.
    #[inline]
    pub fn next_1d(&mut self) -> f32 {
        let bits = mix64(self.key.wrapping_add(self.dimension as u64));
        self.dimension += 1;
        // 24 high bits give every float in [0, 1) with spacing 2^-24.
        (bits >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    /// Two numbers in `[0, 1)`.
    #[inline]
    pub fn next_2d(&mut self) -> Vec2 {
        Vec2::new(self.next_1d(), self.next_1d())
    }
}

/// SplitMix64's finaliser: a bijective mix with good avalanche.
#[inline]
fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A point jittered inside stratum `stratum` of an `n` x `n` grid over the
/// unit square: row-major strata, `u` a uniform point of the unit square.
#[inline]
pub fn jittered(stratum: u32, n: u32, u: Vec2) -> Vec2 {
    let n = n.max(1);
    let cell = Vec2::new((stratum % n) as f32, (stratum / n) as f32);
    (cell + u) / n as f32
}

/// Maps the unit square onto the unit disk preserving strata (Shirley and
/// Chiu's concentric mapping), so jittered lens samples stay well spread.
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let p = u * 2.0 - Vec2::ONE;
    if p == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, theta) = if p.x.abs() > p.y.abs() {
        (p.x, std::f32::consts::FRAC_PI_4 * (p.y / p.x))
    } else {
        (
            p.y,
            std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (p.x / p.y),
        )
    };
    Vec2::new(r * theta.cos(), r * theta.sin())
}

/// The order in which the `n * n` strata of a pixel are visited by
/// progressive passes: each prefix is spread over the pixel (a bit-reversed
/// walk), so the first passes already approximate the final average.
pub fn stratum_order(n: u32) -> Vec<u32> {
    let count = n.max(1) * n.max(1);
    let bits = u32::BITS - (count - 1).leading_zeros();
    let mut order: Vec<u32> = (0..1u32 << bits)
        .map(|i| {
            if bits == 0 {
                0
            } else {
                i.reverse_bits() >> (u32::BITS - bits)
            }
        })
        .filter(|&s| s < count)
        .collect();
    // Bit reversal over a row-major index spreads rows first; interleave
    // columns by visiting the strata in that order along a diagonal shift.
    for s in order.iter_mut() {
        let (x, y) = (*s % n.max(1), *s / n.max(1));
        *s = y * n.max(1) + (x + y) % n.max(1);
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_deterministic_and_distinct() {
        let mut a = SampleStream::new(7, 10, 3);
        let mut b = SampleStream::new(7, 10, 3);
        let mut c = SampleStream::new(7, 11, 3);
        let xs: Vec<f32> = (0..8).map(|_| a.next_1d()).collect();
        let ys: Vec<f32> = (0..8).map(|_| b.next_1d()).collect();
        let zs: Vec<f32> = (0..8).map(|_| c.next_1d()).collect();
        assert_eq!(xs, ys);
        assert_ne!(xs, zs);
        assert!(xs.iter().all(|x| (0.0..1.0).contains(x)));
    }

    #[test]
    fn uniform_mean_and_variance() {
        let mut sum = 0.0f64;
        let mut sq = 0.0f64;
        let n = 200_000;
        for i in 0..n {
            let x = SampleStream::new(1, i, 0).next_1d() as f64;
            sum += x;
            sq += x * x;
        }
        let mean = sum / n as f64;
        let var = sq / n as f64 - mean * mean;
        assert!((mean - 0.5).abs() < 0.005, "{mean}");
        assert!((var - 1.0 / 12.0).abs() < 0.002, "{var}");
    }

    #[test]
    fn jittered_points_stay_in_their_stratum() {
        let n = 4;
        for s in 0..16 {
            let p = jittered(s, n, Vec2::new(0.999, 0.0));
            assert_eq!((p.x * 4.0) as u32, s % 4);
            assert_eq!((p.y * 4.0) as u32, s / 4);
        }
    }

    #[test]
    fn concentric_disk_stays_in_the_unit_disk() {
        for i in 0..=20 {
            for j in 0..=20 {
                let u = Vec2::new(i as f32 / 20.0, j as f32 / 20.0);
                assert!(concentric_disk(u).length() <= 1.0 + 1e-6);
            }
        }
        assert!((concentric_disk(Vec2::new(1.0, 0.5)) - Vec2::new(1.0, 0.0)).length() < 1e-6);
    }

    #[test]
    fn stratum_order_is_a_permutation_with_spread_prefixes() {
        for n in 1..=8 {
            let mut order = stratum_order(n);
            assert_eq!(order.len() as u32, n * n);
            // The first n strata cover every row and every column once.
            let rows: std::collections::BTreeSet<u32> =
                order[..n as usize].iter().map(|s| s / n).collect();
            let cols: std::collections::BTreeSet<u32> =
                order[..n as usize].iter().map(|s| s % n).collect();
            if n.is_power_of_two() {
                assert_eq!(rows.len() as u32, n, "n={n} {order:?}");
                assert_eq!(cols.len() as u32, n, "n={n} {order:?}");
            }
            order.sort_unstable();
            assert_eq!(order, (0..n * n).collect::<Vec<_>>());
        }
    }
}
