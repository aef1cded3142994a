//! Determinism: the same scene, settings and seed give byte-identical PNG
//! files across runs and thread counts, even with every random feature on
//! (jittered anti-aliasing, soft shadows from point and area lights, depth
//! of field), because every random number is a pure function of pixel,
//! sample, dimension and seed, and tiles are summed in a fixed order.

use std::path::Path;

use crate::support::scenes::spheres_on_a_floor;
use crate::support::{Scratch, workbench_ok};

/// Renders the scene with `threads` workers and `seed`; returns the PNG bytes.
fn render(scene: &Path, out: &Path, threads: u32, seed: u32) -> Vec<u8> {
    let (threads, seed) = (threads.to_string(), seed.to_string());
    workbench_ok(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--soft-shadows",
        "--aa",
        "--dof",
        "--depth",
        "3",
        "--threads",
        &threads,
        "--seed",
        &seed,
    ]);
    std::fs::read(out).unwrap()
}

#[test]
fn same_seed_gives_identical_png_bytes_across_runs_and_thread_counts() {
    let dir = Scratch::new("determinism");
    let scene = dir.join("random.p3f");
    // The aperture puts the far sphere out of focus; an area light beside
    // the point light.
    let text = spheres_on_a_floor(
        40,
        30,
        "aperture 3\nfocal 1.2",
        "al -3 -2 5  0 0 0  1.5 1 0.6 0.6 0.6\nspp 3",
    );
    std::fs::write(&scene, text).unwrap();
    let reference = render(&scene, &dir.join("t1a.png"), 1, 42);
    for (name, threads) in [("t1b", 1), ("t2a", 2), ("t2b", 2), ("t3", 3)] {
        let bytes = render(&scene, &dir.join(format!("{name}.png")), threads, 42);
        assert!(
            bytes == reference,
            "{name} ({threads} threads) differs from the first single-threaded run"
        );
    }
    // The seed does reach the image: otherwise the test would prove nothing
    // about the random features.
    let other = render(&scene, &dir.join("seed7.png"), 2, 7);
    assert_ne!(other, reference, "a different seed gave the same image");
}
