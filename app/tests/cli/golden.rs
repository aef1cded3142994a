//! Golden images: every scene in `scenes/` rendered small and compared with
//! its reference in `app/tests/golden/`, plus a few variants that turn on what
//! the scenes' own settings leave off (the grid, soft shadows, a wide
//! lens with many samples, many anti-aliasing samples, sRGB output),
//! magnified crops of the features those variants exist for, and linear
//! EXR references of the cases with values above 1. See
//! `app/tests/golden/README.md`.
//!
//! `WORKBENCH_BLESS=1 cargo test --test cli golden` rewrites the references on
//! purpose; otherwise a missing reference is a failure. On a failure the new
//! render and a difference heat map are written to `target/golden-diff/`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use tracer::accel::{AccelKind, SceneIndex};
use tracer::metrics::{diff_heatmap, psnr};
use tracer::render::{AdaptiveSampling, Encoding, RenderSettings, Sampling, render};
use tracer::scene::mesh_io::MeshFormat;
use workbench::load::{Loaded, SceneSource};

/// Lowest PSNR that passes, in dB. Renders are deterministic, so with one
/// build the PSNR is infinite; another compiler may round a value across
/// a quantisation step (every value one level off is 48 dB). One pixel
/// wrong by 255 on every channel of a 64 x 64 image is 36 dB, a uniform
/// bias of 4 levels 36 dB: both fail.
const MIN_PSNR_DB: f64 = 40.0;
/// A pixel is "off" when one of its channels differs by more than this
/// many levels: more than rounding can explain.
const OFF_LEVELS: u8 = 2;
/// No channel of any pixel may be further off than this, in levels: one
/// pixel wrong by 163 levels costs a 64 x 64 image only 45 dB and is one
/// pixel of the nine [`MAX_OFF_FRACTION`] allows, so without a cap it passed.
const MAX_LEVELS: u8 = 6;
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
/// An EXR golden's tolerance per value: this many levels of the 8-bit
/// scale, or this fraction of the value where it is larger (above 1).
const HDR_LEVELS: f32 = 4.0;
const HDR_RELATIVE: f32 = 0.01;
/// And on average over all its values, at most this many levels.
const HDR_MEAN_LEVELS: f64 = 0.5;

/// A configuration the scenes' own settings do not reach, rendered from one
/// scene into the reference `app/tests/golden/<scene>.<name>.png`.
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
    /// Magnified: rendered with this longest side, then only the
    /// [`SIDE`] x [`SIDE`] window at this corner is compared.
    crop: Option<Crop>,
    /// Compared as linear floats with an EXR reference, values above 1 kept.
    hdr: bool,
}

/// A window of a larger render: the feature a golden exists for, at three
/// times the pixels per scene unit of the full-view golden.
#[derive(Clone, Copy)]
struct Crop {
    side: u32,
    x: u32,
    y: u32,
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
            crop: None,
            hdr: false,
        }
    }

    /// This variant as a magnified crop `<scene>.<name>` of a render with
    /// longest side `side`, its window's top-left corner at `(x, y)`.
    const fn cropped(self, name: &'static str, side: u32, x: u32, y: u32) -> Variant {
        Variant {
            name,
            crop: Some(Crop { side, x, y }),
            ..self
        }
    }
}

/// Soft shadows both ways the tracer samples them: N x N multi-jittered
/// light samples per pixel without AA, one light sample per AA sample.
fn soft(s: &mut RenderSettings) {
    s.soft_shadows = true;
    s.samples = 4;
}

fn soft_aa(s: &mut RenderSettings) {
    s.soft_shadows = true;
    s.antialiasing = true;
    s.samples = 3;
}

/// The lens at 4 x 4 samples, so the blur is smooth enough to compare.
fn lens(s: &mut RenderSettings) {
    s.samples = 4;
}

/// Anti-aliasing at 4 x 4 on hard edges and reflections.
fn aa(s: &mut RenderSettings) {
    s.antialiasing = true;
    s.samples = 4;
}

/// Adaptive anti-aliasing at a threshold of 0.02, 4 to 64 samples a
/// pixel: the most on edges, penumbrae and blur.
fn adaptive(s: &mut RenderSettings) {
    s.antialiasing = true;
    s.sampling = Sampling::Adaptive(AdaptiveSampling {
        noise_threshold: 0.02,
        min_spp: 4,
        max_spp: 64,
        budget: None,
    });
}

