#!/usr/bin/env bash
# End-to-end benchmark: rotating square patch at -n SIDE (default 100: 10^6 particles) for a few
# steps, repeated; prints the median particle-steps/s (total and per core), peak RSS bytes per
# particle and seconds per step of each phase, as Markdown.
# Usage: bench/square_patch.sh [SIDE] [STEPS] [REPEATS] [THREADS]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
side=${1:-100}
steps=${2:-5}
repeats=${3:-3}
threads=${4:-2}
bash "$root/scripts/setup.sh" >/dev/null
exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for r in $(seq "$repeats"); do
    "$exe" --init square-patch -n "$side" -s "$steps" --threads "$threads" --out "$out/run$r" \
        > "$out/log$r"
done

. "$root/bench/lib.sh"
echo "command: exasph --init square-patch -n $side -s $steps --threads $threads (median of $repeats)"
echo
echo "| particles | threads | particle-steps/s | per core | peak RSS B/particle |"
echo "|---|---|---|---|---|"
n=$(grep -o '[0-9]* particles' "$out/log1" | awk '{print $1}')
echo "| $n | $threads | $(value 'particle-steps/s ([0-9.e+-]+),') |" \
     "$(value 'per core ([0-9.e+-]+) ') | $(value 'peak RSS ([0-9.]+) B') |"
echo
echo "| phase | s/step (median) |"
echo "|---|---|"
for name in $(phase_names); do
    echo "| $name | $(phase "$name") |"
done
