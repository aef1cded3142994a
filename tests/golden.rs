//! Golden images: every scene in `scenes/` rendered small and compared with
//! its reference in `tests/golden/` by PSNR. See `tests/golden/README.md`.
//!
//! `WORKBENCH_BLESS=1 cargo test --test golden` rewrites the references on
//! purpose; otherwise a missing reference is a failure. On a failure the new
//! render and a difference heat map are written to `target/golden-diff/`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use tracer::accel::SceneIndex;
use tracer::metrics::{diff_heatmap, psnr};
use tracer::render::{Encoding, RenderSettings, render};
use tracer::scene::{Limits, parse_scene_file};
use tracer::world::World;

/// Pass threshold in dB. Renders are deterministic, so on one machine the
/// PSNR is infinite; across compilers and CPUs a few edge pixels may flip
/// (a handful of pixels off by 200 levels in a 64x64 image is ~36 dB, one
/// level everywhere is 48 dB). A wrong shadow or highlight changes a region:
/// 2% of the pixels off by 80 levels is already 30 dB, a missing shadow far
/// less. 35 dB sits between the two.
const THRESHOLD_DB: f64 = 35.0;
/// Longest image side of a golden render: big enough to show shadows and
/// reflections, small enough that the suite takes seconds.
const SIDE: u32 = 64;
/// Cap on N (N x N samples per pixel), to keep big scenes fast.
const MAX_SAMPLES: u32 = 2;
/// Heat-map gain: a difference of 32 levels shows as full red.
const DIFF_GAIN: f32 = 8.0;

fn root() -> PathBuf {
    let app = Path::new(env!("CARGO_MANIFEST_DIR"));
    app.parent().unwrap_or(app).to_path_buf()
}

/// `scenes/*.p3f` and `*.nff`, sorted; empty if the folder is missing.
fn scenes() -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(root().join("scenes")) else {
        return Vec::new();
    };
    let mut found: Vec<PathBuf> = entries
        .filter_map(|e| Some(e.ok()?.path()))
        .filter(|p| {
            p.extension()
                .is_some_and(|x| x.eq_ignore_ascii_case("p3f") || x.eq_ignore_ascii_case("nff"))
        })
        .collect();
    found.sort();
    found
}

/// The scene's own settings at golden size: aspect ratio and lens kept,
/// seed 0, at most `MAX_SAMPLES`, every core (renders do not depend on
/// threads).
fn render_small(path: &Path) -> Result<image::RgbImage, String> {
    let scene = parse_scene_file(path, &Limits::default()).map_err(|e| e.to_string())?;
    let mut settings = RenderSettings::from_scene(&scene);
    let (w, h) = (settings.width.max(1), settings.height.max(1));
    let scale = f64::from(SIDE) / f64::from(w.max(h));
    settings.width = ((f64::from(w) * scale).round() as u32).max(1);
    settings.height = ((f64::from(h) * scale).round() as u32).max(1);
    // The aperture counts pixels of the scene's own resolution: keep the
    // lens the same size in the scene, or a 64-pixel golden of a 512-pixel
    // scene gets a lens eight times wider and shows nothing but blur.
    let pixel_ratio = f64::from(settings.height.max(2) - 1) / f64::from(h.max(2) - 1);
    settings.aperture = (f64::from(settings.aperture) * pixel_ratio) as f32;
    settings.samples = settings.samples.min(MAX_SAMPLES);
    settings.seed = 0;
    let world = Arc::new(World::build(&scene));
    let index = Arc::new(SceneIndex::build(
        &world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    let (film, _) = render(world, index, settings, None).map_err(|e| e.to_string())?;
    Ok(film.to_image(Encoding::Linear))
}

#[test]
fn every_scene_matches_its_golden_image() {
    let scenes = scenes();
    if scenes.is_empty() {
        println!("golden: no scenes found in scenes/, nothing to compare");
        return;
    }
    let bless = std::env::var_os("WORKBENCH_BLESS").is_some_and(|v| v != "0");
    let golden = root().join("tests/golden");
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let diffs = tmp.parent().unwrap_or(tmp).join("golden-diff");
    let mut failures = Vec::new();
    for path in &scenes {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let reference_path = golden.join(format!("{name}.png"));
        let image = match render_small(path) {
            Ok(image) => image,
            Err(e) => {
                failures.push(format!("{name}: cannot render: {e}"));
                continue;
            }
        };
        if bless {
            std::fs::create_dir_all(&golden).unwrap();
            image.save(&reference_path).unwrap();
            println!("golden: blessed {}", reference_path.display());
            continue;
        }
        let reference = match image::open(&reference_path) {
            Ok(r) => r.to_rgb8(),
            Err(e) => {
                failures.push(format!(
                    "{name}: no reference {} ({e}); run WORKBENCH_BLESS=1 cargo test --test golden",
                    reference_path.display()
                ));
                continue;
            }
        };
        let db = psnr(&image, &reference).unwrap_or(f64::NEG_INFINITY);
        println!("golden: {name}: {db:.1} dB");
        if db < THRESHOLD_DB {
            std::fs::create_dir_all(&diffs).unwrap();
            let new = diffs.join(format!("{name}.new.png"));
            image.save(&new).unwrap();
            let mut what = format!("new render {}", new.display());
            if let Ok(map) = diff_heatmap(&image, &reference, DIFF_GAIN) {
                let heat = diffs.join(format!("{name}.png"));
                map.save(&heat).unwrap();
                what = format!("{what}, heat map {}", heat.display());
            }
            failures.push(format!(
                "{name}: PSNR {db:.1} dB below {THRESHOLD_DB} dB ({what})"
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
