//! The order of a pixel's adaptive samples over its strata.

use crate::sampling::{sobol_second, stratum_order};

/// The order in which a pixel's adaptive samples visit its `m * m` strata,
/// as the uniform passes whose samples they take (see `stratum_order`):
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
    /// The order for `m` x `m` strata a round (`m` below 1 counts as 1).
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
