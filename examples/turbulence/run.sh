#!/usr/bin/env bash
# Driven subsonic turbulence, 27k particles to t = 10: rms Mach number against time and the velocity power spectrum (docs/validation.md).
# Usage: bash examples/turbulence/run.sh [OUT_DIR] [extra exasph options, e.g. --stir-seed 7]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-turbulence-output}
shift || true
bash "$root/scripts/run.sh" --init turbulence -n 30 -w 2.5 --out "$out" "$@"
/usr/bin/python3 "$root/tools/case_plots.py" turb "$out"/snapshot_*.h5 -o "$out/turbulence.png"
echo "figure: $out/turbulence.png"
