#!/usr/bin/env bash
# Serves web/dist/ (scripts/build-web.sh) at http://127.0.0.1:PORT/ with
# the two headers that make the page cross-origin isolated, which its
# Web Workers need to share memory. --no-isolation leaves them out, to
# see what a host that cannot send them gives.
#
#   scripts/serve-web.sh [--port N] [--no-isolation]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
exec python3 "$root/scripts/serve_web.py" --dir "$root/web/dist" "$@"
