//! Test inputs from outside the crate (the shared corpus of scene files,
//! the repository's `scenes/`): a developer's checkout may lack them, and
//! a test then says it skipped; in CI (`CI` set, to anything) a missing
//! input fails the test, or the check it feeds would pass by checking
//! nothing.

/// Reports that `what` is missing: a failure under `CI`, a skip otherwise.
///
/// # Panics
/// When `CI` is set.
pub fn missing(what: &str) {
    if let Some(ci) = std::env::var_os("CI") {
        panic!("{what} is missing, and CI (CI={ci:?}) must check it");
    }
    eprintln!("{what} is missing: skipped (a failure under CI)");
}
