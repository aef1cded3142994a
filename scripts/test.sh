#!/usr/bin/env bash
# Runs every test: installs what the window tests need (Mesa's software
# Vulkan/GL drivers for the snapshot tests, Xvfb for the real window) and
# Chromium for the lab report's page, idempotently, then `cargo test`, the
# real window under Xvfb, and a report opened in headless Chromium.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/test-packages.sh

# wgpu and Mesa ask for a runtime directory; give them a private one.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
    XDG_RUNTIME_DIR=$(mktemp -d)
    export XDG_RUNTIME_DIR
fi

echo "== lock files"
# The fuzz crate has its own lock file, which CI's fuzz stage reads with
# --locked: a tracer dependency added or dropped must show up there too.
# Checked first, in seconds, not after twenty minutes of tests.
cargo metadata --locked --format-version 1 --manifest-path fuzz/Cargo.toml >/dev/null

echo "== cargo test"
# --locked: the tests run on the versions Cargo.lock names, or fail.
cargo test --locked

echo "== the real window under Xvfb"
# -noreset: by default Xvfb resets when its last client leaves, and a
# window opening during the reset cannot connect ("Failed to open
# connection to X server": 13 of 1 300 back-to-back connections, against
# 0 of 1 300 with it). The tests' windows come and go two at a time.
xvfb-run -a -s "-screen 0 1400x900x24 -noreset" cargo test --locked --test window -- --ignored

echo "== the lab report in headless Chromium"
# No console error, no request leaving the file, every image loaded.
report_dir=$(mktemp -d)
trap 'rm -rf "$report_dir"' EXIT
# The binary `cargo test` built for the end-to-end tests: `cargo run` would
# build the app once more (without the tests' features), minutes in CI.
"${CARGO_TARGET_DIR:-target}/debug/workbench" report scenes/balls_low.p3f --quick --runs 1 -o "$report_dir/report.html"
python3 scripts/check_report_page.py "$report_dir/report.html"
