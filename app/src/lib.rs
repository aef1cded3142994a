//! The Whitted Workbench application: the command line, the headless
//! commands and the window. The binary only calls [`run`].
//!
//! Items are `pub(crate)` unless the binary or the tests use them. Some
//! serve only the window (study charts, lesson progress) or only the
//! headless commands, so a build without the window, or for the web,
//! leaves them unused; the default build's dead-code lint, which CI runs,
//! still finds code that nothing uses.
#![cfg_attr(any(not(feature = "window"), target_family = "wasm"), allow(dead_code))]

pub mod bundled;
pub mod cli;
pub(crate) mod compare_side;
pub(crate) mod describe;
pub(crate) mod figures;
#[cfg(feature = "window")]
pub mod gui;
#[cfg(not(target_family = "wasm"))]
pub(crate) mod headless;
pub(crate) mod image_file;
pub mod lessons;
pub mod load;
pub mod measure;
pub(crate) mod reports;

#[cfg(not(target_family = "wasm"))]
use clap::Parser;
/// The web page starts its workers with this (`initThreadPool(n)` in
/// `web/index.html`) before it starts the window.
#[cfg(target_family = "wasm")]
pub use wasm_bindgen_rayon::init_thread_pool;

/// Parses the command line and runs what it asks for: a subcommand, or the
/// window when there is none.
#[cfg(not(target_family = "wasm"))]
pub fn run() -> std::process::ExitCode {
    let cli = cli::Cli::parse();
    if cli.command.is_some() {
        headless::quiet_on_closed_stdout();
    }
    let result = match cli.command {
        Some(cli::Headless::Render(args)) => headless::render::run(&args),
        Some(cli::Headless::Inspect(args)) => headless::inspect::run(&args),
        Some(cli::Headless::Observe(args)) => headless::observe::run(&args),
        Some(cli::Headless::Bench(args)) => headless::bench::run(&args),
        Some(cli::Headless::Compare(args)) => headless::compare::run(&args),
        Some(cli::Headless::Gen(args)) => headless::generate::run(&args),
        Some(cli::Headless::Sweep(args)) => headless::sweep::run(&args),
        Some(cli::Headless::Lesson(args)) => headless::lesson::run(&args),
        Some(cli::Headless::Report(args)) => headless::report::run(&args),
        None => window(cli),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}

/// The window the command line asks for without a subcommand.
#[cfg(all(feature = "window", not(target_family = "wasm")))]
fn window(cli: cli::Cli) -> anyhow::Result<()> {
    cli.screenshot_plan()
        .and_then(|plan| gui::run(cli.scene, plan, cli.observer, cli.lesson, cli.lesson_folder))
}

/// Built without the window (cargo feature `window`): the flags are still
/// checked, then the user is told what this build can do.
#[cfg(all(not(feature = "window"), not(target_family = "wasm")))]
fn window(cli: cli::Cli) -> anyhow::Result<()> {
    cli.screenshot_plan()?;
    anyhow::bail!(
        "this workbench was built without the window (cargo feature `window`): \
         run a subcommand (workbench --help lists them)"
    )
}
