//! One side of an A/B comparison set up from `workbench render`'s flags
//! in one string: what `workbench compare --a/--b` and the web page's
//! `?compare` share. Above the command line's definitions, which the
//! measuring runners stand below.

use std::sync::Arc;

use anyhow::{Context, Result, anyhow};
use tracer::render::RenderSettings;
use tracer::world::World;

use crate::cli::{EncodingArgs, SettingsArgs};
use crate::load::Loaded;
use crate::measure::benchmark::Case;

/// One side of a comparison: its case, the world it renders (the scene
/// with the side's own `--set` edits) and those edits in words.
pub(crate) struct SideSetup {
    pub(crate) case: Case,
    pub(crate) world: Arc<World>,
    pub(crate) edits: Vec<String>,
}

/// Side `name` (`a`, `b`) of a comparison of `loaded`, from `flags`,
/// `workbench render`'s flags in one string, over `base` and
/// `base_encoding`, what both sides share: `workbench compare --a` and the
/// web page's `?compare` set their sides up alike.
pub(crate) fn side_from_flags(
    loaded: &Loaded,
    name: &str,
    flags: &str,
    base: &SettingsArgs,
    base_encoding: &EncodingArgs,
) -> Result<SideSetup> {
    let (own, own_encoding) =
        SettingsArgs::parse_str(flags).map_err(|e| anyhow!("--{name} \"{flags}\": {e}"))?;
    let (edited, edits) = loaded
        .edited(&own.set)
        .with_context(|| format!("--{name} \"{flags}\""))?;
    // The side's lens edits turn depth of field on as its scene's lens
    // does.
    let mut settings = RenderSettings::from_scene(&edited.scene);
    base.apply(&mut settings);
    own.apply(&mut settings);
    let encoding = if own_encoding.srgb {
        own_encoding.encoding()
    } else {
        base_encoding.encoding()
    };
    let case = Case {
        label: name.to_uppercase(),
        settings,
        encoding,
    };
    Ok(SideSetup {
        case,
        world: edited.world,
        edits,
    })
}
