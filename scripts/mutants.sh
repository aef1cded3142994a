#!/usr/bin/env bash
# Mutation testing: cargo-mutants changes the code one mutant at a time (a
# `>` into `>=`, a result into a default, a statement deleted) and reports
# each one the tests let through. docs/TESTING.md says how to read it.
#
#   scripts/mutants.sh [OPTIONS...] FILES...
#   scripts/mutants.sh --install       installs cargo-mutants, if missing
#
# FILES are source files (tracer/src/optics.rs ...); OPTIONS go to
# `cargo mutants` as they are (`--shard 3/20`, `--in-place`, `--list`).
# `--cargo-arg=--lib` builds and runs the library's unit tests only (the
# maths next to the code), not the examples and integration tests beside
# them; words after `-- --` filter the tests by name. Fastest on a loaded
# machine, judged by one module's own tests (docs/TESTING.md):
#   CARGO_TARGET_DIR=$PWD/target scripts/mutants.sh --baseline=skip \
#     --cargo-arg=--lib --cargo-arg=--config=profile.dev.package.tracer.opt-level=0 \
#     tracer/src/render/film.rs -- -- render::film
# Settings and the reviewed exclusions: .cargo/mutants.toml. Results:
# MUTANTS_OUT (default target/mutants)/mutants.out/ (caught.txt, missed.txt, timeout.txt,
# unviable.txt, outcomes.json). Fails when a mutant is missed or times out.
#
# By default each mutant is built in a copy of the tree (the worktree
# stays free to edit), one at a time (MUTANTS_JOBS, default 1: the tests
# are multi-threaded already), each mutant's tests killed after
# MUTANTS_TIMEOUT seconds (default 300: a mutant that loops for ever).
set -euo pipefail
cd "$(dirname "$0")/.."

version=27.1.0
if ! cargo mutants --version 2>/dev/null | grep -qF "$version"; then
    echo "== installing cargo-mutants $version"
    cargo install --locked cargo-mutants --version "$version"
fi
# `--install` alone: only that (CI installs it beside its builds).
[ "$*" = --install ] && exit 0

# A word naming a file is a file to mutate; every other word goes to
# cargo-mutants (`--shard 3/20` and `--shard=3/20` alike).
options=()
files=()
for arg in "$@"; do
    if [ -f "$arg" ]; then
        files+=(--file "$arg")
    else
        options+=("$arg")
    fi
done
if [ ${#files[@]} -eq 0 ]; then
    echo "usage: scripts/mutants.sh [OPTIONS...] FILES..." >&2
    exit 1
fi

# `--in-place` runs one mutant at a time in the tree itself, and
# cargo-mutants refuses `--jobs` beside it.
jobs=(--jobs "${MUTANTS_JOBS:-1}")
for arg in "${options[@]}"; do
    [ "$arg" = --in-place ] && jobs=()
done

exec cargo mutants \
    "${jobs[@]}" \
    --timeout "${MUTANTS_TIMEOUT:-300}" \
    --output "${MUTANTS_OUT:-target/mutants}" \
    "${files[@]}" "${options[@]}"
