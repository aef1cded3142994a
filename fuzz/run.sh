#!/usr/bin/env bash
# A bounded fuzz run of both targets, for CI: fails on any crash (the
# crashing input is kept in fuzz/artifacts/<target>/). Seconds per target:
# FUZZ_SECONDS (default 30).
#
# Builds with cargo itself, with the flags `cargo fuzz build --sanitizer
# none` gives rustc (cargo-fuzz 0.13's src/project.rs), so CI need not
# install cargo-fuzz (about 90 s cold) for a 60 s run. Stable Rust: the
# coverage instrumentation takes stable `-C` flags; only the sanitizers
# would need nightly (the tracer's only unsafe code is the BVH's AVX2 node
# test and its traversal stack, which the property tests compare with the
# safe paths). Overflow checks and debug assertions are on in the fuzz
# crate's release profile. Unlike cargo-fuzz, rustc keeps its default
# codegen units: quicker to build, a little slower to run.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
# libFuzzer reads 0 as "no limit": a run that never ends is no bounded run.
if ! [[ $seconds =~ ^[0-9]+$ ]] || ((10#$seconds == 0)); then
    echo "FUZZ_SECONDS=$seconds: give a positive whole number of seconds" >&2
    exit 1
fi
triple=$(rustc -vV | sed -n 's/^host: //p')
coverage=(
    -Cpasses=sancov-module
    -Cllvm-args=-sanitizer-coverage-level=4
    -Cllvm-args=-sanitizer-coverage-inline-8bit-counters
    -Cllvm-args=-sanitizer-coverage-pc-table
    -Cllvm-args=-sanitizer-coverage-trace-compares
    -Cllvm-args=-sanitizer-coverage-stack-depth
    -Cllvm-args=-simplifycfg-branch-fold-threshold=0
    --cfg fuzzing
)
# --target keeps these flags away from build scripts and proc macros.
RUSTFLAGS="${coverage[*]} ${RUSTFLAGS:-}" cargo build --locked --manifest-path fuzz/Cargo.toml \
    --target "$triple" --release --bins
for target in parse parse_render; do
    # New inputs go to a scratch corpus; the committed seeds stay as they are.
    work=$(mktemp -d)
    fuzz/seed.sh "$work"
    mkdir -p "fuzz/artifacts/$target"
    "fuzz/target/$triple/release/$target" -artifact_prefix="fuzz/artifacts/$target/" \
        "$work" "fuzz/corpus/$target" \
        -max_total_time="$seconds" -max_len=16384 -dict=fuzz/scene.dict \
        -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 2>&1 \
        | sed '/^"/d' | tail -n 25
    rm -rf "$work"
done
