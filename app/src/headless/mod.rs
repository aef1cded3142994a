//! One module per subcommand.

pub(crate) mod bench;
pub(crate) mod compare;
pub(crate) mod generate;
pub(crate) mod inspect;
pub(crate) mod lesson;
pub(crate) mod observe;
pub(crate) mod render;
pub(crate) mod report;
pub(crate) mod sweep;

use std::io::IsTerminal;

use tracer::render::RenderSettings;
use tracer::stats::SceneCounts;

use crate::measure::benchmark::Event;
use crate::measure::cost::BruteForceCost;

/// Lets a closed stdout end a subcommand quietly, as it ends any Unix tool.
/// Rust starts programs with SIGPIPE ignored, so once the reader of a pipe
/// has gone (`workbench lesson check | head -1`) every `println!` fails and
/// panics with "failed printing to stdout". With the signal's default
/// action restored the process is simply ended by SIGPIPE (status 141 in a
/// shell), once, for every subcommand and every line it prints. The window
/// keeps SIGPIPE ignored: a socket it writes to closing (the display
/// server, the file dialog's portal) is an error it handles, not its end.
pub(crate) fn quiet_on_closed_stdout() {
    #[cfg(unix)]
    // SAFETY: `signal` with `SIG_DFL` only resets the disposition of
    // SIGPIPE; it runs before any thread of ours is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

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
