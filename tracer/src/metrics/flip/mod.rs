// The FLIP port in this folder (mod.rs, magma.rs) is translated from NVIDIA's
// reference C++ code of FLIP (https://github.com/NVlabs/flip), as shipped in the
// nv-flip-sys 0.1.1 crate, and is distributed under its licence:
//
// Copyright (c) 2020-2022, NVIDIA CORPORATION & AFFILIATES. All rights reserved.
//
// Redistribution and use in source and binary forms, with or without
// modification, are permitted provided that the following conditions are met:
//
// 1. Redistributions of source code must retain the above copyright notice, this
// list of conditions and the following disclaimer.
//
// 2. Redistributions in binary form must reproduce the above copyright notice,
// this list of conditions and the following disclaimer in the documentation
// and/or other materials provided with the distribution.
//
// 3. Neither the name of the copyright holder nor the names of its
// contributors may be used to endorse or promote products derived from
// this software without specific prior written permission.
//
// THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS"
// AND ANY EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE
// IMPLIED WARRANTIES OF MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE
// DISCLAIMED. IN NO EVENT SHALL THE COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE
// FOR ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL, EXEMPLARY, OR CONSEQUENTIAL
// DAMAGES (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF SUBSTITUTE GOODS OR
// SERVICES; LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION) HOWEVER
// CAUSED AND ON ANY THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY,
// OR TORT (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE
// OF THIS SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
//
// SPDX-FileCopyrightText: Copyright (c) 2020-2022 NVIDIA CORPORATION & AFFILIATES
// SPDX-License-Identifier: BSD-3-Clause

//! NVIDIA's FLIP (LDR-FLIP: Andersson et al., "FLIP: A Difference Evaluator
//! for Alternating Images", HPG 2020), ported from the reference C++ code
//! (`CPP/image.h`, `CPP/color.h`, `common/sharedflip.h`) that the `nv-flip`
//! crate binds. A port because the web build cannot link C++; `nv-flip`
//! stays as the tests' oracle, which this port matches per pixel.
//!
//! Per pixel of two sRGB images:
//! 1. both images go to YCxCz, an opponent space linear in XYZ;
//! 2. each is blurred by the contrast sensitivity functions (CSF) of a
//!    viewer at `pixels_per_degree`, then moved to CIELab with the Hunt
//!    adjustment; their HyAB distance, compressed, is the colour error;
//! 3. edges and points (first and second derivatives of a Gaussian) of the
//!    lightness are compared: the feature difference;
//! 4. the two are pooled: `colour error ^ (1 - feature difference)`.
//!
//! Every filter is separable (a horizontal pass, then a vertical one) and
//! every sum adds its taps in the reference's order, so the results agree
//! with the C++ to rounding; both passes run on rows in parallel.

mod magma;

use image::RgbImage;
use rayon::prelude::*;

pub use magma::MAGMA_LUT;

/// The viewing condition FLIP's authors default to: a 0.7 m wide 4K
/// monitor seen from 0.7 m, 67 pixels per degree of visual angle.
pub const DEFAULT_PIXELS_PER_DEGREE: f32 = 67.0;

/// An RGB, XYZ, YCxCz or Lab triple (the reference's `color3`).
type Colour = [f32; 3];

// FLIP's constants (`FLIPConstants` in sharedflip.h).
/// Exponent compressing the colour error.
const GQC: f32 = 0.7;
/// Share of the largest colour error mapped to [0, GPT].
const GPC: f32 = 0.4;
/// Where the colour error's two linear pieces meet.
const GPT: f32 = 0.95;
/// Width of the feature detectors, in degrees.
const GW: f32 = 0.082;
/// Exponent of the feature difference.
const GQF: f32 = 0.5;

// The CSFs as sums of Gaussians `a sqrt(pi / b) exp(-pi^2 x^2 / b)`
// (`GaussianConstants`): Y, Cx and Cz's first, then Cz's second.
const CSF_A1: Colour = [1.0, 1.0, 34.1];
const CSF_B1: Colour = [0.0047, 0.0053, 0.04];
const CSF_A2_CZ: f32 = 13.5;
const CSF_B2: Colour = [1.0e-5, 1.0e-5, 0.025];

