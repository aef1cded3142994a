#!/usr/bin/env bash
# The window's render speed against a headless render of the same scene and
# settings (issue 14: the window should reach >= 80% of headless rays/s).
#
#   scripts/window_speed.sh [--rounds N] [--profile] [--observer] [SCENE...]
#
# For each scene (default: balls_medium, AA 2 x 2 from its own `spp 2`, and
# showcase, adaptive within 12 x 12's bounds, its 8 px lens), each round opens the real window under Xvfb with a
# fresh home (no saved settings), leaves it alone until the render is done
# (`--screenshot`: the line it prints is what the statistics panel shows),
# and runs `workbench render` of the same file; the order alternates every
# round, as the machine's speed drifts. Prints each round's rays/s and the
# medians, and the median of the per-round ratios.
#
# --observer: compares the window with the observer view on (`--observer`)
# against the window without it, instead of against headless (issue 25: the
# main render keeps >= 90% of its speed with the observer on).
#
# --profile: one more window per scene under `perf record`, printing which
# threads took the CPU while the render ran (render-N, llvmpipe-N, the UI
# thread `workbench`, ...), as a share of the samples in that span.
#
# WORKBENCH=path uses that binary; otherwise the dev profile is built (the
# tracer is optimised in it as in release, see Cargo.toml).
set -euo pipefail
cd "$(dirname "$0")/.."

rounds=5
profile=0
observer=0
scenes=()
while [ $# -gt 0 ]; do
    case "$1" in
        --rounds) rounds="$2"; shift 2 ;;
        --profile) profile=1; shift ;;
        --observer) observer=1; shift ;;
        -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
        *) scenes+=("$1"); shift ;;
    esac
done
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/balls_medium.p3f scenes/showcase.p3f)

if [ -z "${WORKBENCH:-}" ]; then
    cargo build --quiet --bin workbench
    WORKBENCH=target/debug/workbench
fi
for tool in xvfb-run python3; do
    command -v "$tool" >/dev/null || { echo "needs $tool (scripts/test.sh installs Xvfb)" >&2; exit 1; }
done
[ "$profile" = 0 ] || command -v perf >/dev/null || { echo "--profile needs perf" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$work}"

# Runs the window on $1 in a fresh home, the command prefix in the rest
# (WINDOW_FLAGS go to the window); prints the window's line ("saved
# screenshot ... (12.3M rays/s)").
window() {
    local scene="$1"
    shift
    local home
    home=$(mktemp -d "$work/home.XXXX")
    # shellcheck disable=SC2086
    HOME="$home" XDG_CONFIG_HOME="$home" xvfb-run -a -s "-screen 0 1400x900x24" \
        "$@" "$WORKBENCH" --scene "$scene" ${WINDOW_FLAGS:-} --screenshot "$home/shot.png" \
        2>/dev/null | tail -n 1
}

# rays/s of the window's line, in rays/s.
window_rays() {
    python3 -c '
import re, sys
m = re.search(r"\(([\d.]+)([kMG]?) rays/s\)", sys.stdin.read())
if not m: sys.exit("the window printed no rays/s")
print(float(m.group(1)) * {"": 1, "k": 1e3, "M": 1e6, "G": 1e9}[m.group(2)])'
}

# What the window is compared with: a headless render, or with --observer
# the window with the observer view on.
headless_rays() {
    if [ "$observer" = 1 ]; then
        WINDOW_FLAGS=--observer window "$1" | window_rays
        return
    fi
    "$WORKBENCH" render "$1" -o "$work/headless.png" --stats json 2>/dev/null |
        python3 -c 'import json, sys; print(json.load(sys.stdin)["rays_per_second"])'
}
second=headless
[ "$observer" = 0 ] || second="observer on"

for scene in "${scenes[@]}"; do
    echo "== $scene: window vs $second, $rounds rounds"
    results="$work/results"
    : >"$results"
    for round in $(seq 1 "$rounds"); do
        if [ $((round % 2)) = 1 ]; then
            w=$(window "$scene" | window_rays)
            h=$(headless_rays "$scene")
        else
            h=$(headless_rays "$scene")
            w=$(window "$scene" | window_rays)
        fi
        echo "$w $h" >>"$results"
        python3 -c "print(f'round $round: window {$w/1e6:.2f} M rays/s, $second {$h/1e6:.2f} M rays/s, ratio {$w/$h:.2f}')"
    done
    python3 - "$results" "$second" <<'EOF'
import statistics, sys
rows = [tuple(map(float, line.split())) for line in open(sys.argv[1])]
w = statistics.median(r[0] for r in rows)
h = statistics.median(r[1] for r in rows)
ratios = sorted(r[0] / r[1] for r in rows)
print(f"median: window {w/1e6:.2f} M rays/s, {sys.argv[2]} {h/1e6:.2f} M rays/s; "
      f"ratio of medians {w/h:.2f}, median ratio {statistics.median(ratios):.2f} "
      f"(range {ratios[0]:.2f}-{ratios[-1]:.2f})")
EOF
    if [ "$profile" = 1 ]; then
        window "$scene" perf record -q -F 997 -o "$work/perf.data" >/dev/null
        perf script -i "$work/perf.data" -F comm,time 2>/dev/null | python3 -c '
import collections, sys
samples = []
for line in sys.stdin:
    *comm, time = line.split()
    samples.append((" ".join(comm), float(time.rstrip(":"))))
render = [t for c, t in samples if c.startswith("render-")]
start, end = min(render), max(render)
during = collections.Counter(c for c, t in samples if start <= t <= end)
total = sum(during.values())
print(f"CPU samples while the window rendered ({end - start:.2f} s):")
for comm, n in during.most_common():
    print(f"  {comm:16} {100 * n / total:5.1f}%")'
    fi
done
