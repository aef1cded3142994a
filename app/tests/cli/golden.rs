//! Golden images: every scene in `scenes/` rendered small and compared with
//! its reference in `app/tests/golden/`, plus a few variants that turn on what
//! the scenes' own settings leave off (the grid, soft shadows, a wide
//! lens with many samples, many anti-aliasing samples, sRGB output). See
//! `app/tests/golden/README.md`.
//!
//! `WORKBENCH_BLESS=1 cargo test --test cli golden` rewrites the references on
//! purpose; otherwise a missing reference is a failure. On a failure the new
//! render and a difference heat map are written to `target/golden-diff/`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use tracer::accel::{AccelKind, SceneIndex};
use tracer::metrics::{diff_heatmap, psnr};
use tracer::render::{Encoding, RenderSettings, render};
use tracer::scene::{Limits, parse_scene_file};
use tracer::world::World;

/// Lowest PSNR that passes, in dB. Renders are deterministic, so with one
/// build the PSNR is infinite; another compiler may round a value across
/// a quantisation step (every value one level off is 48 dB). One pixel
/// wrong by 255 on every channel of a 64 x 64 image is 36 dB, a uniform
/// bias of 4 levels 36 dB: both fail.
const MIN_PSNR_DB: f64 = 40.0;
/// A pixel is "off" when one of its channels differs by more than this
/// many levels: more than rounding can explain.
const OFF_LEVELS: u8 = 2;
/// At most this fraction of the pixels may be off. A brighter ambient term
/// (0.1 -> 0.115) keeps most scenes above 40 dB but puts 22 to 3 900
/// pixels of a 64 x 64 golden off; a shifted shadow or a missing blur
/// changes whole regions too.
const MAX_OFF_FRACTION: f64 = 0.002;
/// Longest image side of a golden render: big enough to show shadows and
/// reflections, small enough that the suite takes seconds.
const SIDE: u32 = 64;
/// Cap on N (N x N samples per pixel) for the scenes' own settings, to
/// keep big scenes fast.
const MAX_SAMPLES: u32 = 2;
/// Heat-map gain: a difference of 32 levels shows as full red.
const DIFF_GAIN: f32 = 8.0;

/// A configuration the scenes' own settings do not reach, rendered from one
/// scene into the reference `tests/golden/<scene>.<name>.png`.
struct Variant {
    scene: &'static str,
    name: &'static str,
    /// Longest side, at most [`SIDE`].
    side: u32,
    encoding: Encoding,
    /// Applied after the scene's settings are scaled to golden size.
    apply: fn(&mut RenderSettings),
    /// The variant must give exactly the scene's own image (another
    /// structure finds the same hits); otherwise it must differ from it.
    same_as_scene: bool,
}

impl Variant {
    /// A variant whose image must differ from its scene's own.
    const fn changes(
        scene: &'static str,
        name: &'static str,
        side: u32,
        apply: fn(&mut RenderSettings),
    ) -> Variant {
        Variant {
            scene,
            name,
            side,
            encoding: Encoding::Linear,
            apply,
            same_as_scene: false,
        }
    }
}

const VARIANTS: &[Variant] = &[
    // The grid on spheres and on a triangle mesh.
    Variant {
        same_as_scene: true,
        ..Variant::changes("balls_medium", "grid", 48, |s| s.accel = AccelKind::Grid)
    },
    Variant {
        same_as_scene: true,
        ..Variant::changes("mount_low", "grid", 48, |s| s.accel = AccelKind::Grid)
    },
    // Soft shadows both ways the tracer samples them: N x N stratified
    // light samples per pixel without AA, one light sample per AA sample.
    Variant::changes("soft_shadows", "soft", 64, |s| {
        s.soft_shadows = true;
        s.samples = 4;
    }),
    Variant::changes("soft_shadows", "soft_aa", 48, |s| {
        s.soft_shadows = true;
        s.antialiasing = true;
        s.samples = 3;
    }),
    // The lens at 4 x 4 samples, so the blur is smooth enough to compare.
    Variant::changes("dof", "lens", 64, |s| s.samples = 4),
    // Anti-aliasing at 4 x 4 on hard edges and reflections.
    Variant::changes("mirrors", "aa", 48, |s| {
        s.antialiasing = true;
        s.samples = 4;
    }),
    // The sRGB curve, on a scene with dark and bright regions.
    Variant {
        encoding: Encoding::Srgb,
        ..Variant::changes("showcase", "srgb", 48, |_| {})
    },
];

