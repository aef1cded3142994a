#!/usr/bin/env bash
# A bounded fuzz run of both targets, for CI: fails on any crash (the
# crashing input is kept in fuzz/artifacts/<target>/). Stable Rust works with
# `--sanitizer none` (ASan needs nightly; the tracer's only unsafe code is
# the BVH's AVX2 node test and its traversal stack, which the property
# tests compare with the safe paths). Seconds per target: FUZZ_SECONDS (default 30).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
# libFuzzer reads 0 as "no limit": a run that never ends is no bounded run.
if ! [[ $seconds =~ ^[0-9]+$ ]] || ((10#$seconds == 0)); then
    echo "FUZZ_SECONDS=$seconds: give a positive whole number of seconds" >&2
    exit 1
fi
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
for target in parse parse_render; do
    # New inputs go to a scratch corpus; the committed seeds stay as they are.
    work=$(mktemp -d)
    fuzz/seed.sh "$work"
    cargo fuzz run --sanitizer none "$target" "$work" "fuzz/corpus/$target" -- \
        -max_total_time="$seconds" -max_len=16384 -dict=fuzz/scene.dict \
        -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 2>&1 \
        | sed '/^"/d' | tail -n 25
    rm -rf "$work"
done
