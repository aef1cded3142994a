#!/usr/bin/env bash
# Adds the project's scenes (scenes/*.p3f, scenes/*.nff) to a fuzz corpus at
# run time, so the fuzzer starts from real files without committing copies.
# Usage: fuzz/seed.sh DEST_DIR. Files over 64 KiB are left out: the fuzzer
# mutates small inputs far faster, and big meshes add little new syntax.
set -euo pipefail
dest=${1:?usage: fuzz/seed.sh DEST_DIR}
root="$(cd "$(dirname "$0")/.." && pwd)"
mkdir -p "$dest"
shopt -s nullglob
n=0
for scene in "$root"/scenes/*.p3f "$root"/scenes/*.nff; do
    if [ "$(stat -c %s "$scene")" -le 65536 ]; then
        cp "$scene" "$dest/scene-$(basename "$scene")"
        n=$((n + 1))
    fi
done
echo "seeded $dest with $n scene(s) from scenes/"
