#!/usr/bin/env bash
# Sets up and builds exasph if needed, then runs every test (unit, validation, command line).
# Extra arguments go to ctest (e.g. -L unit).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh"
cd "${EXASPH_BUILD_DIR:-$root/build}"
exec ctest --output-on-failure -j 2 "$@"
