#!/usr/bin/env bash
# Runs every test: installs what the window tests need (Mesa's software
# Vulkan/GL drivers for the snapshot tests, Xvfb for the real window),
# idempotently, then `cargo test`, then the real window under Xvfb.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(mesa-vulkan-drivers libvulkan1 libegl1 libegl-mesa0 libgl1-mesa-dri xvfb xauth)
missing=()
for p in "${packages[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    if ! command -v apt-get >/dev/null; then
        echo "missing ${missing[*]} and no apt-get: install Mesa's drivers and Xvfb yourself" >&2
        exit 1
    fi
    sudo=""
    [ "$(id -u)" = 0 ] || sudo="sudo"
    echo "== installing ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# wgpu and Mesa ask for a runtime directory; give them a private one.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
    XDG_RUNTIME_DIR=$(mktemp -d)
    export XDG_RUNTIME_DIR
fi

echo "== cargo test"
# --locked: the tests run on the versions Cargo.lock names, or fail.
cargo test --locked

echo "== the real window under Xvfb"
xvfb-run -a -s "-screen 0 1400x900x24" cargo test --locked --test window -- --ignored
