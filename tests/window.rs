//! The real window on a real (virtual) display: `.ci/run` runs these under
//! Xvfb with Mesa's software renderer (`cargo test --test window --
//! --ignored`). Without a display they are skipped, as `cargo test` alone
//! cannot open a window.

use std::path::PathBuf;
use std::process::Command;

/// The viewport's background where no image is drawn (see `gui::viewport`).
const BACKGROUND: [u8; 3] = [24, 24, 24];

fn screenshot_path(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("workbench-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Opens the window on the bundled default scene, lets it render for a few
/// seconds, and checks the middle of the window shows an image: many
/// colours, mostly not the empty viewport's grey.
#[test]
#[ignore = "needs a display: .ci/run runs it under Xvfb"]
fn the_window_shows_a_rendered_image_after_a_few_seconds() {
    let shot = screenshot_path("window.png");
    let output = Command::new(env!("CARGO_BIN_EXE_workbench"))
        .args([
            "--screenshot",
            shot.to_str().unwrap(),
            "--screenshot-after",
            "5",
        ])
        .env("XDG_CONFIG_HOME", shot.parent().unwrap())
        .env("HOME", shot.parent().unwrap())
        .output()
        .expect("the workbench binary runs");
    assert!(
        output.status.success(),
        "the window failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let image = image::open(&shot)
        .unwrap_or_else(|e| panic!("cannot read the screenshot {}: {e}", shot.display()))
        .to_rgb8();
    let (w, h) = image.dimensions();
    assert!(w >= 640 && h >= 400, "window of {w} x {h}");
    // The middle fifth of the window lies inside the image area.
    let (x0, y0, x1, y1) = (w * 2 / 5, h * 2 / 5, w * 3 / 5, h * 3 / 5);
    let mut colours = std::collections::HashSet::new();
    let mut background = 0u32;
    let mut total = 0u32;
    for y in y0..y1 {
        for x in x0..x1 {
            let p = image.get_pixel(x, y).0;
            background += u32::from(p == BACKGROUND);
            total += 1;
            colours.insert(p);
        }
    }
    assert!(
        colours.len() >= 64,
        "the image area is nearly uniform ({} colours): {}",
        colours.len(),
        shot.display()
    );
    assert!(
        background * 10 < total,
        "the image area is mostly empty viewport: {}",
        shot.display()
    );
    std::fs::remove_dir_all(shot.parent().unwrap()).ok();
}