/// One golden comparison: what to render and the reference's name.
struct Case {
    /// `<scene>` or `<scene>.<variant>`: the reference is `<name>.png`.
    name: String,
    scene: PathBuf,
    side: u32,
    encoding: Encoding,
    apply: fn(&mut RenderSettings),
}

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

/// Every scene with its own settings, then every variant.
fn cases() -> Vec<Case> {
    let scenes = scenes();
    let own = scenes.iter().map(|path| Case {
        name: path.file_stem().unwrap().to_string_lossy().into_owned(),
        scene: path.clone(),
        side: SIDE,
        encoding: Encoding::Linear,
        apply: |_| {},
    });
    let variants = VARIANTS.iter().map(|v| Case {
        name: format!("{}.{}", v.scene, v.name),
        scene: root().join("scenes").join(format!("{}.p3f", v.scene)),
        side: v.side.min(SIDE),
        encoding: v.encoding,
        apply: v.apply,
    });
    own.chain(variants).collect()
}

/// The case's scene at golden size: its own settings with the aspect ratio
/// and lens kept, seed 0, at most `MAX_SAMPLES`, every core (renders do not
/// depend on threads), then the case's changes.
fn render_small(case: &Case) -> Result<image::RgbImage, String> {
    let scene = parse_scene_file(&case.scene, &Limits::default()).map_err(|e| e.to_string())?;
    let mut settings = RenderSettings::from_scene(&scene);
    let (w, h) = (settings.width.max(1), settings.height.max(1));
    let scale = f64::from(case.side) / f64::from(w.max(h));
    settings.width = ((f64::from(w) * scale).round() as u32).max(1);
    settings.height = ((f64::from(h) * scale).round() as u32).max(1);
    // The aperture counts pixels of the scene's own resolution: keep the
    // lens the same size in the scene, or a 64-pixel golden of a 512-pixel
    // scene gets a lens eight times wider and shows nothing but blur.
    let pixel_ratio = f64::from(settings.height.max(2) - 1) / f64::from(h.max(2) - 1);
    settings.aperture = (f64::from(settings.aperture) * pixel_ratio) as f32;
    settings.samples = settings.samples.min(MAX_SAMPLES);
    settings.seed = 0;
    (case.apply)(&mut settings);
    let world = Arc::new(World::build(&scene));
    let index = Arc::new(SceneIndex::build(
        &world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    let (film, _) = render(world, index, settings, None).map_err(|e| e.to_string())?;
    Ok(film.to_image(case.encoding))
}

/// How far a render is from its reference.
struct Difference {
    psnr_db: f64,
    /// Pixels with a channel more than [`OFF_LEVELS`] away.
    off_pixels: usize,
    /// The most [`Difference::off_pixels`] allowed for this image size.
    max_off_pixels: usize,
}

impl Difference {
    fn between(image: &image::RgbImage, reference: &image::RgbImage) -> Option<Difference> {
        let psnr_db = psnr(image, reference).ok()?;
        let off_pixels = image
            .pixels()
            .zip(reference.pixels())
            .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > OFF_LEVELS))
            .count();
        let pixels = image.pixels().len() as f64;
        Some(Difference {
            psnr_db,
            off_pixels,
            max_off_pixels: (pixels * MAX_OFF_FRACTION).ceil() as usize,
        })
    }

    fn passes(&self) -> bool {
        self.psnr_db >= MIN_PSNR_DB && self.off_pixels <= self.max_off_pixels
    }
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "PSNR {:.1} dB (at least {MIN_PSNR_DB}), {} pixels off by more than {OFF_LEVELS} levels (at most {})",
            self.psnr_db, self.off_pixels, self.max_off_pixels
        )
    }
}

