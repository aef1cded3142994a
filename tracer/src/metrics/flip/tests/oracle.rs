//! The port against NVIDIA's code (`nv-flip`), pixel by pixel: on the
//! golden images paired with their variants and with perturbations of
//! themselves, on synthetic images (edges, gradients, noise, saturated
//! colours, tiny and non-square sizes) and on random small images.

use std::path::Path;

use image::{Rgb, RgbImage, imageops};
use proptest::prelude::*;

use super::super::*;
use super::{Noise, flat, noise};

/// Largest difference allowed between the port and the oracle, per pixel
/// and for the mean.
const TOLERANCE: f32 = 1e-4;

fn oracle(reference: &RgbImage, test: &RgbImage) -> Vec<f32> {
    let (w, h) = reference.dimensions();
    let image = |i: &RgbImage| nv_flip::FlipImageRgb8::with_data(w, h, i.as_raw());
    nv_flip::flip(
        image(reference),
        image(test),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    )
    .to_vec()
}

fn mean(errors: &[f32]) -> f64 {
    errors.iter().map(|&e| f64::from(e)).sum::<f64>() / errors.len() as f64
}

/// The largest per-pixel difference of port and oracle on the pair, after
/// checking it and the means' difference against [`TOLERANCE`].
fn check(name: &str, reference: &RgbImage, test: &RgbImage) -> f32 {
    let port = error_map(reference, test, DEFAULT_PIXELS_PER_DEGREE);
    let oracle = oracle(reference, test);
    assert_eq!(port.len(), oracle.len(), "{name}");
    let (worst, at) = port
        .iter()
        .zip(&oracle)
        .map(|(p, o)| (p - o).abs())
        .enumerate()
        .fold(
            (0.0f32, 0),
            |(d, i), (j, e)| if e > d { (e, j) } else { (d, i) },
        );
    let w = reference.width() as usize;
    assert!(
        worst <= TOLERANCE && port.iter().all(|e| e.is_finite()),
        "{name}: pixel ({}, {}) port {} oracle {}",
        at % w,
        at / w,
        port[at],
        oracle[at]
    );
    let means = (mean(&port) - mean(&oracle)).abs();
    assert!(
        means <= f64::from(TOLERANCE),
        "{name}: means differ by {means}"
    );
    worst
}

/// `image` with each channel moved by up to `amplitude` levels.
fn perturbed(image: &RgbImage, amplitude: u8, seed: u64) -> RgbImage {
    let mut noise = Noise(seed);
    let mut out = image.clone();
    for c in out.iter_mut() {
        let step = i16::from(noise.byte() % (2 * amplitude + 1)) - i16::from(amplitude);
        *c = (i16::from(*c) + step).clamp(0, 255) as u8;
    }
    out
}

/// `image` moved one pixel right, its first column repeated.
fn shifted(image: &RgbImage) -> RgbImage {
    RgbImage::from_fn(image.width(), image.height(), |x, y| {
        *image.get_pixel(x.saturating_sub(1), y)
    })
}

fn goldens() -> Vec<(String, RgbImage)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../app/tests/golden");
    let mut goldens: Vec<(String, RgbImage)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "png"))
        .map(|path| {
            let name = path.file_stem().unwrap().to_string_lossy().into_owned();
            let image = image::open(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            (name, image.into_rgb8())
        })
        .collect();
    goldens.sort_by(|a, b| a.0.cmp(&b.0));
    goldens
}

