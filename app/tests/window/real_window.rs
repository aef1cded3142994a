//! The real window on a real (virtual) display: `scripts/test.sh` runs these
//! under Xvfb with Mesa's software renderer (`cargo test --test window --
//! --ignored`). Without a display they are skipped, as `cargo test` alone
//! cannot open a window.

use std::path::Path;
use std::process::{Command, Output};
use std::time::Duration;

use crate::support::{RUN_TIMEOUT, Scratch, output_within};
use image::RgbImage;

/// The viewport's background where no image is drawn (see `gui::viewport`).
const BACKGROUND: [u8; 3] = [24, 24, 24];
/// The scene both the window and the headless render show.
const SCENE: &str = "../scenes/balls_low.p3f";

/// Runs `command` (killed if it outlives [`RUN_TIMEOUT`]: only a guard
/// against a window that never finishes, as the window takes its
/// screenshot as soon as the render is done), which must succeed.
fn run_bounded(command: Command) -> Output {
    let shown = format!("{command:?}");
    let output = output_within(command, RUN_TIMEOUT).unwrap_or_else(|e| panic!("{shown}: {e}"));
    assert!(
        output.status.success(),
        "{shown} failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

fn workbench(home: &Path) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_workbench"));
    // A fresh home: no settings from an earlier session, and none written
    // anywhere else (eframe keeps its state in the data folder).
    for folder in ["HOME", "XDG_CONFIG_HOME", "XDG_DATA_HOME", "XDG_CACHE_HOME"] {
        command.env(folder, home);
    }
    command
}

/// Walks from `from` by `step` while the pixel is not the background;
/// the last image pixel's coordinate, or `None` at the shot's edge.
fn edge(shot: &RgbImage, from: (i64, i64), step: (i64, i64)) -> Option<i64> {
    let (mut x, mut y) = from;
    loop {
        let (nx, ny) = (x + step.0, y + step.1);
        if nx < 0 || ny < 0 || nx >= shot.width() as i64 || ny >= shot.height() as i64 {
            return None;
        }
        if shot.get_pixel(nx as u32, ny as u32).0 == BACKGROUND {
            return Some(if step.0 != 0 { x } else { y });
        }
        (x, y) = (nx, ny);
    }
}

/// Pixels of `reference` whose screen pixel (at their centre, for the image
/// drawn with its top-left corner at `origin` and `scale` screen pixels per
/// image pixel) has neither their colour nor a neighbour's: nearest
/// sampling at a fractional scale may pick the next texel, nothing else.
fn wrong_pixels(shot: &RgbImage, reference: &RgbImage, origin: (f64, f64), scale: f64) -> usize {
    let close = |a: [u8; 3], b: [u8; 3]| (0..3).all(|c| a[c].abs_diff(b[c]) <= 2);
    let (w, h) = (reference.width() as i64, reference.height() as i64);
    let mut wrong = 0;
    for (x, y, _) in reference.enumerate_pixels() {
        let sx = origin.0 + (x as f64 + 0.5) * scale;
        let sy = origin.1 + (y as f64 + 0.5) * scale;
        let fits = sx >= 0.0 && sy >= 0.0 && sx < shot.width() as f64 && sy < shot.height() as f64;
        let matches = fits && {
            let got = shot.get_pixel(sx as u32, sy as u32).0;
            (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                    (0..w).contains(&nx)
                        && (0..h).contains(&ny)
                        && close(got, reference.get_pixel(nx as u32, ny as u32).0)
                })
            })
        };
        wrong += usize::from(!matches);
    }
    wrong
}

