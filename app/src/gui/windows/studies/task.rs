//! The study's thread and its export: points measured in the background,
//! forwarded to the window as they come, and the results written to disk.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::Sender;

use anyhow::Context;

use crate::figures::study_plot;
use crate::image_file::save_png;
use crate::measure::benchmark::Stop;
use crate::measure::study::{self, Param, Point, Study, StudyEvent, Subject};
use crate::reports::bench_table::Format;
use crate::reports::study_table;

use super::Update;

/// The table as `table.md` and `table.csv` and the chart as `chart.png`
/// in `dir/study-<param>-<subject>`; returns that folder.
pub fn write_export(
    dir: &Path,
    param: Param,
    points: &[Point],
    subject: &str,
) -> anyhow::Result<PathBuf> {
    let stem = Path::new(subject)
        .file_stem()
        .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
    let dir = dir.join(format!("study-{param}-{stem}"));
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    for (name, format) in [("table.md", Format::Markdown), ("table.csv", Format::Csv)] {
        let path = dir.join(name);
        std::fs::write(&path, study_table::table(param, points, format))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    save_png(
        &study_plot::chart(param, points, &stem)?,
        &dir.join("chart.png"),
    )?;
    Ok(dir)
}

/// Runs the study, forwarding its events and points.
pub(super) fn run(
    study: &Study,
    subject: &Subject,
    stop: &AtomicBool,
    tx: &Sender<Update>,
    wake: &dyn Fn(),
) {
    let never = AtomicBool::new(false);
    let stop = Stop {
        now: stop,
        after_frame: &never,
    };
    let mut on_event = |event: StudyEvent| {
        let update = match event {
            StudyEvent::Preparing { what, fraction } => {
                Update::Preparing(what.to_string(), fraction)
            }
            StudyEvent::Rendering {
                point,
                run,
                fraction,
            } => Update::Rendering {
                point,
                run,
                fraction,
            },
            StudyEvent::Measured { result, .. } => Update::Measured(Box::new(result.clone())),
        };
        let _ = tx.send(update);
        wake();
    };
    let result = study::run(study, subject, stop, &mut on_event)
        .map(|outcome| outcome.cancelled)
        .map_err(|e| format!("{e:#}"));
    let _ = tx.send(Update::Finished(result));
    wake();
}
