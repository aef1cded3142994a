#!/usr/bin/env bash
# Installs what the tests need beyond the Rust toolchain, if missing:
# Mesa's software Vulkan/GL drivers (the window's snapshot tests), Xvfb (the
# real window) and Chromium (the lab report's page). Idempotent: a machine
# that has them installs nothing. `scripts/test.sh` calls it; `.ci/run`
# starts it early, beside the build, so the download costs no time.
set -euo pipefail

packages=(mesa-vulkan-drivers libvulkan1 libegl1 libegl-mesa0 libgl1-mesa-dri xvfb xauth chromium)
missing=()
for p in "${packages[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
if ! command -v apt-get >/dev/null; then
    echo "missing ${missing[*]} and no apt-get: install Mesa's drivers, Xvfb and Chromium yourself" >&2
    exit 1
fi
sudo=""
[ "$(id -u)" = 0 ] || sudo="sudo"
echo "== installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