fn adaptive_soft(s: &mut RenderSettings) {
    s.soft_shadows = true;
    adaptive(s);
}

/// The scene's own settings, as linear floats: the settings change
/// nothing, so these are left out of the variant test; their EXR golden
/// checks what they add (values above 1, [`HdrDifference::passes`]).
const fn hdr(scene: &'static str) -> Variant {
    Variant {
        hdr: true,
        ..Variant::changes(scene, "hdr", SIDE, |_| {})
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
    Variant::changes("soft_shadows", "soft", 64, soft),
    Variant::changes("soft_shadows", "soft_aa", 48, soft_aa),
    Variant::changes("dof", "lens", 64, lens),
    Variant::changes("mirrors", "aa", 48, aa),
    // Adaptive anti-aliasing on edges, on penumbrae (one light sample per
    // pixel sample) and on the lens's blur.
    Variant::changes("mirrors", "adaptive", 48, adaptive),
    Variant::changes("soft_shadows", "adaptive_soft", 48, adaptive_soft),
    Variant::changes("dof", "adaptive_lens", 64, adaptive),
    // The sRGB curve, on a scene with dark and bright regions.
    Variant {
        encoding: Encoding::Srgb,
        ..Variant::changes("showcase", "srgb", 48, |_| {})
    },
    // The same features magnified three times: the penumbrae of the box,
    // the post and the floating sphere; the blur of the lens's nearest
    // and farthest objects; the mirrors' edges and inter-reflections.
    Variant::changes("soft_shadows", "soft", 64, soft).cropped(
        "soft_crop",
        192,
        CROP_SOFT.0,
        CROP_SOFT.1,
    ),
    Variant::changes("soft_shadows", "soft_aa", 64, soft_aa).cropped(
        "soft_aa_crop",
        192,
        CROP_SOFT.0,
        CROP_SOFT.1,
    ),
    Variant::changes("dof", "lens", 64, lens).cropped("lens_crop", 192, CROP_LENS.0, CROP_LENS.1),
    Variant::changes("mirrors", "aa", 64, aa).cropped("aa_crop", 192, CROP_AA.0, CROP_AA.1),
    // Linear floats where values pass 1: the sky in the showcase's
    // mirrors and glass, the mirrors' highlights.
    hdr("showcase"),
    hdr("mirrors"),
];

/// Top-left corners of the crops, in pixels of the 192-pixel render: the
/// floating sphere's wide penumbra (with the blue sphere's foot), the near
/// red sphere's blur beside the orange one's edge, the mirror's nested
/// reflections.
const CROP_SOFT: (u32, u32) = (110, 100);
const CROP_LENS: (u32, u32) = (16, 80);
const CROP_AA: (u32, u32) = (24, 48);

/// One golden comparison: what to render and the reference's name.
struct Case {
    /// `<scene>` or `<scene>.<variant>`: the reference is `<name>.png`.
    name: String,
    scene: PathBuf,
    side: u32,
    encoding: Encoding,
    apply: fn(&mut RenderSettings),
    crop: Option<Crop>,
    /// The reference is `<name>.exr`, linear floats.
    hdr: bool,
}

impl Case {
    fn reference(&self) -> PathBuf {
        let extension = if self.hdr { "exr" } else { "png" };
        golden_dir().join(format!("{}.{extension}", self.name))
    }
}

/// `app/tests/golden/`, where the references are.
fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

fn root() -> PathBuf {
    let app = Path::new(env!("CARGO_MANIFEST_DIR"));
    app.parent().unwrap_or(app).to_path_buf()
}

/// `scenes/*.p3f`, `*.nff` and the bare meshes, sorted; empty if the folder
/// is missing.
fn scenes() -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(root().join("scenes")) else {
        return Vec::new();
    };
    let mut found: Vec<PathBuf> = entries
        .filter_map(|e| Some(e.ok()?.path()))
        .filter(|p| {
            p.extension()
                .is_some_and(|x| x.eq_ignore_ascii_case("p3f") || x.eq_ignore_ascii_case("nff"))
                || MeshFormat::of(p).is_some()
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
        crop: None,
        hdr: false,
    });
    let variants = VARIANTS.iter().map(|v| Case {
        name: format!("{}.{}", v.scene, v.name),
        scene: root().join("scenes").join(format!("{}.p3f", v.scene)),
        side: v.crop.map_or(v.side.min(SIDE), |c| c.side),
        encoding: v.encoding,
        apply: v.apply,
        crop: v.crop,
        hdr: v.hdr,
    });
    own.chain(variants).collect()
}