#[test]
fn every_scene_and_variant_matches_its_golden_image() {
    let cases = cases();
    if cases.len() == VARIANTS.len() {
        println!("golden: no scenes found in scenes/, nothing to compare");
        return;
    }
    let bless = std::env::var_os("WORKBENCH_BLESS").is_some_and(|v| v != "0");
    let golden = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let diffs = tmp.parent().unwrap_or(tmp).join("golden-diff");
    let mut failures = Vec::new();
    for case in &cases {
        let name = &case.name;
        let reference_path = golden.join(format!("{name}.png"));
        let image = match render_small(case) {
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
                    "{name}: no reference {} ({e}); run WORKBENCH_BLESS=1 cargo test --test cli golden",
                    reference_path.display()
                ));
                continue;
            }
        };
        let Some(difference) = Difference::between(&image, &reference) else {
            failures.push(format!(
                "{name}: {}x{} render, {}x{} reference",
                image.width(),
                image.height(),
                reference.width(),
                reference.height()
            ));
            continue;
        };
        println!("golden: {name}: {difference}");
        if !difference.passes() {
            std::fs::create_dir_all(&diffs).unwrap();
            let new = diffs.join(format!("{name}.new.png"));
            image.save(&new).unwrap();
            let mut what = format!("new render {}", new.display());
            if let Ok(map) = diff_heatmap(&image, &reference, DIFF_GAIN) {
                let heat = diffs.join(format!("{name}.png"));
                map.save(&heat).unwrap();
                what = format!("{what}, heat map {}", heat.display());
            }
            failures.push(format!("{name}: {difference} ({what})"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A variant must change the image its scene gives with its own settings
/// at the same size, or a setting the renderer ignored would be blessed as
/// a golden of nothing new; the grid instead must give exactly the image
/// of the BVH, as it finds exactly the same hits.
#[test]
fn every_variant_changes_its_scene_except_the_grid() {
    for variant in VARIANTS {
        let name = format!("{}.{}", variant.scene, variant.name);
        let find = |name: &str| cases().into_iter().find(|c| c.name == name);
        let (Some(own), Some(changed)) = (find(variant.scene), find(&name)) else {
            continue;
        };
        let own = Case {
            side: changed.side,
            ..own
        };
        let (a, b) = (render_small(&own).unwrap(), render_small(&changed).unwrap());
        if variant.same_as_scene {
            assert!(a == b, "{name} differs from the BVH's image");
        } else {
            let difference = Difference::between(&a, &b).unwrap();
            assert!(
                !difference.passes(),
                "{name} looks like {}: {difference}",
                variant.scene
            );
        }
    }
}

/// The check itself, on a synthetic image: rounding (every value one level
/// off) passes; one pixel wrong by 255 on every channel, a uniform bias of
/// 4 levels (what ambient 0.1 -> 0.115 does to a bright surface) and a
/// region a few levels off fail.
#[test]
fn the_check_tolerates_rounding_only() {
    // A gradient with one black pixel at (5, 7).
    let reference = image::RgbImage::from_fn(SIDE, SIDE, |x, y| match (x, y) {
        (5, 7) => image::Rgb([0; 3]),
        _ => image::Rgb([(x * 3 + 20) as u8, (y * 3 + 20) as u8, 128]),
    });
    let changed = |change: fn(u32, u32, u8) -> u8| {
        let mut image = reference.clone();
        for (x, y, pixel) in image.enumerate_pixels_mut() {
            pixel.0 = pixel.0.map(|v| change(x, y, v));
        }
        Difference::between(&image, &reference).unwrap()
    };
    let rounding = changed(|x, y, v| {
        if (x + y) % 2 == 0 {
            v + 1
        } else {
            v.max(1) - 1
        }
    });
    assert!(rounding.passes(), "{rounding}");
    let one_pixel = changed(|x, y, v| if (x, y) == (5, 7) { 255 } else { v });
    assert!(!one_pixel.passes(), "{one_pixel}");
    let bias = changed(|_, _, v| v + 4);
    assert!(!bias.passes(), "{bias}");
    let region = changed(|x, y, v| if x < 8 && y < 8 { v + 3 } else { v });
    assert!(!region.passes(), "{region}");
}