/// The D65 white point in XYZ and its inverse, as the reference writes them.
#[allow(clippy::excessive_precision)]
const D65: Colour = [0.950428545, 1.000000000, 1.088900371];
#[allow(clippy::excessive_precision)]
const INV_D65: Colour = [1.052156925, 1.000000000, 0.918357670];

/// Per-pixel LDR-FLIP errors in 0..=1, row-major, of `test` against
/// `reference` (sRGB-encoded; empty images give no errors): what
/// `nv_flip::flip(reference, test, pixels_per_degree)` returns.
///
/// # Panics
/// When the images differ in size (callers check, see `metrics::flip`).
pub(crate) fn error_map(reference: &RgbImage, test: &RgbImage, pixels_per_degree: f32) -> Vec<f32> {
    assert_eq!(reference.dimensions(), test.dimensions());
    let (w, h) = (reference.width() as usize, reference.height() as usize);
    if w == 0 || h == 0 {
        return Vec::new();
    }
    let filters = Filters::new(pixels_per_degree);
    let srgb = srgb_decoding_table();

    // Horizontal passes: each row holds both images' planes, side by side.
    let row_len = 2 * PLANES * w;
    let mut rows = vec![0.0; h * row_len];
    rows.par_chunks_mut(row_len).enumerate().for_each_init(
        || Channels::new(w, filters.radius()),
        |channels, (y, out)| {
            let (r, t) = out.split_at_mut(PLANES * w);
            for (image, out) in [(reference, r), (test, t)] {
                channels.load(image, y, &srgb);
                channels.filter(&filters, out);
            }
        },
    );

    // Vertical passes, then each pixel's error.
    let colour_max = max_colour_distance();
    let mut errors = vec![0.0; w * h];
    errors.par_chunks_mut(w).enumerate().for_each_init(
        || vec![0.0; 2 * SUMS * w],
        |sums, (y, out)| {
            let (r, t) = sums.split_at_mut(SUMS * w);
            filters.vertical_pass(&rows, row_len, 0, y, r);
            filters.vertical_pass(&rows, row_len, PLANES, y, t);
            let (r, t) = (&*r, &*t);
            for (x, error) in out.iter_mut().enumerate() {
                let sum = |s: &[f32], i: usize| s[i * w + x];
                let filtered = |s: &[f32]| [sum(s, Y), sum(s, CX), sum(s, CZ1) + sum(s, CZ2)];
                let colour = colour_error(filtered(r), filtered(t), colour_max);
                let features = |s: &[f32]| {
                    let edge = (sum(s, DX) * sum(s, DX) + sum(s, DY) * sum(s, DY)).sqrt();
                    let point = (sum(s, DDX) * sum(s, DDX) + sum(s, DDY) * sum(s, DDY)).sqrt();
                    (edge, point)
                };
                *error = pool(colour, feature_difference(features(r), features(t)));
            }
        },
    );
    errors
}

/// The planes of one image after the horizontal pass, in a row: Y, Cx and
/// Cz (twice) under their CSF kernels, then the lightness under the first
/// and second derivatives and under the Gaussian.
const PLANES: usize = 7;
/// The sums of one image after the vertical pass, in a row.
const SUMS: usize = 8;
// What each sum is: the CSF-filtered Y and Cx, Cz's two Gaussians (added
// together they are Cz), then the lightness's first and second derivatives
// along x and along y.
const Y: usize = 0;
const CX: usize = 1;
const CZ1: usize = 2;
const CZ2: usize = 3;
const DX: usize = 4;
const DDX: usize = 5;
const DY: usize = 6;
const DDY: usize = 7;

/// The channels of [`Channels`].
const CHANNELS: usize = 4;
const CH_Y: usize = 0;
const CH_CX: usize = 1;
const CH_CZ: usize = 2;
/// Y scaled to 0..=1, the lightness the feature detectors look at.
const CH_LIGHTNESS: usize = 3;

