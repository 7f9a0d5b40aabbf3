#!/usr/bin/env bash
# Noh implosion, 33.5k particles to t = 0.6, profiles against the exact solution (docs/validation.md).
# Usage: bash examples/noh/run.sh [OUT_DIR] [extra exasph options, e.g. --scheme std]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-noh-output}
shift || true
bash "$root/scripts/run.sh" --init noh -n 40 -w 0.6 --out "$out" "$@"
/usr/bin/python3 "$root/tools/profiles.py" "$(ls "$out"/snapshot_*.h5 | tail -1)" -o "$out/noh.png"
echo "figure: $out/noh.png"