/// Finds where the window drew `reference` (fit to the view, centred, with
/// background bars on two opposite sides) and counts the pixels that differ.
fn compare_viewport(shot: &RgbImage, reference: &RgbImage) -> usize {
    let centre = (shot.width() as i64 / 2, shot.height() as i64 / 2);
    let (w, h) = (reference.width() as f64, reference.height() as f64);
    let vertical = (edge(shot, centre, (0, -1)), edge(shot, centre, (0, 1)));
    let horizontal = (edge(shot, centre, (-1, 0)), edge(shot, centre, (1, 0)));
    // The bars give the scale and one coordinate of the corner; the other
    // is searched along the axis the image fills.
    let candidates: Vec<((f64, f64), f64)> = match (vertical, horizontal) {
        ((Some(top), Some(bottom)), _) => {
            let scale = (bottom - top + 1) as f64 / h;
            let width = w * scale;
            (0..width as i64)
                .map(|dx| ((centre.0 as f64 - width + dx as f64, top as f64), scale))
                .collect()
        }
        (_, (Some(left), Some(right))) => {
            let scale = (right - left + 1) as f64 / w;
            let height = h * scale;
            (0..height as i64)
                .map(|dy| ((left as f64, centre.1 as f64 - height + dy as f64), scale))
                .collect()
        }
        _ => panic!("no viewport background around the image"),
    };
    candidates
        .into_iter()
        .map(|(origin, scale)| wrong_pixels(shot, reference, origin, scale))
        .min()
        .expect("a candidate position")
}

/// Where the window's line (`saved screenshot ... drawn at X0,Y0 to
/// X1,Y1`) says it drew the image, in the screenshot's pixels.
fn drawn_at(said: &str) -> [f64; 4] {
    let corners = said
        .split("drawn at ")
        .nth(1)
        .and_then(|rest| rest.lines().next())
        .unwrap_or_else(|| panic!("the window said not where the image is: {said}"));
    let numbers: Vec<f64> = corners
        .split([',', ' '])
        .filter_map(|word| word.parse().ok())
        .collect();
    let rect: [f64; 4] = numbers
        .try_into()
        .unwrap_or_else(|n| panic!("not two corners in {corners:?}: {n:?}"));
    assert!(rect[0] < rect[2] && rect[1] < rect[3], "{said}");
    rect
}

/// The screenshot's pixel at (`x`, `y`) in its own pixels.
fn pixel(shot: &RgbImage, x: f64, y: f64) -> [u8; 3] {
    shot.get_pixel(x as u32, y as u32).0
}

/// Opens the window on a scene, leaves it alone, and lets it photograph
/// itself once the render is done and on screen (no fixed delay): the
/// viewport must show what `workbench render` makes of the same scene with
/// the same settings, pixel for pixel (texture sampling aside). An image one
/// pass short (1 sample instead of 2 x 2) differs in about 4% of its pixels.
#[test]
#[ignore = "needs a display: scripts/test.sh runs it under Xvfb"]
fn the_window_shows_the_final_render_of_the_requested_scene() {
    // The screenshot, the reference and the window's home (settings,
    // shader caches) all go here.
    let dir = Scratch::new("window");
    let shot = dir.join("window.png");
    let reference = dir.join("reference.png");
    let mut window = workbench(&dir);
    window.args(["--scene", SCENE, "--screenshot"]).arg(&shot);
    run_bounded(window);
    let mut render = workbench(&dir);
    render.args(["render", SCENE, "-o"]).arg(&reference);
    run_bounded(render);

    let shot_image = image::open(&shot).expect("the screenshot").to_rgb8();
    let reference_image = image::open(&reference).expect("the reference").to_rgb8();
    let (w, h) = shot_image.dimensions();
    assert!(w >= 640 && h >= 400, "window of {w} x {h}");
    let wrong = compare_viewport(&shot_image, &reference_image);
    let total = (reference_image.width() * reference_image.height()) as usize;
    assert!(
        wrong * 1000 <= total,
        "{wrong} of {total} pixels of the viewport differ from `workbench render` ({})",
        shot.display()
    );
}

/// `--screenshot-after`: the photograph waits for the delay, not for the
/// render, and the window closes with the line saying what it shows.
#[test]
#[ignore = "needs a display: scripts/test.sh runs it under Xvfb"]
fn a_screenshot_after_a_delay_waits_for_the_delay() {
    let dir = Scratch::new("window-delay");
    let shot = dir.join("window.png");
    let mut window = workbench(&dir);
    window
        .args(["--scene", SCENE, "--screenshot"])
        .arg(&shot)
        .args(["--screenshot-after", "2"]);
    let start = std::time::Instant::now();
    let output = run_bounded(window);
    assert!(
        start.elapsed() >= Duration::from_secs(2),
        "taken before the delay"
    );
    let said = String::from_utf8_lossy(&output.stdout);
    assert!(said.contains("saved screenshot"), "{said}");
    let shot_image = image::open(&shot).expect("the screenshot").to_rgb8();
    assert!(shot_image.width() >= 640, "the whole window");
}