/// FLIP's one-dimensional kernels; each 2D filter is a product of two.
#[derive(Debug)]
struct Filters {
    /// The CSFs': Y, Cx, Cz's first and Cz's second Gaussian.
    csf: [Vec<f32>; 4],
    /// The feature detectors': a Gaussian, its first and second derivatives.
    features: [Vec<f32>; 3],
}

impl Filters {
    fn new(pixels_per_degree: f32) -> Self {
        Self {
            csf: csf_kernels(pixels_per_degree),
            features: feature_kernels(pixels_per_degree),
        }
    }

    /// The largest kernel's radius: how far a pass reads past a pixel.
    fn radius(&self) -> usize {
        self.csf
            .iter()
            .chain(&self.features)
            .map(|k| k.len() / 2)
            .max()
            .unwrap_or(0)
    }

    /// The channel and kernel of each of the horizontal pass's [`PLANES`].
    fn horizontal(&self) -> [(usize, &[f32]); PLANES] {
        let [y, cx, cz1, cz2] = &self.csf;
        let [gaussian, first, second] = &self.features;
        [
            (CH_Y, y),
            (CH_CX, cx),
            (CH_CZ, cz1),
            (CH_CZ, cz2),
            (CH_LIGHTNESS, first),
            (CH_LIGHTNESS, second),
            (CH_LIGHTNESS, gaussian),
        ]
    }

    /// The plane and kernel of each of the vertical pass's [`SUMS`]: the
    /// derivatives along x are smoothed along y, and the Gaussian-smoothed
    /// plane is differentiated along y.
    fn vertical(&self) -> [(usize, &[f32]); SUMS] {
        let [y, cx, cz1, cz2] = &self.csf;
        let [gaussian, first, second] = &self.features;
        [
            (0, y),
            (1, cx),
            (2, cz1),
            (3, cz2),
            (4, gaussian),
            (5, gaussian),
            (6, first),
            (6, second),
        ]
    }

    /// The vertical pass at row `y` of one image whose planes start at
    /// `first_plane` in each `row_len` row of `rows` (`h` rows): its
    /// [`SUMS`] into `sums`. Rows above and below the image repeat its edge.
    fn vertical_pass(
        &self,
        rows: &[f32],
        row_len: usize,
        first_plane: usize,
        y: usize,
        sums: &mut [f32],
    ) {
        let w = sums.len() / SUMS;
        let h = rows.len() / row_len;
        for ((plane, kernel), out) in self.vertical().into_iter().zip(sums.chunks_exact_mut(w)) {
            out.fill(0.0);
            let radius = kernel.len() / 2;
            for (tap, &weight) in kernel.iter().enumerate() {
                let source = (y + tap).saturating_sub(radius).min(h - 1);
                let start = source * row_len + (first_plane + plane) * w;
                accumulate(out, weight, &rows[start..start + w]);
            }
        }
    }
}

/// `out += weight * source`, element by element: one tap of a kernel over
/// a whole row, which the compiler vectorises.
fn accumulate(out: &mut [f32], weight: f32, source: &[f32]) {
    for (o, &s) in out.iter_mut().zip(source) {
        *o += weight * s;
    }
}

/// One row of an image in YCxCz and lightness, padded at both ends with
/// copies of the edge pixels (the reference clamps its reads to the image),
/// so the horizontal pass reads every tap from a slice.
#[derive(Debug)]
struct Channels {
    width: usize,
    pad: usize,
    channels: [Vec<f32>; CHANNELS],
}

impl Channels {
    fn new(width: usize, pad: usize) -> Self {
        Self {
            width,
            pad,
            channels: std::array::from_fn(|_| vec![0.0; width + 2 * pad]),
        }
    }

