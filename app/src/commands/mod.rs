//! One module per subcommand.

pub mod bench;
pub mod compare;
pub mod generate;
pub mod inspect;
pub mod render;

use std::io::IsTerminal;

use crate::measure::benchmark::Event;

/// A progress bar on stderr for `runs` frames of each of `labels`, fed by
/// the benchmark runner's events; hidden when stderr is not a terminal, so
/// scripted output stays clean.
fn runner_progress(labels: Vec<String>, runs: usize) -> impl FnMut(Event) {
    const STEPS: u64 = 1000;
    let runs = runs.max(1);
    let bar = if std::io::stderr().is_terminal() {
        indicatif::ProgressBar::new((labels.len() * runs) as u64 * STEPS)
    } else {
        indicatif::ProgressBar::hidden()
    };
    bar.set_style(
        indicatif::ProgressStyle::with_template("{spinner} [{elapsed_precise}] {wide_bar} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
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
