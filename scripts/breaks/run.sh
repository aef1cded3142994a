#!/usr/bin/env bash
# Shows that a test fails on the break it exists for, and passes without it.
#
#   scripts/breaks/run.sh [NAME...]     (default: every scripts/breaks/*.patch)
#   scripts/breaks/run.sh --check       each patch names its test and still
#                                       applies (seconds; CI runs this)
#
# Each NAME.patch here is a deliberate bug: its header says what it breaks,
# and its `Test:` line the command that must catch it. For each, this
# applies the patch, runs the command expecting a test to fail (a build
# error does not count), reverts the patch and runs it again expecting at
# least one test to pass. The patch is reverted on any exit. A patch that no
# longer applies (the code moved on) fails: make it again on today's code.
# The window's patches run the real window under Xvfb (scripts/test.sh
# installs it).
set -euo pipefail
cd "$(dirname "$0")/../.."

check_only=false
if [ "${1:-}" = --check ]; then
    check_only=true
    shift
fi
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
    for patch in scripts/breaks/*.patch; do
        names+=("$(basename "$patch" .patch)")
    done
fi

applied=""
revert() {
    if [ -n "$applied" ]; then
        git apply -R "$applied"
        applied=""
    fi
}
trap revert EXIT

log=$(mktemp)
failures=0
for name in "${names[@]}"; do
    patch=scripts/breaks/$name.patch
    command=$(sed -n 's/^Test: //p' "$patch")
    if [ -z "$command" ]; then
        echo "FAIL $name: no Test: line in $patch"; failures=$((failures + 1)); continue
    fi
    if ! git apply --check "$patch" 2>"$log"; then
        echo "FAIL $name: the patch does not apply"; cat "$log"; failures=$((failures + 1)); continue
    fi
    if $check_only; then
        echo "ok   $name: applies; tested by: $command"
        continue
    fi
    git apply "$patch"
    applied=$patch
    bash -c "$command" >"$log" 2>&1 && broken=0 || broken=$?
    revert
    if [ "$broken" = 0 ] || ! grep -q "^test result: FAILED" "$log"; then
        echo "FAIL $name: no test failed with the break ($command)"; tail -20 "$log"
        failures=$((failures + 1)); continue
    fi
    caught=$(grep -m1 "panicked at" -A2 "$log" | tail -n +2 | head -2 | tr '\n' ' ')
    if ! bash -c "$command" >"$log" 2>&1 || ! grep -Eq "^test result: ok\. [1-9][0-9]* passed" "$log"; then
        echo "FAIL $name: the test does not pass without the break ($command)"; tail -20 "$log"
        failures=$((failures + 1)); continue
    fi
    echo "ok   $name: caught (${caught:0:200}), passes once reverted"
done
rm -f "$log"
[ "$failures" = 0 ]
