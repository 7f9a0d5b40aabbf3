#!/usr/bin/env bash
# Sedov-Taylor blast wave, 125k particles to t = 0.05, profiles against the exact solution (docs/validation.md).
# Usage: bash examples/sedov/run.sh [OUT_DIR] [extra exasph options, e.g. --scheme std]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-sedov-output}
shift || true
bash "$root/scripts/run.sh" --init sedov -n 50 --t-end 0.05 -w 0.05 --out "$out" "$@"
/usr/bin/python3 "$root/tools/profiles.py" "$(ls "$out"/snapshot_*.h5 | tail -1)" -o "$out/sedov.png"
echo "figure: $out/sedov.png"
