//! `workbench gen`: the project's procedural scenes (after Eric Haines's
//! SPD) as P3F, and the procedural skybox as six PNG faces.

use std::io::Write;

use anyhow::{Context, Result, bail};
use tracer::generate::{self, GenerateOptions, GeneratorName, describe, sky};
use tracer::scene::write_p3f;
use tracer::skybox::FACE_NAMES;

use crate::cli::GenArgs;
use crate::image_file::save_png;

pub fn run(args: &GenArgs) -> Result<()> {
    if args.name.eq_ignore_ascii_case("sky") {
        for (given, flag) in [
            (args.level.is_some(), "--level"),
            (args.seed.is_some(), "--seed"),
        ] {
            if given {
                bail!("{flag} does not apply to the sky: it has one look (--size sets its faces)");
            }
        }
        return paint_sky(args);
    }
    if let Some(size) = args.size {
        bail!(
            "--size {size} does not apply to {}: it sets the sky's faces",
            args.name
        );
    }
    let name: GeneratorName = args.name.parse().with_context(|| {
        let names: Vec<&str> = GeneratorName::ALL.iter().map(|g| g.name()).collect();
        format!("choose one of: {}, sky", names.join(", "))
    })?;
    if args.seed.is_some() && !generate::uses_seed(name) {
        bail!(
            "--seed does not apply to {name}: it draws nothing at random (mount, tree and gears do)"
        );
    }
    let level = args.level.unwrap_or_else(|| generate::default_level(name));
    let scene = generate::generate(
        name,
        &GenerateOptions {
            level,
            seed: args.seed.unwrap_or(0),
        },
    )?;
    let text = format!(
        "# {}\n{}",
        describe(name, level, args.seed.unwrap_or(0)),
        write_p3f(&scene)
    );
    match &args.output {
        Some(path) => std::fs::write(path, text)
            .with_context(|| format!("cannot write {}", path.display()))?,
        None => std::io::stdout()
            .lock()
            .write_all(text.as_bytes())
            .context("cannot write to standard output")?,
    }
    Ok(())
}

/// Side of each sky face in pixels unless `--size` says otherwise.
const DEFAULT_SKY_SIZE: u32 = 512;

fn paint_sky(args: &GenArgs) -> Result<()> {
    let Some(dir) = &args.output else {
        bail!("`workbench gen sky` needs -o FOLDER for the six faces");
    };
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let size = args.size.unwrap_or(DEFAULT_SKY_SIZE).clamp(8, 4096);
    for (image, face) in sky::paint_sky(size).iter().zip(FACE_NAMES) {
        save_png(image, &dir.join(format!("{face}.png")))?;
    }
    Ok(())
}