/// `--observer`: the window opens with the observer view beside the image
/// (the viewport then fills only the left half), and still finishes its
/// render.
#[test]
#[ignore = "needs a display: scripts/test.sh runs it under Xvfb"]
fn the_window_opens_with_the_observer_on_when_asked() {
    let dir = Scratch::new("window-observer");
    let (plain, observed) = (dir.join("plain.png"), dir.join("observed.png"));
    let said = [(&plain, None), (&observed, Some("--observer"))].map(|(shot, extra)| {
        let mut window = workbench(&dir);
        window.args(["--scene", SCENE, "--screenshot"]).arg(shot);
        window.args(extra);
        let said = String::from_utf8_lossy(&run_bounded(window).stdout).into_owned();
        assert!(said.contains("spp"), "{said}");
        said
    });
    let [plain_said, observed_said] = said;
    let plain_shot = image::open(&plain).unwrap().to_rgb8();
    let observed_shot = image::open(&observed).unwrap().to_rgb8();
    // Probed where each window says it drew the image (the side panels,
    // which the scene list's counts and the sampling controls widen, move
    // it): the image is there in both, and with the observer beside it
    // the render has at most half the width it had, centred vertically
    // with the background above it.
    let plain = drawn_at(&plain_said);
    let observed = drawn_at(&observed_said);
    let centre = |r: [f64; 4]| ((r[0] + r[2]) / 2.0, (r[1] + r[3]) / 2.0);
    let (x, y) = centre(plain);
    assert_ne!(
        pixel(&plain_shot, x, y),
        BACKGROUND,
        "the plain window's image"
    );
    let (x, y) = centre(observed);
    assert_ne!(
        pixel(&observed_shot, x, y),
        BACKGROUND,
        "the observed window's image"
    );
    let width = |r: [f64; 4]| r[2] - r[0];
    assert!(
        width(observed) <= width(plain) / 2.0 + 1.0,
        "the image beside the observer is not halved: {observed:?} against {plain:?}"
    );
    assert!(
        observed[1] > plain[1] + 2.0,
        "{observed:?} against {plain:?}"
    );
    assert_eq!(
        pixel(&observed_shot, x, observed[1] - 2.0),
        BACKGROUND,
        "the halved image's margin"
    );
}

/// A one-step lesson on a red sphere under a black sky, rendered at
/// 40 x 30: what [`assert_lesson_set_up`] looks for.
const RED_SPHERE_LESSON: &str = r#"title = "Eye rays"
chapter = 1

[scene]
p3f = """
v from 0 0 5 at 0 0 0 up 0 1 0 angle 40 resolution 40 30
l 0 5 5 1 1 1
f 1 0 0 1 0 0 0 0 1 0 1
s 0 0 0 1
"""

[[step]]
title = "Pin a pixel"
text = "Pin a pixel on the sphere."
check = { kind = "value", of = "tree eye-object", is = 0 }
solution = { pixel = [20, 15] }
"#;

/// Runs the window with `args` and a screenshot, and checks that it shows
/// [`RED_SPHERE_LESSON`] set up: its scene rendered at the lesson's own
/// resolution, the red sphere in the middle of the image, the lesson's
/// black sky at its corners.
fn assert_lesson_set_up(dir: &Scratch, args: &[&std::ffi::OsStr]) {
    let shot = dir.join("window.png");
    let mut window = workbench(dir);
    window.args(args).arg("--screenshot").arg(&shot);
    let said = String::from_utf8_lossy(&run_bounded(window).stdout).into_owned();
    assert!(said.contains("of 40 x 30"), "{said}");
    let shot = image::open(&shot).expect("the screenshot").to_rgb8();
    let [x0, y0, x1, y1] = drawn_at(&said);
    // Half a lesson pixel in from the corner, and the image's centre.
    let inset = (x1 - x0) / 80.0;
    let [r, g, b] = pixel(&shot, (x0 + x1) / 2.0, (y0 + y1) / 2.0);
    assert!(
        r > 100 && g < 40 && b < 40,
        "not the lesson's red sphere at the centre: {:?}",
        [r, g, b]
    );
    let corner = pixel(&shot, x0 + inset, y0 + inset);
    assert!(
        corner.iter().all(|&c| c < 40),
        "not the lesson's sky in the corner: {corner:?}"
    );
}

