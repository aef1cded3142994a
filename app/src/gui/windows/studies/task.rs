//! The study's thread and its export: points measured in the background,
//! forwarded to the window as they come, and the results written to disk.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use anyhow::Context;

use crate::figures::study_plot;
use crate::image_file::save_png;
use crate::measure::benchmark::Stop;
use crate::measure::study::{self, Param, Point, Study, StudyEvent, Subject};
use crate::reports::bench_table::Format;
use crate::reports::study_table;

use super::{StudyProgress, Update};

/// The table as `table.md` and `table.csv` and the chart as `chart.png`
/// in `dir/study-<param>-<subject>`; returns that folder.
pub(crate) fn write_export(
    dir: &Path,
    param: Param,
    points: &[Point],
    subject: &str,
) -> anyhow::Result<PathBuf> {
    let stem = study_plot::subject_stem(subject);
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

/// Runs the study, sending its progress and points; says whether it was
/// cancelled.
pub(super) fn run(
    study: &Study,
    subject: &Subject,
    stop: &AtomicBool,
    send: &dyn Fn(Update),
) -> anyhow::Result<bool> {
    let never = AtomicBool::new(false);
    let stop = Stop {
        now: stop,
        after_frame: &never,
    };
    let mut on_event = |event: StudyEvent| {
        send(match event {
            StudyEvent::Preparing { what, fraction } => {
                Update::Progress(StudyProgress::Preparing(what.to_string(), fraction))
            }
            StudyEvent::Rendering {
                point,
                run,
                fraction,
            } => Update::Progress(StudyProgress::Rendering {
                point,
                run,
                fraction,
            }),
            StudyEvent::Measured { result, .. } => Update::Measured(Box::new(result.clone())),
        })
    };
    study::run(study, subject, stop, &mut on_event).map(|outcome| outcome.cancelled)
}
