#!/usr/bin/env bash
# Gresho-Chan vortex, 12.8k particles to t = 1: v_phi against the analytic profile and L1 against time (docs/validation.md).
# Usage: bash examples/gresho-chan/run.sh [OUT_DIR] [extra exasph options, e.g. --scheme std]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-gresho-chan-output}
shift || true
bash "$root/scripts/run.sh" --init gresho-chan -n 40 -w 0.25 --out "$out" "$@"
/usr/bin/python3 "$root/tools/case_plots.py" gresho "$out"/snapshot_*.h5 -o "$out/gresho-chan.png"
echo "figure: $out/gresho-chan.png"
