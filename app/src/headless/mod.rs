//! One module per subcommand.

pub mod bench;
pub mod compare;
pub mod generate;
pub mod inspect;
pub mod lesson;
pub mod observe;
pub mod render;
pub mod report;
pub mod sweep;

use std::io::IsTerminal;

use tracer::render::RenderSettings;
use tracer::stats::SceneCounts;

use crate::measure::benchmark::Event;
use crate::measure::cost::BruteForceCost;

/// Warns on stderr, before rendering, when brute force over this scene
/// would look like a hang; the scene's `accel` is respected all the same.
fn warn_brute_force(settings: &RenderSettings, counts: &SceneCounts) {
    warn_brute_force_with(
        settings,
        counts,
        "add `--accel bvh` to render it in seconds",
    );
}

/// [`warn_brute_force`] with the `fix` the subcommand offers.
fn warn_brute_force_with(settings: &RenderSettings, counts: &SceneCounts, fix: &str) {
    if let Some(cost) = BruteForceCost::of(settings, counts) {
        eprintln!("warning: {}; {fix}", cost.describe());
    }
}

/// A spinner on stderr naming the stage of a long piece of work (it says
/// what runs while a large scene's structure builds or its frames trace);
/// hidden when stderr is not a terminal, so scripted output stays clean.
fn stage_spinner() -> indicatif::ProgressBar {
    let spinner = if std::io::stderr().is_terminal() {
        indicatif::ProgressBar::new_spinner()
    } else {
        indicatif::ProgressBar::hidden()
    };
    spinner.enable_steady_tick(std::time::Duration::from_millis(200));
    spinner.set_style(
        indicatif::ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    spinner
}

/// Steps of a progress bar per frame.
const STEPS: u64 = 1000;

/// A progress bar on stderr for `frames` frames of [`STEPS`] steps; hidden
/// when stderr is not a terminal, so scripted output stays clean.
fn progress_bar(frames: usize) -> indicatif::ProgressBar {
    let bar = if std::io::stderr().is_terminal() {
        indicatif::ProgressBar::new(frames as u64 * STEPS)
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template("{spinner} [{elapsed_precise}] {wide_bar} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

/// A progress bar on stderr for `runs` frames of each of `labels`, fed by
/// the benchmark runner's events; hidden when stderr is not a terminal, so
/// scripted output stays clean.
fn runner_progress(labels: Vec<String>, runs: usize) -> impl FnMut(Event) {
    let runs = runs.max(1);
    let bar = progress_bar(labels.len() * runs);
    move |event| match event {
        Event::Rendering {
            case,
            run,
            fraction,
        } => {
            let done = (case * runs + run) as f64 + f64::from(fraction);
            bar.set_position((done * STEPS as f64) as u64);
            bar.set_message(format!(
                "{}/{} {} (run {}/{runs})",
                case + 1,
                labels.len(),
                labels[case],
                run + 1
            ));
        }
        Event::Measured { case, .. } if case + 1 == labels.len() => bar.finish_and_clear(),
        Event::Measured { .. } => {}
    }
}
