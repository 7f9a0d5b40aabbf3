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

median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
value() { # SED-REGEX with one group: the number it captures, median over the runs
    for r in $(seq "$repeats"); do sed -nE "s|.*$1.*|\1|p" "$out/log$r"; done | median
}
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
phases=$(grep 'seconds per step by phase' "$out/log1" | sed 's/.*phase[^:]*: //')
set -- $phases
while [ $# -ge 2 ]; do
    name=$1
    vals=$(for r in $(seq "$repeats"); do
        grep 'seconds per step by phase' "$out/log$r" | sed 's/.*phase[^:]*: //' |
            awk -v k="$name" '{for (i = 1; i < NF; i += 2) if ($i == k) print $(i+1)}'
    done | median)
    echo "| $name | $vals |"
    shift 2
done
