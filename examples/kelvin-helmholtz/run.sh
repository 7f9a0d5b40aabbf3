#!/usr/bin/env bash
# Kelvin-Helmholtz instability, 12k particles to t = 3: mode amplitude against time (docs/validation.md).
# Usage: bash examples/kelvin-helmholtz/run.sh [OUT_DIR] [extra exasph options, e.g. --scheme std]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-kelvin-helmholtz-output}
shift || true
bash "$root/scripts/run.sh" --init kelvin-helmholtz -n 32 -w 0.25 --out "$out" "$@"
/usr/bin/python3 "$root/tools/case_plots.py" kh "$out"/snapshot_*.h5 -o "$out/kelvin-helmholtz.png"
echo "figure: $out/kelvin-helmholtz.png"
