//! Tests of the FLIP port: its maths step by step (`maths`), then the
//! whole metric against NVIDIA's code, the `nv-flip` crate (`oracle`).

mod maths;
mod oracle;

use image::{Rgb, RgbImage};

/// A deterministic stream of bytes (xorshift), for noise and perturbations.
struct Noise(u64);

impl Noise {
    fn byte(&mut self) -> u8 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 24) as u8
    }
}

fn flat(w: u32, h: u32, rgb: [u8; 3]) -> RgbImage {
    RgbImage::from_pixel(w, h, Rgb(rgb))
}

fn noise(w: u32, h: u32, seed: u64) -> RgbImage {
    let mut noise = Noise(seed);
    RgbImage::from_fn(w, h, |_, _| Rgb([noise.byte(), noise.byte(), noise.byte()]))
}
