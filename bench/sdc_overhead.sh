#!/usr/bin/env bash
# Overhead of the silent-data-corruption defences (issue 8, acceptance 5): the same run with
# --on-sdc off and --on-sdc rollback (state hashes, invariants, watchdog, a rollback point every
# 10 steps), alternating, REPEATS times each; prints the median wall time per step of each and
# the overhead.
#   bash bench/sdc_overhead.sh [SIDE] [STEPS] [REPEATS]      (default: Sedov -n 50, 20 steps, 3)
set -euo pipefail
cd "$(dirname "$0")/.."
side=${1:-50}
steps=${2:-20}
repeats=${3:-3}
exe=build/exasph
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
per_step() { sed -nE 's|^done: ([0-9]+) steps, .* wall ([0-9.]+) s.*|\2 \1|p' "$1" | awk '{print $1 / $2}'; }
for r in $(seq "$repeats"); do
    for mode in off rollback; do
        "$exe" --init sedov -n "$side" -s "$steps" --on-sdc "$mode" --out "$work/$mode" \
            > "$work/$mode.$r.log" 2>&1
        per_step "$work/$mode.$r.log" >> "$work/$mode.times"
    done
done
off=$(median < "$work/off.times")
on=$(median < "$work/rollback.times")
echo "Sedov -n $side, $steps steps, $repeats runs each (median s/step): off $off, rollback $on"
awk -v a="$off" -v b="$on" 'BEGIN {printf "overhead %.2f %%\n", 100 * (b - a) / a}'
