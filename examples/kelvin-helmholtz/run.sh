#!/usr/bin/env bash
# Kelvin-Helmholtz instability, 27k particles to t = 3 (about 15 min on 2 cores): the mode
# amplitude against time and density slices at t = 1.5 and 3, where the billows have rolled up
# (docs/validation.md).
# Usage: bash examples/kelvin-helmholtz/run.sh [OUT_DIR] [extra exasph options, e.g. --scheme std]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-kelvin-helmholtz-output}
shift || true
bash "$root/scripts/run.sh" --init kelvin-helmholtz -n 48 -w 0.25 --out "$out" "$@"
/usr/bin/python3 "$root/tools/case_plots.py" kh "$out"/snapshot_*.h5 -o "$out/kelvin-helmholtz.png"
# The snapshots nearest t = 1.5 and the last one (-w 0.25 writes 12, the 6th at t = 1.5).
snaps=("$out"/snapshot_*.h5)
/usr/bin/python3 "$root/tools/case_plots.py" slice "${snaps[5]}" "${snaps[-1]}" --size 1 \
    -o "$out/kelvin-helmholtz-slices.png"
echo "figures: $out/kelvin-helmholtz.png $out/kelvin-helmholtz-slices.png"
