#!/usr/bin/env bash
# Sets up and builds exasph if needed, then runs it. Without arguments: the default case (rotating
# square patch, 27,000 particles, to t = 0.02 s). Any arguments are passed to exasph.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh" >&2
exec "${EXASPH_BUILD_DIR:-$root/build}/exasph" "$@"
