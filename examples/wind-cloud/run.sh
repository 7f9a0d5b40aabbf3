#!/usr/bin/env bash
# Wind-cloud test, 32k particles to 4 tau_KH: surviving cloud fraction against time (docs/validation.md).
# Usage: bash examples/wind-cloud/run.sh [OUT_DIR] [extra exasph options, e.g. --scheme std]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-wind-cloud-output}
shift || true
bash "$root/scripts/run.sh" --init wind-cloud -n 20 -w 0.0234375 --out "$out" "$@"
/usr/bin/python3 "$root/tools/case_plots.py" wind "$out"/snapshot_*.h5 -o "$out/wind-cloud.png"
echo "figure: $out/wind-cloud.png"
