#!/usr/bin/env bash
# Isobaric cube, 15k particles to t = 2: density slices through the cube (docs/validation.md).
# Usage: bash examples/isobaric-cube/run.sh [OUT_DIR] [extra exasph options, e.g. --scheme std]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-isobaric-cube-output}
shift || true
bash "$root/scripts/run.sh" --init isobaric-cube -n 20 -w 0.5 --out "$out" "$@"
/usr/bin/python3 "$root/tools/case_plots.py" slice "$out"/snapshot_*.h5 -o "$out/isobaric-cube.png" --field rho
echo "figure: $out/isobaric-cube.png"
