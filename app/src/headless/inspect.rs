//! `workbench inspect`: the ray tree of one sample of one pixel, as an
//! indented tree or JSON.

use anyhow::{Result, anyhow};
use tracer::render::RenderSettings;

use crate::cli::{InspectArgs, MetricsFormat};
use crate::load::Loaded;
use crate::reports::ray_tree;

pub fn run(args: &InspectArgs) -> Result<()> {
    let loaded = Loaded::for_command(&args.scene, &args.settings.set)?;
    let mut settings = RenderSettings::from_scene(&loaded.scene);
    args.settings.apply(&mut settings);
    let [x, y] = args.pixel[..] else {
        return Err(anyhow!("--pixel takes two numbers, X and Y"));
    };
    let tree = ray_tree::inspect(&loaded.world, None, &settings, (x, y), args.sample)
        .map_err(|e| anyhow!("cannot inspect {}: {e}", args.scene.display()))?;
    match args.format {
        MetricsFormat::Text => print!("{}", ray_tree::text(&tree)),
        MetricsFormat::Json => println!(
            "{}",
            serde_json::to_string_pretty(&ray_tree::json(&tree)).unwrap_or_default()
        ),
    }
    Ok(())
}