/// The case's scene at golden size, as 8-bit pixels in its encoding.
fn render_small(case: &Case) -> Result<image::RgbImage, String> {
    let film = render_film(case)?;
    Ok(crop(case, film.to_image(case.encoding)))
}

/// The case's scene at golden size, as linear floats.
fn render_linear(case: &Case) -> Result<image::Rgb32FImage, String> {
    let film = render_film(case)?;
    Ok(crop(case, film.to_linear_image()))
}

/// The case's window of a render, or all of it.
fn crop<P: image::Pixel + 'static>(
    case: &Case,
    image: image::ImageBuffer<P, Vec<P::Subpixel>>,
) -> image::ImageBuffer<P, Vec<P::Subpixel>>
where
    P::Subpixel: 'static,
{
    match case.crop {
        Some(c) => image::imageops::crop_imm(&image, c.x, c.y, SIDE, SIDE).to_image(),
        None => image,
    }
}

/// The case's scene at golden size: its own settings with the aspect ratio
/// and lens kept, seed 0, at most `MAX_SAMPLES`, every core (renders do not
/// depend on threads), then the case's changes.
fn render_film(case: &Case) -> Result<tracer::render::Film, String> {
    // As the binary reads it: a bare mesh framed, a scene's sky loaded.
    let source = SceneSource::File(case.scene.clone());
    let Loaded { scene, world, .. } =
        Loaded::read(source, &[], &mut |_| {}).map_err(|e| format!("{e:#}"))?;
    let mut settings = RenderSettings::from_scene(&scene);
    let (w, h) = (settings.width.max(1), settings.height.max(1));
    let scale = f64::from(case.side) / f64::from(w.max(h));
    settings.width = ((f64::from(w) * scale).round() as u32).max(1);
    settings.height = ((f64::from(h) * scale).round() as u32).max(1);
    // The aperture counts pixels of the scene's own resolution: keep the
    // lens the same size in the scene, or a 64-pixel golden of a 512-pixel
    // scene gets a lens eight times wider and shows nothing but blur.
    let pixel_ratio = f64::from(settings.height.max(2) - 1) / f64::from(h.max(2) - 1);
    let aperture = settings.chosen_lens(&scene.view).aperture;
    settings.lens_override.aperture = Some((f64::from(aperture) * pixel_ratio) as f32);
    settings.samples = settings.samples.min(MAX_SAMPLES);
    settings.seed = 0;
    (case.apply)(&mut settings);
    let index = Arc::new(SceneIndex::build(
        &world.shapes,
        settings.accel,
        settings.grid_multiplier,
    ));
    let (film, _) = render(world, index, settings, None).map_err(|e| e.to_string())?;
    Ok(film)
}

/// How far a render is from its reference.
struct Difference {
    psnr_db: f64,
    /// Pixels with a channel more than [`OFF_LEVELS`] away.
    off_pixels: usize,
    /// The most [`Difference::off_pixels`] allowed for this image size.
    max_off_pixels: usize,
    /// The largest difference of any channel, in levels.
    max_levels: u8,
}

impl Difference {
    fn between(image: &image::RgbImage, reference: &image::RgbImage) -> Option<Difference> {
        let psnr_db = psnr(image, reference).ok()?;
        let off_pixels = image
            .pixels()
            .zip(reference.pixels())
            .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > OFF_LEVELS))
            .count();
        let max_levels = image
            .pixels()
            .zip(reference.pixels())
            .flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c])))
            .max()
            .unwrap_or(0);
        let pixels = image.pixels().len() as f64;
        Some(Difference {
            psnr_db,
            off_pixels,
            max_off_pixels: (pixels * MAX_OFF_FRACTION).ceil() as usize,
            max_levels,
        })
    }

    fn passes(&self) -> bool {
        self.psnr_db >= MIN_PSNR_DB
            && self.off_pixels <= self.max_off_pixels
            && self.max_levels <= MAX_LEVELS
    }
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "PSNR {:.1} dB (at least {MIN_PSNR_DB}), {} pixels off by more than {OFF_LEVELS} levels (at most {}), \
             at most {} levels off (cap {MAX_LEVELS})",
            self.psnr_db, self.off_pixels, self.max_off_pixels, self.max_levels
        )
    }
}