    /// Row `y` of `image`, sRGB decoded with `srgb` (see
    /// [`srgb_decoding_table`]), into the channels.
    fn load(&mut self, image: &RgbImage, y: usize, srgb: &[f32; 256]) {
        let (w, pad) = (self.width, self.pad);
        let row = &image.as_raw()[y * 3 * w..(y + 1) * 3 * w];
        for (x, pixel) in row.chunks_exact(3).enumerate() {
            let rgb = [0, 1, 2].map(|c| srgb[usize::from(pixel[c])]);
            let ycxcz = xyz_to_ycxcz(linear_rgb_to_xyz(rgb));
            for (channel, value) in [ycxcz[0], ycxcz[1], ycxcz[2], lightness(ycxcz[0])]
                .into_iter()
                .enumerate()
            {
                self.channels[channel][pad + x] = value;
            }
        }
        for channel in &mut self.channels {
            let (first, last) = (channel[pad], channel[pad + w - 1]);
            channel[..pad].fill(first);
            channel[pad + w..].fill(last);
        }
    }

    /// The horizontal pass over the loaded row: its [`PLANES`] into `out`.
    fn filter(&self, filters: &Filters, out: &mut [f32]) {
        let w = self.width;
        for ((channel, kernel), out) in filters
            .horizontal()
            .into_iter()
            .zip(out.chunks_exact_mut(w))
        {
            out.fill(0.0);
            let start = self.pad - kernel.len() / 2;
            for (tap, &weight) in kernel.iter().enumerate() {
                accumulate(
                    out,
                    weight,
                    &self.channels[channel][start + tap..start + tap + w],
                );
            }
        }
    }
}

/// The CSFs' kernels (`setSpatialFilters`), `2 r + 1` taps each (r from
/// [`csf_radius`]): Y's and Cx's each sum to 1; Cz's CSF is a sum of two
/// Gaussians, so its 2D filter is `cz1(x) cz1(y) + cz2(x) cz2(y)`, scaled
/// so that it sums to 1.
fn csf_kernels(pixels_per_degree: f32) -> [Vec<f32>; 4] {
    let radius = csf_radius(pixels_per_degree) as i32;
    let delta_x = 1.0 / pixels_per_degree;
    let taps: Vec<[f32; 4]> = (-radius..=radius)
        .map(|i| {
            let ix = i as f32 * delta_x;
            let ix2 = ix * ix;
            [
                gaussian(ix2, CSF_A1[0], CSF_B1[0]),
                gaussian(ix2, CSF_A1[1], CSF_B1[1]),
                gaussian_sqrt(ix2, CSF_A1[2], CSF_B1[2]),
                gaussian_sqrt(ix2, CSF_A2_CZ, CSF_B2[2]),
            ]
        })
        .collect();
    let sum = |k: usize| taps.iter().fold(0.0, |s, t| s + t[k]);
    let (sum_cz1, sum_cz2) = (sum(2), sum(3));
    let norm_cz = 1.0 / (sum_cz1 * sum_cz1 + sum_cz2 * sum_cz2).sqrt();
    let norms = [1.0 / sum(0), 1.0 / sum(1), norm_cz, norm_cz];
    std::array::from_fn(|k| taps.iter().map(|t| t[k] * norms[k]).collect())
}

/// The CSF kernels' radius in pixels (`calculateSpatialFilterRadius`):
/// three standard deviations of the widest Gaussian.
fn csf_radius(pixels_per_degree: f32) -> usize {
    let widest = CSF_B1.into_iter().chain(CSF_B2).fold(0.0, f32::max);
    (3.0 * (widest / (2.0 * PI_SQ)).sqrt() * pixels_per_degree).ceil() as usize
}

const PI: f32 = std::f32::consts::PI;
const PI_SQ: f32 = PI * PI;

/// One Gaussian of a CSF, `a sqrt(pi / b) exp(-pi^2 x^2 / b)`, at `x2 = x^2`.
fn gaussian(x2: f32, a: f32, b: f32) -> f32 {
    a * (PI / b).sqrt() * (-PI_SQ * x2 / b).exp()
}

/// [`gaussian`] with the square root of its scale: one factor of a
/// separated term of Cz's CSF.
fn gaussian_sqrt(x2: f32, a: f32, b: f32) -> f32 {
    (a * (PI / b).sqrt()).sqrt() * (-PI_SQ * x2 / b).exp()
}

