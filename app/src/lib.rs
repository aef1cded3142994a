//! The Whitted Workbench application: the command line, the headless
//! commands and the window. The binary only calls [`run`].

pub mod bundled;
pub mod cli;
pub mod commands;
pub mod gui;
pub mod load;
pub mod measure;
pub mod output;
pub mod report;

use clap::Parser;

/// Parses the command line and runs what it asks for: a subcommand, or the
/// window when there is none.
pub fn run() -> std::process::ExitCode {
    let cli = cli::Cli::parse();
    let result = match cli.command {
        Some(cli::Command::Render(args)) => commands::render::run(&args),
        Some(cli::Command::Inspect(args)) => commands::inspect::run(&args),
        Some(cli::Command::Bench(args)) => commands::bench::run(&args),
        Some(cli::Command::Compare(args)) => commands::compare::run(&args),
        Some(cli::Command::Gen(args)) => commands::generate::run(&args),
        Some(cli::Command::Sweep(args)) => commands::sweep::run(&args),
        None => cli
            .screenshot_plan()
            .and_then(|plan| gui::run(cli.scene, plan)),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
