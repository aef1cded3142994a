//! `workbench`: the Whitted Workbench. With no arguments it opens the
//! window; subcommands run the same engine headless.

fn main() -> std::process::ExitCode {
    workbench::run()
}