/// `--lesson FILE`: the window opens with the lesson's first step set up.
#[test]
#[ignore = "needs a display: scripts/test.sh runs it under Xvfb"]
fn the_window_opens_a_lesson_set_up() {
    let dir = Scratch::new("window-lesson");
    let lesson = dir.join("eye_rays.toml");
    std::fs::write(&lesson, RED_SPHERE_LESSON).unwrap();
    assert_lesson_set_up(&dir, &["--lesson".as_ref(), lesson.as_os_str()]);
}

/// `--lesson-folder DIR`: the window opens with the folder's first lesson
/// (by chapter) set up, not the bundled lesson listed before it.
#[test]
#[ignore = "needs a display: scripts/test.sh runs it under Xvfb"]
fn the_window_opens_a_lesson_folders_first_lesson_set_up() {
    let dir = Scratch::new("window-lesson-folder");
    let class = dir.join("class");
    std::fs::create_dir(&class).unwrap();
    std::fs::write(class.join("a_eye_rays.toml"), RED_SPHERE_LESSON).unwrap();
    let later = RED_SPHERE_LESSON.replace("chapter = 1", "chapter = 2");
    std::fs::write(
        class.join("b_later.toml"),
        later.replace("1 0 0 1", "0 1 0 1"),
    )
    .unwrap();
    assert_lesson_set_up(&dir, &["--lesson-folder".as_ref(), class.as_os_str()]);
}

/// Every file under `dir`, recursively.
fn files_under(dir: &Path) -> Vec<std::path::PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = entry.path();
        if path.is_dir() {
            found.extend(files_under(&path));
        } else {
            found.push(path);
        }
    }
    found
}

/// eframe's on-disk storage across two runs of the real binary: the scene
/// opened with `--scene` in the first run is the scene the second run,
/// given none, opens (a fresh home opens the bundled showcase instead).
/// The home is in the scratch folder ([`workbench`]), so the state is
/// written there and nowhere else.
#[test]
#[ignore = "needs a display: scripts/test.sh runs it under Xvfb"]
fn the_last_scene_is_remembered_on_disk_across_two_runs() {
    let dir = Scratch::new("window-persistence");
    let home = dir.join("home");
    std::fs::create_dir_all(&home).unwrap();
    // A resolution no bundled scene has, so the second run's line can only
    // come from this scene.
    let scene = crate::support::write(
        &dir,
        "remembered.p3f",
        &crate::support::scenes::spheres_on_a_floor(52, 36, "", ""),
    );
    let run = |home: &Path, scene: Option<&Path>, shot: &str| {
        let mut window = workbench(home);
        if let Some(scene) = scene {
            window.arg("--scene").arg(scene);
        }
        window.arg("--screenshot").arg(dir.join(shot));
        String::from_utf8_lossy(&run_bounded(window).stdout).into_owned()
    };

    let first = run(&home, Some(scene.as_path()), "first.png");
    assert!(first.contains("of 52 x 36"), "first run: {first}");
    let stored: Vec<_> = files_under(&home)
        .into_iter()
        .filter(|f| std::fs::read_to_string(f).is_ok_and(|t| t.contains("remembered.p3f")))
        .collect();
    assert!(
        !stored.is_empty(),
        "no file under {} names the scene after the first run",
        home.display()
    );
    let second = run(&home, None, "second.png");
    assert!(
        second.contains("of 52 x 36"),
        "the second run did not reopen the first run's scene: {second}"
    );

    // The control: the same run in a fresh home shows something else.
    let fresh = dir.join("fresh");
    std::fs::create_dir_all(&fresh).unwrap();
    let control = run(&fresh, None, "control.png");
    assert!(
        control.contains("saved screenshot") && !control.contains("of 52 x 36"),
        "a fresh home: {control}"
    );
}