/// The feature detectors' kernels (`setFeatureFilter`), radius three
/// standard deviations of `0.5 GW` degrees: a Gaussian summing to 1, its
/// first and second derivatives with their positive weights summing to 1
/// and their negative ones to -1.
fn feature_kernels(pixels_per_degree: f32) -> [Vec<f32>; 3] {
    let std_dev = 0.5 * GW * pixels_per_degree;
    let radius = (3.0 * std_dev).ceil() as i32;
    let taps: Vec<[f32; 3]> = (-radius..=radius)
        .map(|i| {
            let x = i as f32;
            let g = (-(x * x) / (2.0 * std_dev * std_dev)).exp();
            [g, -x * g, (x * x / (std_dev * std_dev) - 1.0) * g]
        })
        .collect();
    let g_sum = taps.iter().fold(0.0, |s, t| s + t[0]);
    // The sums of the positive and of the negated negative weights.
    let signed_sums = |k: usize| {
        taps.iter().fold((0.0, 0.0), |(positive, negative), t| {
            if t[k] > 0.0 {
                (positive + t[k], negative)
            } else {
                (positive, negative - t[k])
            }
        })
    };
    let derivative = |k: usize| {
        let (positive, negative) = signed_sums(k);
        taps.iter()
            .map(|t| t[k] / if t[k] > 0.0 { positive } else { negative })
            .collect()
    };
    [
        taps.iter().map(|t| t[0] / g_sum).collect(),
        derivative(1),
        derivative(2),
    ]
}

/// The 256 sRGB levels decoded to linear values, as the reference does it
/// per pixel (`level / 255`, then [`srgb_to_linear`]).
fn srgb_decoding_table() -> [f32; 256] {
    std::array::from_fn(|level| srgb_to_linear(level as f32 / 255.0))
}

/// The sRGB transfer function's inverse.
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear sRGB (D65) to CIE XYZ, with the reference's exact fractions.
fn linear_rgb_to_xyz([r, g, b]: Colour) -> Colour {
    const A: [[f32; 3]; 3] = [
        [
            10135552.0 / 24577794.0,
            8788810.0 / 24577794.0,
            4435075.0 / 24577794.0,
        ],
        [
            2613072.0 / 12288897.0,
            8788810.0 / 12288897.0,
            887015.0 / 12288897.0,
        ],
        [
            1425312.0 / 73733382.0,
            8788810.0 / 73733382.0,
            70074185.0 / 73733382.0,
        ],
    ];
    A.map(|row| row[0] * r + row[1] * g + row[2] * b)
}

/// CIE XYZ to linear sRGB (D65), [`linear_rgb_to_xyz`]'s inverse.
fn xyz_to_linear_rgb([x, y, z]: Colour) -> Colour {
    #[allow(clippy::excessive_precision)]
    const A: [[f32; 3]; 3] = [
        [3.241003275, -1.537398934, -0.498615861],
        [-0.969224334, 1.875930071, 0.041554224],
        [0.055639423, -0.204011202, 1.057148933],
    ];
    A.map(|row| row[0] * x + row[1] * y + row[2] * z)
}

