//! Random numbers as a pure function of (pixel, sample, dimension, seed), so
//! an image never depends on thread count or scheduling, and the sample
//! patterns built on them: jittered strata, multi-jittered light samples,
//! lens disks.

use std::ops::Range;

use glam::Vec2;

/// Where a random number is used: the pixel, the sample index within it and
/// the seed. Each call to `SampleStream::next_1d` moves to the next
/// dimension, so a path through the tracer draws its numbers in a fixed order.
#[derive(Debug, Clone, Copy)]
pub struct SampleStream {
    key: u64,
    /// The pixel's key under the seed, the same for all its samples: what
    /// [`SampleStream::next_2d_across_samples`] spreads a pattern over.
    pixel_key: u64,
    sample: u32,
    dimension: u32,
    /// With adaptive sampling, the sample's place in its pixel's order:
    /// [`SampleStream::next_2d_across_samples`] then takes that point of a
    /// scrambled (0, 2)-sequence, so every prefix of the pixel's samples
    /// is stratified, not only a whole round.
    rank: Option<u32>,
}

impl SampleStream {
    /// The stream for `sample` of pixel `pixel` under `seed`.
    pub fn new(seed: u64, pixel: u32, sample: u32) -> Self {
        let key = mix64(seed ^ mix64(((pixel as u64) << 32) | sample as u64));
        let pixel_key = mix64(seed.rotate_left(32) ^ mix64(u64::from(pixel) | 1 << 63));
        Self {
            key,
            pixel_key,
            sample,
            dimension: 0,
            rank: None,
        }
    }

    /// This stream for the `rank`-th sample a pixel takes in adaptive
    /// order: its patterns across samples become prefix-stratified (see
    /// [`SampleStream::next_2d_across_samples`]).
    pub(crate) fn ranked(self, rank: u32) -> Self {
        Self {
            rank: Some(rank),
            ..self
        }
    }

    /// The next 32 random bits: picks a pattern for [`multi_jittered`].
    #[inline]
    pub(crate) fn next_u32(&mut self) -> u32 {
        let bits = mix64(self.key.wrapping_add(self.dimension as u64));
        self.dimension += 1;
        (bits >> 32) as u32
    }

    /// This sample's point of one `n` x `n` multi-jittered pattern that all
    /// the pixel's samples share: the pattern is chosen by the dimension
    /// (and by the round of `n * n` samples), the point by the sample index,
    /// through a permutation of the round so that it does not follow the
    /// pixel strata that anti-aliasing visits in order. Over a round the
    /// points fill each of the `n x n` cells once and each of the `n * n`
    /// slabs along either axis once, so a straight edge along an axis is
    /// met within one sample. Takes two dimensions, as [`Self::next_2d`].
    ///
    /// A ranked stream ([`SampleStream::ranked`]) takes instead point
    /// `rank` of Sobol's first two dimensions, its index shuffled and its
    /// digits scrambled by the dimension (Burley's hash-based Owen
    /// scrambling): any first 2^j samples of a pixel, where adaptive
    /// sampling may stop, fall once in each of the 2^j boxes of every
    /// elementary shape, as a whole multi-jittered round does, and the
    /// dimensions (light samples, lens) stay independent of each other.
    pub(crate) fn next_2d_across_samples(&mut self, n: u32) -> Vec2 {
        if let Some(rank) = self.rank {
            return scrambled_sobol(rank, self.sobol_seed());
        }
        let n = n.clamp(1, MAX_N);
        let count = n * n;
        let round = self.sample / count;
        let pattern =
            mix64(self.pixel_key ^ ((u64::from(round) << 32) | u64::from(self.dimension)));
        self.dimension += 2;
        let index = permute(self.sample % count, count, (pattern >> 32) as u32);
        multi_jittered(index, n, pattern as u32)
    }

    /// This sample's points on one light, each given to `each` with its
    /// weight (the weights sum to 1): the one point of
    /// [`SampleStream::next_2d_across_samples`], or with a ranked stream
    /// points `indices(rank)` of the pixel's scrambled Sobol sequence (in
    /// place of point `rank`). An aligned block of indices is a net of its
    /// own, so a pixel whose few samples take several points each
    /// averages as many well spread points as one that took a sample a
    /// point. Takes two dimensions.
    pub(crate) fn next_light_points(
        &mut self,
        n: u32,
        indices: impl FnOnce(u32) -> Range<u32>,
        mut each: impl FnMut(Vec2, f32),
    ) {
        let Some(rank) = self.rank else {
            each(self.next_2d_across_samples(n), 1.0);
            return;
        };
        let seed = self.sobol_seed();
        let indices = indices(rank);
        let weight = 1.0 / indices.len().max(1) as f32;
        for index in indices {
            each(scrambled_sobol(index, seed), weight);
        }
    }

