//! Embeds the project's scenes (`scenes/*.p3f`, `*.nff`), lessons
//! (`assets/lessons/*.toml`) and the skybox (`assets/skybox/`) in the
//! binary, so the window opens them from any working directory. The lists
//! are generated, so a new scene or lesson file needs no code change.

use std::fmt::Write as _;
use std::path::Path;

fn main() {
    // A position-dependent executable: the loader has no 39 000 relative
    // relocations to apply, and no pages of pointers to copy for them, at
    // each start (`workbench --version` 5.9 -> 4.0 ms, median of 21
    // alternated runs). The binary's own code loses address
    // randomisation; the libraries it loads keep theirs. (GNU toolchains
    // on Linux: other linkers spell it otherwise.)
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux")
        && std::env::var("CARGO_CFG_TARGET_ENV").as_deref() == Ok("gnu")
    {
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
    // Read when the script runs, not baked in with `env!`: a build script
    // reused from a build cache made in another checkout (a git worktree
    // seeded with a copied `target/`) would otherwise embed that
    // checkout's scenes and sky.
    let manifest_dir = std::env::var_os("CARGO_MANIFEST_DIR").unwrap();
    let root = Path::new(&manifest_dir).join("..");
    let scenes_dir = root.join("scenes");
    let sky_dir = root.join("assets").join("skybox");
    let lessons_dir = root.join("assets").join("lessons");
    println!("cargo:rerun-if-changed={}", scenes_dir.display());
    println!("cargo:rerun-if-changed={}", lessons_dir.display());
    println!("cargo:rerun-if-changed={}", sky_dir.display());

    let mut scenes = files_in(&scenes_dir, &["p3f", "nff"]);
    // The web page embeds only the scenes it opens by itself: the default
    // (`bundled::DEFAULT_SCENE`) and those a lesson names; the whole
    // folder (20 MB) would be most of the page's download. The others
    // are files beside the page (`scripts/build-web.sh` copies them),
    // listed here so its scene list offers them without asking the site.
    let mut on_site = Vec::new();
    if std::env::var("CARGO_CFG_TARGET_FAMILY").as_deref() == Ok("wasm") {
        let wanted = lesson_scenes(&lessons_dir);
        (scenes, on_site) = scenes.into_iter().partition(|path| {
            let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
            name == "showcase" || wanted.iter().any(|w| w == name)
        });
    }

    let mut out = String::from("/// Scenes embedded from `scenes/`, sorted by file name.\n");
    out.push_str("pub(crate) const SCENES: &[BundledScene] = &[\n");
    for path in &scenes {
        println!("cargo:rerun-if-changed={}", path.display());
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
        let file = path.file_name().and_then(|s| s.to_str()).unwrap_or("scene");
        let text = std::fs::read_to_string(path).unwrap_or_default();
        let description = description(&text);
        writeln!(
            out,
            "    BundledScene {{ name: {name:?}, file: {file:?}, description: {description:?}, text: include_str!({:?}) }},",
            path.canonicalize().unwrap_or(path.clone()).display().to_string()
        )
        .unwrap();
    }
    out.push_str("];\n\n");

    out.push_str(
        "/// Scenes of `scenes/` left out of [`SCENES`] (on the web page), sorted\n\
         /// by file name: fetched from `scenes/FILE` beside the page when picked.\n",
    );
    out.push_str("pub(crate) const SITE_SCENES: &[SiteScene] = &[\n");
    for path in &on_site {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
        let file = path.file_name().and_then(|s| s.to_str()).unwrap_or("scene");
        let text = std::fs::read_to_string(path).unwrap_or_default();
        let description = description(&text);
        let size = text.len();
        writeln!(
            out,
            "    SiteScene {{ name: {name:?}, file: {file:?}, description: {description:?}, size: {size} }},",
        )
        .unwrap();
    }
    out.push_str("];\n\n");

    out.push_str("/// Lessons embedded from `assets/lessons/`, sorted by file name.\n");
    out.push_str("pub(crate) const LESSONS: &[BundledLesson] = &[\n");
    for path in files_in(&lessons_dir, &["toml"]) {
        println!("cargo:rerun-if-changed={}", path.display());
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("lesson");
        writeln!(
            out,
            "    BundledLesson {{ name: {name:?}, text: include_str!({:?}) }},",
            path.canonicalize()
                .unwrap_or(path.clone())
                .display()
                .to_string()
        )
        .unwrap();
    }
    out.push_str("];\n\n");

    let faces = ["right", "left", "top", "bottom", "front", "back"];
    let files: Vec<_> = faces
        .iter()
        .map(|f| sky_dir.join(format!("{f}.png")))
        .filter(|p| p.is_file())
        .collect();
    out.push_str(
        "/// The skybox faces embedded from `assets/skybox/`, if all six exist,\n\
         /// decoded here to RGB bytes: a start then decodes nothing.\n",
    );
    if files.len() == 6 {
        out.push_str("pub(crate) const SKYBOX: Option<[tracer::skybox::Rgb8Face; 6]> = Some([\n");
        let out_dir = std::env::var_os("OUT_DIR").unwrap();
        for (face, file) in faces.iter().zip(&files) {
            let (width, height, rgb) = decode_rgb8(file);
            let raw = Path::new(&out_dir).join(format!("sky_{face}.rgb"));
            std::fs::write(&raw, rgb).unwrap();
            writeln!(
                out,
                "    tracer::skybox::Rgb8Face {{ width: {width}, height: {height}, bytes: include_bytes!({:?}) }},",
                raw.display().to_string()
            )
            .unwrap();
        }
        out.push_str("]);\n");
    } else {
        out.push_str("pub(crate) const SKYBOX: Option<[tracer::skybox::Rgb8Face; 6]> = None;\n");
    }
    let dest = Path::new(&std::env::var("OUT_DIR").unwrap()).join("bundled.rs");
    std::fs::write(dest, out).unwrap();
    expose_commit(&root);
}

/// Sets `WORKBENCH_COMMIT` to the checkout's commit, for reports that say
/// which build measured them; "unknown" when the source is not a git
/// checkout or git is missing (a tarball, a vendored build), which must
/// still build. Reruns when HEAD moves (a commit, a checkout).
fn expose_commit(root: &Path) {
    let git = |args: &[&str]| -> Option<String> {
        let out = std::process::Command::new("git")
            .arg("-C")
            .arg(root)
            .args(args)
            .output()
            .ok()?;
        let text = String::from_utf8(out.stdout).ok()?;
        (out.status.success() && !text.trim().is_empty()).then(|| text.trim().to_string())
    };
    let commit = git(&["rev-parse", "--short=12", "HEAD"]).unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=WORKBENCH_COMMIT={commit}");
    for file in ["HEAD", "logs/HEAD"] {
        if let Some(path) = git(&["rev-parse", "--path-format=absolute", "--git-path", file])
            && Path::new(&path).is_file()
        {
            println!("cargo:rerun-if-changed={path}");
        }
    }
}

/// A scene's first comment line, which says how it was made and what it
/// shows.
fn description(text: &str) -> &str {
    text.lines()
        .find_map(|l| l.trim().strip_prefix('#'))
        .map(str::trim)
        .unwrap_or("")
}

/// The bundled scenes the lessons in `dir` open (`bundled = "NAME"`).
fn lesson_scenes(dir: &Path) -> Vec<String> {
    files_in(dir, &["toml"])
        .iter()
        .filter_map(|path| std::fs::read_to_string(path).ok())
        .flat_map(|text| {
            text.lines()
                .filter_map(|line| {
                    let value = line.trim().strip_prefix("bundled")?.trim_start();
                    let name = value.strip_prefix('=')?.trim().trim_matches('"');
                    Some(name.to_string())
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The files in `dir` with one of `extensions`, sorted; none when the
/// folder is missing.
fn files_in(dir: &Path, extensions: &[&str]) -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(Result::ok)
                .map(|e| e.path())
                .filter(|p| {
                    p.extension()
                        .and_then(|e| e.to_str())
                        .is_some_and(|e| extensions.contains(&e))
                })
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

/// A PNG face's size and its texels as 8-bit RGB, as the `image` crate's
/// `to_rgb8` gives them (palettes and low bit depths expanded, alpha
/// dropped, grey repeated), so the embedded sky is the one in the folder.
/// A face that is not 8-bit is a build error: the project's own asset.
fn decode_rgb8(file: &Path) -> (u32, u32, Vec<u8>) {
    let fail = |e: &dyn std::fmt::Display| -> ! { panic!("skybox face {}: {e}", file.display()) };
    let reader = std::fs::File::open(file).unwrap_or_else(|e| fail(&e));
    let mut decoder = png::Decoder::new(std::io::BufReader::new(reader));
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().unwrap_or_else(|e| fail(&e));
    let mut buf = vec![
        0;
        reader
            .output_buffer_size()
            .unwrap_or_else(|| fail(&"too large"))
    ];
    let info = reader.next_frame(&mut buf).unwrap_or_else(|e| fail(&e));
    if info.bit_depth != png::BitDepth::Eight {
        fail(&"not 8 bits per channel");
    }
    let bytes = &buf[..info.buffer_size()];
    let rgb = match info.color_type {
        png::ColorType::Rgb => bytes.to_vec(),
        png::ColorType::Rgba => bytes
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect(),
        png::ColorType::Grayscale => bytes.iter().flat_map(|&v| [v, v, v]).collect(),
        png::ColorType::GrayscaleAlpha => bytes
            .chunks_exact(2)
            .flat_map(|p| [p[0], p[0], p[0]])
            .collect(),
        png::ColorType::Indexed => fail(&"a palette left after expansion"),
    };
    (info.width, info.height, rgb)
}
