//! `workbench`: the Whitted Workbench. With no arguments it will open the
//! window; subcommands run the same engine headless.

mod cli;
mod commands;
mod load;
mod output;
mod report;

use clap::{CommandFactory, Parser};

fn main() -> std::process::ExitCode {
    let cli = cli::Cli::parse();
    let result = match cli.command {
        Some(cli::Command::Render(args)) => commands::render::run(&args),
        Some(cli::Command::Bench(args)) => commands::bench::run(&args),
        None => {
            // The window is not there yet: say what the binary can do.
            let _ = cli::Cli::command().print_help();
            Ok(())
        }
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