/// CIE XYZ to CIELab relative to D65.
fn xyz_to_lab(xyz: Colour) -> Colour {
    const DELTA: f32 = 6.0 / 29.0;
    const DELTA_SQUARE: f32 = DELTA * DELTA;
    const DELTA_CUBE: f32 = DELTA * DELTA_SQUARE;
    const FACTOR: f32 = 1.0 / (3.0 * DELTA_SQUARE);
    const TERM: f32 = 4.0 / 29.0;
    let [x, y, z] = [0, 1, 2].map(|c| {
        let t = xyz[c] * INV_D65[c];
        if t > DELTA_CUBE {
            t.powf(1.0 / 3.0)
        } else {
            FACTOR * t + TERM
        }
    });
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

/// CIE XYZ to YCxCz: CIELab without its cube roots, so linear, so the
/// CSFs can filter it.
fn xyz_to_ycxcz(xyz: Colour) -> Colour {
    let [x, y, z] = [0, 1, 2].map(|c| xyz[c] * INV_D65[c]);
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

/// [`xyz_to_ycxcz`]'s inverse.
fn ycxcz_to_xyz([luminance, cx, cz]: Colour) -> Colour {
    let y = (luminance + 16.0) / 116.0;
    let (cx, cz) = (cx / 500.0, cz / 200.0);
    let xyz = [y + cx, y, y - cz];
    [0, 1, 2].map(|c| xyz[c] * D65[c])
}

/// YCxCz's Y scaled to 0..=1 for the feature detectors.
fn lightness(y: f32) -> f32 {
    const ONE_OVER_116: f32 = 1.0 / 116.0;
    const SIXTEEN_OVER_116: f32 = 16.0 / 116.0;
    y * ONE_OVER_116 + SIXTEEN_OVER_116
}

/// Clamps to 0..=1 as the reference's `Min`/`Max` macros do (NaN is 0).
fn clamp01(v: f32) -> f32 {
    let v = if v > 0.0 { v } else { 0.0 };
    if v > 1.0 { 1.0 } else { v }
}

/// The Hunt effect: chroma scaled with lightness (`Hunt`), so dark
/// colours differ less.
fn hunt([l, a, b]: Colour) -> Colour {
    [l, 0.01 * l * a, 0.01 * l * b]
}

/// HyAB distance: city-block in lightness, Euclidean in chroma, which
/// suits large colour differences better than Euclidean Lab.
fn hyab(p: Colour, q: Colour) -> f32 {
    let (da, db) = (p[1] - q[1], p[2] - q[2]);
    (p[0] - q[0]).abs() + (da * da + db * db).sqrt()
}

/// A filtered YCxCz colour as FLIP compares it: clamped to the sRGB gamut,
/// in CIELab with the Hunt adjustment.
fn perceived(ycxcz: Colour) -> Colour {
    let rgb = xyz_to_linear_rgb(ycxcz_to_xyz(ycxcz)).map(clamp01);
    hunt(xyz_to_lab(linear_rgb_to_xyz(rgb)))
}

/// The largest compressed colour distance, between pure green and pure
/// blue (`computeMaxDistance`): the colour error's scale.
fn max_colour_distance() -> f32 {
    let lab = |rgb: Colour| hunt(xyz_to_lab(linear_rgb_to_xyz(rgb)));
    hyab(lab([0.0, 1.0, 0.0]), lab([0.0, 0.0, 1.0])).powf(GQC)
}

/// The colour error of two filtered YCxCz colours in 0..=1: the HyAB
/// distance compressed by [`GQC`], then mapped linearly in two pieces so
/// that small distances use most of the range (see [`remap_colour`]).
fn colour_error(reference: Colour, test: Colour, max_distance: f32) -> f32 {
    remap_colour(
        hyab(perceived(reference), perceived(test)).powf(GQC),
        max_distance,
    )
}

/// A compressed distance `d` in `0..=max` to 0..=1: `GPC max` goes to
/// `GPT`, `max` to 1.
fn remap_colour(d: f32, max: f32) -> f32 {
    let knee = GPC * max;
    if d < knee {
        d * (GPT / knee)
    } else {
        GPT + ((d - knee) / (max - knee)) * (1.0 - GPT)
    }
}

/// The feature difference in 0..=1 from the (edge, point) strengths of the
/// reference and the test: the larger change, scaled and compressed.
fn feature_difference((edge_r, point_r): (f32, f32), (edge_t, point_t): (f32, f32)) -> f32 {
    let normalisation = 1.0 / 2.0f32.sqrt();
    let (edge, point) = ((edge_r - edge_t).abs(), (point_r - point_t).abs());
    let larger = if edge > point { edge } else { point };
    (normalisation * larger).powf(GQF)
}

/// FLIP's pooling of a pixel's colour error and feature difference: a
/// changed edge or point raises even a small colour error towards 1.
fn pool(colour: f32, feature: f32) -> f32 {
    colour.powf(1.0 - feature)
}

#[cfg(test)]
mod tests;
