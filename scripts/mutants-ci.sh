#!/usr/bin/env bash
# Mutation testing as CI runs it, in place (the tree must be free: each
# mutant is written into the sources, then put back).
#
#   scripts/mutants-ci.sh --shard          the shard of .ci/mutants-clean
#                                          this commit's CI runs
#   scripts/mutants-ci.sh --changed REV    the listed files' mutants on
#                                          lines changed since REV
#   scripts/mutants-ci.sh FILE [TESTS...]  every mutant of FILE, judged as
#                                          CI would judge it on the list
#
# .ci/mutants-clean lists the files already clean, each with the tests
# that judge it. Every mutant is built at opt-level 0, in seconds, and
# judged by its crate's library tests (the unit tests next to the code):
# - a tracer file by those whose name holds TESTS (`render::film`), its
#   module's own: a mutant they catch, the whole suite catches too
#   (TESTS are the test program's arguments: `--skip NAME` leaves out a
#   test too slow to judge every mutant by);
# - an app file by all of the workbench library's tests (1.3 s).
# Judged by the whole package's tests at opt-level 3, a tracer mutant
# took about 90 CPU-seconds and an app mutant minutes (docs/TESTING.md).
#
# The shard (k of N) turns with the commit count, so successive runs
# cover every listed mutant; N gives each shard MUTANTS_PER_SHARD
# mutants (default 12). --changed tries at once the mutants on the lines
# the latest commits changed (cargo-mutants' --in-diff), which the shard
# would reach only after a whole turn: at most MUTANTS_CHANGED_MAX
# (default 60, about 6 minutes), the first in the list's order, saying
# how many it left to the shards. A mutant missed or timed out fails the
# run.
# cargo-mutants 27.1 tries a file's "delete field" mutants whatever
# `--re` says (17 in the listed files on 2026-12-07): a shard may try a
# few more.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each mutant rebuilds one crate changed by a token: what incremental
# compilation is for (2-3 s a tracer mutant, against 10-14 s without,
# which CI's CARGO_INCREMENTAL=0 chose for its one-off builds).
export CARGO_INCREMENTAL=1
# A property test that fails judges its mutant at once: shrinking the case
# (minutes at opt-level 0, grid.rs's took 130 s) tells nothing more, and
# the failing seeds of mutants are no regressions to keep in the tree.
export PROPTEST_MAX_SHRINK_ITERS=0 PROPTEST_DISABLE_FAILURE_PERSISTENCE=1

# The mutants of FILE named NAMES (as `--list` gives them; all of them if
# none), judged by TESTS (none: every test of the library).
judge() { # FILE TESTS [NAMES...]
    local file=$1 tests=$2 package
    shift 2
    case $file in
        tracer/*) package=tracer ;;
        app/*) package=workbench ;;
        *)
            echo "$file: neither tracer's nor app's" >&2
            return 1
            ;;
    esac
    local select=()
    if [ $# -gt 0 ]; then
        # One regular expression matching exactly these names.
        select=(--re "^($(printf '%s\n' "$@" | sed 's/[][\\.*^$+?(){}|]/\\&/g' | paste -sd '|'))\$")
    fi
    # $tests split: one test-program argument a word (a filter, --skip NAME).
    scripts/mutants.sh --in-place --baseline=skip "${select[@]}" --cargo-arg=--lib \
        --cargo-arg=--config=profile.dev.package.$package.opt-level=0 "$file" -- -- $tests
}

case ${1:-} in
    --shard) ;;
    --changed)
        if [ $# -ne 2 ] || ! git rev-parse --verify --quiet "$2^{commit}" >/dev/null; then
            echo "usage: scripts/mutants-ci.sh --changed REV (a commit: ${2:-none given})" >&2
            exit 1
        fi
        ;;
    "" | -*)
        echo "usage: scripts/mutants-ci.sh --shard | --changed REV | FILE [TESTS...]" >&2
        exit 1
        ;;
    *)
        if [ ! -f "$1" ]; then
            echo "$1: no such file" >&2
            exit 1
        fi
        judge "$1" "${*:2}"
        exit
        ;;
esac

files=()
declare -A tests=()
while read -r file filter; do
    case $file in '' | '#'*) continue ;; esac
    if [ ! -f "$file" ]; then
        echo ".ci/mutants-clean: $file: no such file" >&2
        exit 1
    fi
    if [[ $file == tracer/* && -z $filter ]]; then
        echo ".ci/mutants-clean: $file names no tests to judge it by" >&2
        exit 1
    fi
    files+=("$file")
    tests[$file]=$filter
done <.ci/mutants-clean
if [ "$1" = --changed ]; then
    diff=$(mktemp)
    trap 'rm -f "$diff"' EXIT
    git diff "$2" HEAD -- "${files[@]}" >"$diff"
    mutants=()
    if [ -s "$diff" ]; then
        mapfile -t mutants < <(scripts/mutants.sh --list --in-diff="$diff" "${files[@]}")
    fi
    most=${MUTANTS_CHANGED_MAX:-60}
    picked=("${mutants[@]:0:most}")
    echo "changed since $2: ${#mutants[@]} mutants in the listed files' changed lines, trying ${#picked[@]}"
    if [ ${#mutants[@]} -gt "$most" ]; then
        echo "the other $((${#mutants[@]} - most)) are left to the rotating shards"
    fi
else
    mapfile -t mutants < <(scripts/mutants.sh --list "${files[@]}")
    if [ ${#mutants[@]} -eq 0 ]; then
        echo ".ci/mutants-clean: its ${#files[@]} files have no mutant" >&2
        exit 1
    fi
    per_shard=${MUTANTS_PER_SHARD:-12}
    shards=$(((${#mutants[@]} + per_shard - 1) / per_shard))
    shard=$(($(git rev-list --count HEAD) % shards))
    picked=("${mutants[@]:shard*per_shard:per_shard}")
    echo "shard $shard of $shards: ${#picked[@]} of ${#mutants[@]} mutants in ${#files[@]} files"
fi
for file in "${files[@]}"; do
    mapfile -t names < <(printf '%s\n' "${picked[@]}" | awk -v f="$file:" 'index($0, f) == 1')
    if [ ${#names[@]} -gt 0 ]; then
        echo "== $file: ${#names[@]} mutants; tests: ${tests[$file]:-all the library has}"
        judge "$file" "${tests[$file]}" "${names[@]}"
    fi
done