/// How far a linear render is from its EXR reference.
struct HdrDifference {
    /// Values off by more than the tolerance, and the worst of them.
    off_values: usize,
    worst: (f32, f32),
    /// Mean absolute difference, in levels of the 8-bit scale.
    mean_levels: f64,
    /// The reference's largest value: an HDR case must pass 1.
    brightest: f32,
}

impl HdrDifference {
    fn between(image: &image::Rgb32FImage, reference: &image::Rgb32FImage) -> Option<Self> {
        if image.dimensions() != reference.dimensions() {
            return None;
        }
        let pairs = || image.as_raw().iter().zip(reference.as_raw());
        let allowed = |r: f32| (HDR_LEVELS / 255.0).max(HDR_RELATIVE * r.abs());
        let off: Vec<(f32, f32)> = pairs()
            // A NaN is off too.
            .filter(|&(a, r)| (a - r).abs().is_nan() || (a - r).abs() > allowed(*r))
            .map(|(a, r)| (*a, *r))
            .collect();
        let worst = off
            .iter()
            .copied()
            .max_by(|x, y| (x.0 - x.1).abs().total_cmp(&(y.0 - y.1).abs()))
            .unwrap_or((0.0, 0.0));
        let total: f64 = pairs().map(|(a, r)| f64::from((a - r).abs())).sum();
        Some(HdrDifference {
            off_values: off.len(),
            worst,
            mean_levels: 255.0 * total / image.as_raw().len().max(1) as f64,
            brightest: reference.as_raw().iter().copied().fold(0.0, f32::max),
        })
    }

    fn passes(&self) -> bool {
        self.off_values == 0 && self.mean_levels <= HDR_MEAN_LEVELS && self.brightest > 1.0
    }
}

impl std::fmt::Display for HdrDifference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} values off by more than {HDR_LEVELS} levels or {}% (worst {} for {}), \
             mean {:.3} levels (at most {HDR_MEAN_LEVELS}), brightest {} (must pass 1)",
            self.off_values,
            HDR_RELATIVE * 100.0,
            self.worst.0,
            self.worst.1,
            self.mean_levels,
            self.brightest
        )
    }
}

/// Compares an HDR case with its EXR reference (or blesses it): the
/// failure, if any.
fn check_hdr(case: &Case, bless: bool, diffs: &Path) -> Option<String> {
    let name = &case.name;
    let path = case.reference();
    let image = match render_linear(case) {
        Ok(image) => image,
        Err(e) => return Some(format!("{name}: cannot render: {e}")),
    };
    if bless {
        image.save(&path).unwrap();
        println!("golden: blessed {}", path.display());
        return None;
    }
    let reference = match image::open(&path) {
        Ok(r) => r.to_rgb32f(),
        Err(e) => return Some(format!("{name}: no reference {} ({e})", path.display())),
    };
    let Some(difference) = HdrDifference::between(&image, &reference) else {
        return Some(format!("{name}: render and reference differ in size"));
    };
    println!("golden: {name}: {difference}");
    if difference.passes() {
        return None;
    }
    std::fs::create_dir_all(diffs).unwrap();
    let new = diffs.join(format!("{name}.new.exr"));
    image.save(&new).unwrap();
    Some(format!(
        "{name}: {difference} (new render {})",
        new.display()
    ))
}

