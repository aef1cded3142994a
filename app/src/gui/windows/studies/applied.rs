//! A study's point shown in the main view: its structure and value set in
//! the controls, or for the level study its generated scene opened.

use std::path::PathBuf;

use anyhow::Context;
use tracer::accel::AccelKind;
use tracer::generate::{self, GenerateOptions, GeneratorName};

use crate::gui::sides::Controls;
use crate::measure::study::Param;

/// A point's settings, for the main view.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Applied {
    pub(crate) param: Param,
    pub(crate) value: f64,
    pub(crate) accel: AccelKind,
    /// The generator of a level study's point.
    pub(crate) generator: Option<GeneratorName>,
}

impl Applied {
    /// Sets `controls` to the point's structure and value; `scene_width`
    /// turns a resolution into the controls' scale.
    pub(crate) fn apply_to(&self, controls: &mut Controls, scene_width: u32) {
        controls.change_settings(scene_width, |settings| {
            settings.accel = self.accel;
            self.param.apply(settings, self.value);
        });
    }

    /// For a level study's point, its generated scene written as P3F in
    /// the temporary folder (with the point's structure), to open.
    pub(crate) fn scene_file(&self) -> anyhow::Result<Option<PathBuf>> {
        let Some(generator) = self.generator else {
            return Ok(None);
        };
        let level = self.value as u32;
        let mut scene = generate::generate(generator, &GenerateOptions { level, seed: 0 })?;
        scene.accel = Some(match self.accel {
            AccelKind::None => 0,
            AccelKind::Grid => 1,
            AccelKind::Bvh => 2,
        });
        let path = std::env::temp_dir().join(format!(
            "workbench-{generator}-{level}-{}.p3f",
            self.accel.name()
        ));
        let text = format!(
            "# {}\n{}",
            generate::describe(generator, level, 0),
            tracer::scene::write_p3f(&scene)
        );
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
        Ok(Some(path))
    }
}
