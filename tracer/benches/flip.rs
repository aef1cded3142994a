//! FLIP of a 512 x 512 pair: the Rust port (`tracer::metrics::flip`, on
//! rayon's threads) against NVIDIA's C++ through `nv-flip` (one thread),
//! both from 8-bit images to the mean error. The pair: the showcase's
//! golden scaled to 512 x 512, and that image with every channel moved by
//! up to 8 levels (sampling noise).

use std::hint::black_box;
use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use image::{RgbImage, imageops};

fn pair() -> (RgbImage, RgbImage) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../app/tests/golden/showcase.png");
    let golden = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .into_rgb8();
    let reference = imageops::resize(&golden, 512, 512, imageops::FilterType::Triangle);
    let mut test = reference.clone();
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    for c in test.iter_mut() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        *c = (i32::from(*c) + (state >> 40) as i32 % 17 - 8).clamp(0, 255) as u8;
    }
    (reference, test)
}

fn nv_flip_mean(reference: &RgbImage, test: &RgbImage) -> f32 {
    let (w, h) = reference.dimensions();
    let image = |i: &RgbImage| nv_flip::FlipImageRgb8::with_data(w, h, i.as_raw());
    let errors = nv_flip::flip(
        image(reference),
        image(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    nv_flip::FlipPool::from_image(&errors).mean()
}

fn flip(c: &mut Criterion) {
    let (reference, test) = pair();
    let mut group = c.benchmark_group("flip/512x512");
    group.sample_size(20);
    group.bench_function("port", |b| {
        b.iter(|| black_box(tracer::metrics::flip(&reference, &test).unwrap()))
    });
    group.bench_function("nv-flip", |b| {
        b.iter(|| black_box(nv_flip_mean(&reference, &test)))
    });
    group.finish();
}

criterion_group!(benches, flip);
criterion_main!(benches);