#[test]
fn every_scene_and_variant_matches_its_golden_image() {
    let cases = cases();
    if cases.len() == VARIANTS.len() {
        tracer::optional_input::missing("scenes/ (the goldens' scenes)");
        return;
    }
    let bless = std::env::var_os("WORKBENCH_BLESS").is_some_and(|v| v != "0");
    let golden = golden_dir();
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let diffs = tmp.parent().unwrap_or(tmp).join("golden-diff");
    let mut failures = Vec::new();
    for case in &cases {
        let name = &case.name;
        if case.hdr {
            failures.extend(check_hdr(case, bless, &diffs));
            continue;
        }
        let reference_path = case.reference();
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

/// Every reference has its case: a golden whose scene was deleted or
/// renamed (or whose variant is gone) would otherwise drop out of the
/// comparison without a word.
#[test]
fn every_golden_image_has_its_scene() {
    if scenes().is_empty() {
        tracer::optional_input::missing("scenes/ (the goldens' scenes)");
        return;
    }
    let cases = cases();
    let mut orphans = Vec::new();
    let mut checked = 0;
    for entry in std::fs::read_dir(golden_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.file_name().is_some_and(|n| n == "README.md") {
            continue;
        }
        checked += 1;
        if !cases.iter().any(|case| case.reference() == path) {
            orphans.push(path.display().to_string());
        }
    }
    assert!(
        orphans.is_empty(),
        "golden images without a scene or variant (delete them, or bring the scene back): {}",
        orphans.join(", ")
    );
    assert_eq!(checked, cases.len(), "one reference per case");
}

/// A variant must change the image its scene gives with its own settings
/// at the same size, or a setting the renderer ignored would be blessed as
/// a golden of nothing new; the grid instead must give exactly the image
/// of the BVH, as it finds exactly the same hits.
#[test]
fn every_variant_changes_its_scene_except_the_grid() {
    if scenes().is_empty() {
        tracer::optional_input::missing("scenes/ (the variants' scenes)");
        return;
    }
    for variant in VARIANTS.iter().filter(|v| !v.hdr) {
        let name = format!("{}.{}", variant.scene, variant.name);
        let find = |name: &str| cases().into_iter().find(|c| c.name == name);
        let (Some(own), Some(changed)) = (find(variant.scene), find(&name)) else {
            panic!("{name}: scenes/{}.p3f is missing", variant.scene);
        };
        let own = Case {
            side: changed.side,
            crop: changed.crop,
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
    // One channel of one pixel 163 levels off: 45 dB and one pixel off,
    // which only the per-pixel cap refuses; 7 levels is past the cap too.
    let spike = changed(|x, y, v| if (x, y) == (5, 7) { v + 163 } else { v });
    let small = changed(|x, y, v| if (x, y) == (5, 7) { v + 7 } else { v });
    for one in [spike, small] {
        assert!(one.psnr_db >= MIN_PSNR_DB && one.off_pixels == 1, "{one}");
        assert!(!one.passes(), "{one}");
    }
}

/// The EXR check: float rounding passes; a value 5 levels off, a bright
/// value 2% off, a bias of 1 level and a reference that never passes 1
/// (an HDR golden of nothing above 1) fail.
#[test]
fn the_hdr_check_tolerates_rounding_only() {
    let reference = image::Rgb32FImage::from_fn(SIDE, SIDE, |x, y| {
        image::Rgb([x as f32 / 16.0, y as f32 / 64.0, 0.5])
    });
    let changed = |change: &dyn Fn(u32, u32, f32) -> f32| {
        let mut image = reference.clone();
        for (x, y, pixel) in image.enumerate_pixels_mut() {
            pixel.0 = pixel.0.map(|v| change(x, y, v));
        }
        HdrDifference::between(&image, &reference).unwrap()
    };
    let rounding = changed(&|_, _, v| v * (1.0 + 1e-6));
    assert!(rounding.passes(), "{rounding}");
    let spike = changed(&|x, y, v| if (x, y) == (3, 3) { v + 5.0 / 255.0 } else { v });
    assert!(!spike.passes(), "{spike}");
    let bright = changed(&|x, y, v| if (x, y) == (60, 3) { v * 1.02 } else { v });
    assert!(!bright.passes(), "{bright}");
    let bias = changed(&|_, _, v| v + 1.0 / 255.0);
    assert!(!bias.passes(), "{bias}");
    let dim = image::Rgb32FImage::from_pixel(SIDE, SIDE, image::Rgb([0.5; 3]));
    let low = HdrDifference::between(&dim, &dim).unwrap();
    assert!(!low.passes(), "{low}");
}
