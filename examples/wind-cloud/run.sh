#!/usr/bin/env bash
# Wind-cloud test, 34k particles (a cloud of radius 0.05, 2,400 particles) to 4 tau_KH, about
# 15 min on 2 cores: surviving cloud fraction against time (docs/validation.md).
# Usage: bash examples/wind-cloud/run.sh [OUT_DIR] [extra exasph options, e.g. --scheme std]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-wind-cloud-output}
shift || true
bash "$root/scripts/run.sh" --init wind-cloud -n 20 --param radius=0.05 -w 0.046875 --out "$out" "$@"
/usr/bin/python3 "$root/tools/case_plots.py" wind "$out"/snapshot_*.h5 -o "$out/wind-cloud.png"
echo "figure: $out/wind-cloud.png"