#[test]
fn goldens_with_their_variants_and_perturbations_match_the_oracle() {
    let goldens = goldens();
    assert!(goldens.len() >= 30, "{} goldens", goldens.len());
    let mut worst = 0.0f32;
    let mut pairs = 0;
    let mut pair = |name: &str, a: &RgbImage, b: &RgbImage| {
        worst = worst.max(check(name, a, b));
        pairs += 1;
    };
    for (name, image) in &goldens {
        pair(&format!("{name} noise 2"), image, &perturbed(image, 2, 1));
        pair(&format!("{name} noise 40"), image, &perturbed(image, 40, 2));
        pair(&format!("{name} shifted"), image, &shifted(image));
        pair(&format!("{name} shifted, reversed"), &shifted(image), image);
        let Some((scene, _variant)) = name.split_once('.') else {
            continue;
        };
        let (_, golden) = goldens
            .iter()
            .find(|(n, _)| n == scene)
            .expect("a variant's scene");
        // The scene's golden at the variant's size: the same view, rendered
        // differently.
        let (w, h) = image.dimensions();
        let scene_image = imageops::resize(golden, w, h, imageops::FilterType::Triangle);
        pair(&format!("{name} against {scene}"), &scene_image, image);
    }
    // Different scenes of one size: large errors everywhere.
    for neighbours in goldens.windows(2) {
        let ((a_name, a), (b_name, b)) = (&neighbours[0], &neighbours[1]);
        if a.dimensions() == b.dimensions() {
            pair(&format!("{a_name} against {b_name}"), a, b);
        }
    }
    eprintln!("{pairs} golden pairs: largest per-pixel difference {worst:e}");
    assert!(pairs > 150);
}

#[test]
fn synthetic_images_match_the_oracle() {
    let step = |w: u32, h: u32, at: u32| {
        RgbImage::from_fn(w, h, move |x, _| Rgb([if x < at { 20 } else { 230 }; 3]))
    };
    // A horizontal ramp in `levels` bands.
    let ramp = |w: u32, h: u32, levels: u32| {
        RgbImage::from_fn(w, h, move |x, _| {
            let v = (x * 255 / (w - 1)) * levels / 256 * 255 / (levels - 1);
            Rgb([v as u8, 128, 255 - v as u8])
        })
    };
    let diagonal = RgbImage::from_fn(40, 40, |x, y| {
        Rgb(if x > y { [255, 0, 0] } else { [0, 0, 255] })
    });
    let dots = RgbImage::from_fn(40, 40, |x, y| {
        Rgb([if x % 7 == 3 && y % 5 == 2 { 255 } else { 10 }; 3])
    });
    let cases: Vec<(&str, RgbImage, RgbImage)> = vec![
        (
            "1x1 black and white",
            flat(1, 1, [0; 3]),
            flat(1, 1, [255; 3]),
        ),
        (
            "1x1 colours",
            flat(1, 1, [200, 30, 90]),
            flat(1, 1, [10, 240, 60]),
        ),
        ("3x2 noise", noise(3, 2, 7), noise(3, 2, 8)),
        ("1x17 noise", noise(1, 17, 9), noise(1, 17, 10)),
        ("23x1 noise", noise(23, 1, 11), noise(23, 1, 12)),
        ("non-square noise", noise(37, 19, 13), noise(37, 19, 14)),
        ("step moved", step(40, 24, 20), step(40, 24, 21)),
        ("step against flat", step(40, 24, 20), flat(40, 24, [20; 3])),
        ("ramp banded", ramp(50, 30, 256), ramp(50, 30, 8)),
        ("ramp against noise", ramp(50, 30, 256), noise(50, 30, 15)),
        (
            "primaries",
            diagonal.clone(),
            RgbImage::from_fn(40, 40, |x, y| {
                Rgb(if x >= y { [0, 255, 0] } else { [255, 255, 0] })
            }),
        ),
        ("diagonal against itself", diagonal.clone(), diagonal),
        ("dots against flat", dots.clone(), flat(40, 40, [10; 3])),
        ("dots perturbed", dots.clone(), perturbed(&dots, 3, 16)),
        ("black and white", flat(9, 9, [0; 3]), flat(9, 9, [255; 3])),
    ];
    for (name, a, b) in &cases {
        check(name, a, b);
        check(&format!("{name}, reversed"), b, a);
    }
}

#[test]
fn the_magma_map_matches_the_oracles() {
    let oracle = nv_flip::magma_lut().to_vec();
    assert_eq!(MAGMA_LUT.as_flattened(), oracle.as_slice());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_small_images_match_the_oracle(
        w in 1u32..24,
        h in 1u32..24,
        seeds in (1u64..u64::MAX, 1u64..u64::MAX),
        amplitude in 0u8..128,
    ) {
        let a = noise(w, h, seeds.0);
        // Smooth or noisy, close or far.
        let a = imageops::blur(&a, 1.5);
        let b = perturbed(&a, amplitude, seeds.1);
        check("random", &a, &b);
    }
}