    /// The scramble of a ranked stream's Sobol points in the next two
    /// dimensions, the same for all the pixel's samples; takes them.
    fn sobol_seed(&mut self) -> u64 {
        let seed = mix64(self.pixel_key ^ (u64::from(self.dimension) << 40 | 0x50b0));
        self.dimension += 2;
        seed
    }

    /// The next number in `[0, 1)`.
    #[inline]
    pub(crate) fn next_1d(&mut self) -> f32 {
        let bits = mix64(self.key.wrapping_add(self.dimension as u64));
        self.dimension += 1;
        // 24 high bits give every float in [0, 1) with spacing 2^-24.
        (bits >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    /// Two numbers in `[0, 1)`.
    #[inline]
    pub(crate) fn next_2d(&mut self) -> Vec2 {
        Vec2::new(self.next_1d(), self.next_1d())
    }
}

/// 32 random bits of pixel `pixel` under `seed`, the same for all its
/// samples: the digits that shift a pixel's adaptive sample pattern.
pub(crate) fn pixel_digits(seed: u64, pixel: u32) -> u32 {
    (mix64(seed ^ 0x5ca1_ab1e_0000_0000 ^ u64::from(pixel)) >> 32) as u32
}

/// Point `index` of a shuffled and scrambled copy of Sobol's first two
/// dimensions chosen by `seed`: the index by a nested uniform shuffle
/// (aligned blocks of 2^j indices stay aligned blocks, and an aligned
/// block of a (0, 2)-sequence is a (0, j, 2)-net), each coordinate by
/// Owen scrambling, which keeps every net a net.
pub(crate) fn scrambled_sobol(index: u32, seed: u64) -> Vec2 {
    let index = nested_uniform_scramble(index, seed as u32);
    let x = nested_uniform_scramble(index.reverse_bits(), (seed >> 32) as u32);
    let y = nested_uniform_scramble(sobol_second(index), mix64(seed) as u32);
    // 24 high bits, as `next_1d`: every value stays below 1.
    let unit = |v: u32| (v >> 8) as f32 * (1.0 / (1u32 << 24) as f32);
    Vec2::new(unit(x), unit(y))
}

/// Point `k` of the second dimension of Sobol's sequence, as 32 bits of a
/// fraction (its generator matrix is Pascal's triangle mod 2): the xor of
/// the matrix's columns for the bits of `k`, a byte at a time from
/// [`SOBOL_SECOND`]. The scrambled index has all 32 bits set at random:
/// with a loop over them (a branch a bit), [`scrambled_sobol`] took about
/// a sixth of an adaptive render with soft shadows (perf).
pub(crate) fn sobol_second(k: u32) -> u32 {
    let t = &SOBOL_SECOND;
    t[0][(k & 0xff) as usize]
        ^ t[1][(k >> 8 & 0xff) as usize]
        ^ t[2][(k >> 16 & 0xff) as usize]
        ^ t[3][(k >> 24) as usize]
}

/// [`sobol_second`] of every byte value in each of the index's 4 bytes.
static SOBOL_SECOND: [[u32; 256]; 4] = sobol_second_tables();

const fn sobol_second_tables() -> [[u32; 256]; 4] {
    // Column i of the generator matrix: 1 << 31, each next one the last
    // xor itself shifted right by one.
    let mut columns = [0u32; 32];
    let (mut i, mut column) = (0, 1u32 << 31);
    while i < 32 {
        columns[i] = column;
        column ^= column >> 1;
        i += 1;
    }
    let mut tables = [[0u32; 256]; 4];
    let mut byte = 0;
    while byte < 4 {
        let mut value = 0;
        while value < 256 {
            let (mut bit, mut y) = (0, 0u32);
            while bit < 8 {
                if value >> bit & 1 != 0 {
                    y ^= columns[byte * 8 + bit];
                }
                bit += 1;
            }
            tables[byte][value] = y;
            value += 1;
        }
        byte += 1;
    }
    tables
}

/// Owen scrambling of a 32-bit fraction (first digit in the top bit) by
/// `seed`: each digit flipped by a hash of the digits before it (Burley,
/// "Practical Hash-based Owen Scrambling", 2020: Laine and Karras's
/// permutation on the reversed bits).
fn nested_uniform_scramble(x: u32, seed: u32) -> u32 {
    let mut v = x.reverse_bits().wrapping_add(seed);
    v ^= v.wrapping_mul(0x6c50_b47c);
    v ^= v.wrapping_mul(0xb82f_1e52);
    v ^= v.wrapping_mul(0xc7af_e638);
    v ^= v.wrapping_mul(0x8d22_f6e6);
    v.reverse_bits()
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

/// Largest N the multi-jittered patterns serve: the renderer's
/// `MAX_SAMPLES`, for whose 4096 fine columns the jitter stays exact.
const MAX_N: u32 = 64;

/// Point `index` of the `n` x `n` multi-jittered pattern `pattern` (Chiu,
/// Shirley and Wang's arrangement, with Kensler's correlated shuffles):
/// `index` picks the cell (row-major), and within it the point sits in
/// the sub-column and sub-row that permutations of the rows and of the
/// columns give, so the `n * n` points fill every cell, every one of the
/// `n * n` columns of width `1 / n^2` and every such row once each, then
/// jitter inside that sub-cell. Computed alone, in O(1), for any index.
pub(crate) fn multi_jittered(index: u32, n: u32, pattern: u32) -> Vec2 {
    let n = n.clamp(1, MAX_N);
    let (col, row) = (index % n, (index / n) % n);
    let sub_col = permute(row, n, pattern ^ 0xa511_e9b3);
    let sub_row = permute(col, n, pattern ^ 0x63d8_3595);
    let bits = mix64((u64::from(pattern) << 32) | u64::from(index));
    // Eleven bits of jitter, at the centres of 2048 bins: `k + j` stays
    // exact in f32 for all 4096 columns of the largest N, and the rounded
    // quotient stays more than an ulp inside its column.
    let jitter = |shift: u32| (((bits >> shift) & 0x7ff) as f32 + 0.5) / 2048.0;
    let fine = (n * n) as f32;
    Vec2::new(
        ((col * n + sub_col) as f32 + jitter(52)) / fine,
        ((row * n + sub_row) as f32 + jitter(40)) / fine,
    )
}

/// A permutation of `0..len` chosen by `key`: a bijection of the smallest
/// power-of-two range holding `len` (xor, odd multiplies and xorshifts, each
/// invertible), walked until it lands inside `0..len`.
pub(crate) fn permute(i: u32, len: u32, key: u32) -> u32 {
    if len <= 1 {
        return 0;
    }
    let mask = u32::MAX >> (len - 1).leading_zeros();
    let shift = (mask.count_ones() / 2).max(1);
    let mut x = i & mask;
    // Walked from `i`, a bijection passes at most the `mask + 1 - len`
    // (fewer than `len`) values outside before it lands inside: `len`
    // steps always suffice. The bound makes a broken step (one that is no
    // bijection) a wrong answer in the tests, not a hang.
    for _ in 0..len {
        x ^= key & mask;
        x = x.wrapping_mul(0x9e37_79b1) & mask;
        x ^= x >> shift;
        x = x.wrapping_add(key >> 16) & mask;
        x = x.wrapping_mul(0x85eb_ca6b) & mask;
        x ^= x >> shift;
        if x < len {
            return x;
        }
    }
    x
}

/// Maps the unit square onto the unit disk preserving strata (Shirley and
/// Chiu's concentric mapping), so jittered lens samples stay well spread.
pub(crate) fn concentric_disk(u: Vec2) -> Vec2 {
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
pub(crate) fn stratum_order(n: u32) -> Vec<u32> {
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
    fn sobol_second_by_bytes_is_the_matrix_product() {
        let by_bits = |mut k: u32| {
            let (mut direction, mut y) = (1u32 << 31, 0);
            while k != 0 {
                if k & 1 != 0 {
                    y ^= direction;
                }
                k >>= 1;
                direction ^= direction >> 1;
            }
            y
        };
        let mut k = 0u32;
        for i in 0..100_000u32 {
            assert_eq!(sobol_second(i), by_bits(i), "{i}");
            k = k.wrapping_mul(0x9e37_79b9).wrapping_add(0x7f4a_7c15);
            assert_eq!(sobol_second(k), by_bits(k), "{k}");
        }
        assert_eq!(sobol_second(u32::MAX), by_bits(u32::MAX));
    }

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

    /// Cell, column and row of a point on the `n * n` fine grid.
    fn fine_cells(p: Vec2, n: u32) -> (u32, u32, u32) {
        let fine = f64::from(n * n);
        let (x, y) = (f64::from(p.x) * fine, f64::from(p.y) * fine);
        let (i, j) = (x.floor() as u32, y.floor() as u32);
        ((j / n) * n + i / n, i, j)
    }

    /// Every cell once, every fine column and row once.
    fn assert_multi_jittered(points: &[Vec2], n: u32, what: &str) {
        let count = (n * n) as usize;
        assert_eq!(points.len(), count);
        let (mut cells, mut cols, mut rows) = (vec![0; count], vec![0; count], vec![0; count]);
        for &p in points {
            assert!(
                (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y),
                "{what}: {p}"
            );
            let (cell, col, row) = fine_cells(p, n);
            cells[cell as usize] += 1;
            cols[col as usize] += 1;
            rows[row as usize] += 1;
        }
        for (name, hits) in [("cell", cells), ("column", cols), ("row", rows)] {
            assert!(hits.iter().all(|&h| h == 1), "{what}: {name}s {hits:?}");
        }
    }

    #[test]
    fn multi_jittered_points_fill_cells_columns_and_rows_once() {
        for n in [1, 2, 3, 4, 5, 7, 8, 16, 64] {
            for pattern in [0, 1, 0xdead_beef, 77_777] {
                let points: Vec<Vec2> = (0..n * n).map(|k| multi_jittered(k, n, pattern)).collect();
                assert_multi_jittered(&points, n, &format!("N = {n}, pattern {pattern}"));
            }
        }
        // Patterns differ.
        assert_ne!(multi_jittered(3, 4, 1), multi_jittered(3, 4, 2));
    }

    #[test]
    fn multi_jittered_patterns_are_many() {
        // A pattern's rows take their sub-columns, and its columns their
        // sub-rows, from permutations its bits choose: the random patterns
        // of 512 pixels give many arrangements, not a few repeated.
        let n = 16;
        let arrangements = |axis: usize| {
            let mut seen: Vec<Vec<u32>> = (0..512)
                .map(|k| {
                    let pattern = mix64(k) as u32;
                    (0..n)
                        .map(|line| {
                            // Along column 0 for the rows, row 0 for the columns.
                            let index = [line * n, line][axis];
                            let (_, column, row) = fine_cells(multi_jittered(index, n, pattern), n);
                            [column, row][axis] % n
                        })
                        .collect()
                })
                .collect();
            seen.sort_unstable();
            seen.dedup();
            seen.len()
        };
        for axis in [0, 1] {
            let count = arrangements(axis);
            assert!(
                count >= 64,
                "axis {axis}: {count} (125 today; at most 32 with a salt's `^` as `|` or `&`)"
            );
        }
    }

    #[test]
    fn permutations_are_those_an_independent_port_computes() {
        // Every image's samples are drawn through these permutations. The
        // values come from an independent port of `permute`'s description
        // (`scripts/permute_oracle.py` prints them), not from this code.
        let table = |len: u32, key: u32, count: u32| -> Vec<u32> {
            (0..count).map(|i| permute(i, len, key)).collect()
        };
        assert_eq!(
            table(16, 0x2545_f491, 16),
            [2, 6, 10, 14, 3, 13, 11, 5, 0, 4, 8, 12, 1, 15, 9, 7]
        );
        assert_eq!(
            table(100, 0xdead_beef, 16),
            [49, 22, 73, 31, 66, 90, 40, 6, 67, 91, 4, 42, 15, 58, 72, 39]
        );
        assert_eq!(table(5, 0x9e37_79b9, 5), [0, 1, 2, 4, 3]);
    }

    #[test]
    fn permute_is_a_permutation_that_depends_on_the_key() {
        for len in [1, 2, 3, 5, 8, 9, 16, 17, 100, 4096] {
            let mut seen: Vec<u32> = (0..len).map(|i| permute(i, len, 12345)).collect();
            let order = seen.clone();
            seen.sort_unstable();
            assert_eq!(seen, (0..len).collect::<Vec<_>>(), "len {len}");
            if len >= 5 {
                let other: Vec<u32> = (0..len).map(|i| permute(i, len, 999)).collect();
                assert_ne!(order, other, "len {len}");
            }
        }
    }

    #[test]
    fn samples_of_a_pixel_share_one_multi_jittered_pattern_per_round() {
        for n in [2, 3, 4, 6] {
            let count = n * n;
            for round in 0..2 {
                // Draw a number first, as a path does before its light
                // samples: the pattern belongs to the dimension.
                let points: Vec<Vec2> = (round * count..(round + 1) * count)
                    .map(|sample| {
                        let mut stream = SampleStream::new(5, 42, sample);
                        stream.next_1d();
                        stream.next_2d_across_samples(n)
                    })
                    .collect();
                assert_multi_jittered(&points, n, &format!("N = {n}, round {round}"));
            }
            let first = |pixel| {
                let mut stream = SampleStream::new(5, pixel, 0);
                stream.next_2d_across_samples(n)
            };
            assert_ne!(first(42), first(43), "another pixel, another pattern");
        }
    }

    #[test]
    fn ranked_samples_are_stratified_in_every_power_of_two_prefix() {
        for pixel in [0, 42, 1234] {
            // Two dimensions of one stream (a light's, then a second
            // light's): each on its own stratified and different.
            let points = |skip: usize| -> Vec<Vec2> {
                (0..64)
                    .map(|k| {
                        let mut stream = SampleStream::new(9, pixel, 1000 + k).ranked(k);
                        for _ in 0..skip {
                            stream.next_2d_across_samples(8);
                        }
                        stream.next_2d_across_samples(8)
                    })
                    .collect()
            };
            let (first, second) = (points(0), points(1));
            assert_ne!(first, second);
            for points in [first, second] {
                for j in 0..=6u32 {
                    for a in 0..=j {
                        // 2^a columns by 2^(j - a) rows: one point each.
                        let mut boxes: Vec<u32> = points[..1 << j]
                            .iter()
                            .map(|p| {
                                let col = (p.x * (1u32 << a) as f32) as u32;
                                let row = (p.y * (1u32 << (j - a)) as f32) as u32;
                                row * (1 << a) + col
                            })
                            .collect();
                        boxes.sort_unstable();
                        assert_eq!(
                            boxes,
                            (0..1 << j).collect::<Vec<_>>(),
                            "pixel {pixel}, j {j}, a {a}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn light_points_are_one_point_or_the_ranked_range() {
        let points = |stream: &mut SampleStream| {
            let mut points = Vec::new();
            stream.next_light_points(4, |rank| 4 * rank..4 * rank + 4, |p, w| points.push((p, w)));
            points
        };
        // Uniform sampling: the pattern's one point, at full weight.
        let (mut first, mut second) = (SampleStream::new(3, 17, 5), SampleStream::new(3, 17, 5));
        assert_eq!(
            points(&mut first),
            [(second.next_2d_across_samples(4), 1.0)]
        );
        // Ranked: points 4 k .. 4 k + 4 of the sequence point k takes alone.
        let alone = |k: u32| {
            let mut stream = SampleStream::new(3, 17, 100 + k).ranked(k);
            stream.next_2d_across_samples(8)
        };
        let mut ranked = SampleStream::new(3, 17, 100).ranked(1);
        let taken = points(&mut ranked);
        assert_eq!(taken.len(), 4);
        for (i, (p, w)) in taken.into_iter().enumerate() {
            assert_eq!((p, w), (alone(4 + i as u32), 0.25));
        }
        // Two dimensions taken, as for one point.
        let mut one = SampleStream::new(3, 17, 100).ranked(1);
        one.next_2d_across_samples(8);
        assert_eq!(ranked.next_1d(), one.next_1d());
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
    fn concentric_disk_maps_square_rings_to_circles_and_sides_to_quarter_arcs() {
        // Shirley and Chiu's mapping: the square's ring at distance r from
        // its centre goes to the circle of radius r, each side to a quarter
        // of it, the angle moving linearly along the side: -pi/4 to pi/4
        // on the right side, pi/4 to 3 pi/4 on the top, and so on.
        use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};
        for ring in [0.25f32, 0.5, 1.0] {
            for step in 0..=8 {
                let t = step as f32 / 4.0 - 1.0;
                // Counter-clockwise from the right side, each with the
                // angle at its middle.
                let sides = [
                    (Vec2::new(ring, ring * t), 0.0),
                    (Vec2::new(-ring * t, ring), FRAC_PI_2),
                    (Vec2::new(-ring, -ring * t), PI),
                    (Vec2::new(ring * t, -ring), -FRAC_PI_2),
                ];
                for (p, middle) in sides {
                    let d = concentric_disk((p + Vec2::ONE) / 2.0);
                    let want = Vec2::from_angle(middle + FRAC_PI_4 * t) * ring;
                    assert!((d - want).length() < 1e-5, "{p}: {d}, want {want}");
                }
            }
        }
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

    #[test]
    fn mix64_is_splitmix64() {
        // SplitMix64's outputs from seed 0: its state steps by the gamma.
        let gamma = 0x9E37_79B9_7F4A_7C15u64;
        let outputs = [
            0xE220_A839_7B1D_CDAF,
            0x6E78_9E6A_A1B9_65F4,
            0x06C4_5D18_8009_454F,
        ];
        for (k, want) in outputs.into_iter().enumerate() {
            assert_eq!(mix64(gamma.wrapping_mul(k as u64)), want, "output {k}");
        }
    }

    #[test]
    fn each_draw_is_a_new_dimension() {
        let mut s = SampleStream::new(7, 3, 1); // patterns first, from dimension 0
        let points: Vec<Vec2> = (0..4).map(|_| s.next_2d_across_samples(4)).collect();
        let bits: Vec<u32> = (0..4).map(|_| s.next_u32()).collect();
        let units: Vec<f32> = (0..4).map(|_| s.next_1d()).collect();
        for k in 1..4 {
            assert!(
                !bits[..k].contains(&bits[k]) && !units[..k].contains(&units[k]),
                "{bits:?} {units:?}"
            );
            assert!(!points[..k].contains(&points[k]), "{points:?}");
        }
    }

    #[test]
    fn every_kind_of_draw_takes_the_next_dimension() {
        // From dimension 0, as a shading point draws: j draws of any kind
        // leave the stream where j plain draws leave it.
        let start = SampleStream::new(7, 3, 1);
        let (mut bits, mut pairs, mut plain) = (start, start, start);
        for _ in 0..4 {
            bits.next_u32();
            plain.next_1d();
        }
        assert_eq!(bits.next_1d(), plain.next_1d());
        let mut plain = start;
        let firsts: Vec<Vec2> = (0..3).map(|_| pairs.next_2d()).collect();
        let by_ones: Vec<Vec2> = (0..3)
            .map(|_| Vec2::new(plain.next_1d(), plain.next_1d()))
            .collect();
        assert_eq!(firsts, by_ones);
        assert!(firsts.iter().all(|p| p.x > 0.0 && p.y > 0.0), "{firsts:?}");
    }

    #[test]
    fn patterns_across_samples_change_with_the_round_and_the_pixel() {
        let first = |pixel, sample| SampleStream::new(5, pixel, sample).next_2d_across_samples(4);
        // Sample 16 starts the second round of a 4 x 4 pattern: another one.
        assert!((0..64).all(|p| first(p, 0) != first(p, 16)));
        // Sample 0's cell is a shuffled one, not the same in every pixel.
        let cell = |p| (first(p, 0) * 4.0).floor();
        assert!((1..64).any(|p| cell(p) != cell(0)));
    }

    #[test]
    fn every_bit_of_the_seed_and_pixel_moves_the_digits() {
        for seed in [0, u64::MAX, 0x1234_5678_9abc_def0] {
            let mut digits: Vec<u32> = (0..256).map(|p| pixel_digits(seed, p)).collect();
            digits.sort_unstable();
            digits.dedup();
            assert_eq!(digits.len(), 256, "seed {seed:x}");
        }
        assert!((0..64).all(|b| pixel_digits(1 << b, 5) != pixel_digits(0, 5)));
        // Sobol's x scramble takes the seed's high half: seeds differing
        // there give other points.
        let xs: Vec<f32> = (1..17u64).map(|i| scrambled_sobol(0, i << 32).x).collect();
        assert!(xs.windows(2).all(|w| w[0] != w[1]), "{xs:?}");
    }
}
