#!/usr/bin/env bash
# The cost of --double-precision (issue 17): Sedov (glass, cached) at SIDE^3 particles, 1 rank x
# 2 threads, runs alternating without and with the flag; prints medians of particle-steps/s,
# peak RSS bytes per particle and the momentum-energy pass's seconds per step.
# Usage: bench/precision.sh [STEPS] [REPEATS] [SIDE]     (defaults: 5, 3, 100)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
steps=${1:-5}
repeats=${2:-3}
side=${3:-100}
exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
. "$root/bench/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for r in $(seq "$repeats"); do
    for mode in float double; do
        flag=()
        [ "$mode" = double ] && flag=(--double-precision)
        mkdir -p "$tmp/$mode"
        OMP_NUM_THREADS=2 "$exe" --init sedov -n "$side" -s "$steps" --threads 2 "${flag[@]}" \
            --out "$tmp/$mode/run$r" > "$tmp/$mode/log$r"
    done
done
echo "Sedov -n $side, $steps steps, 1 x 2, median of $repeats (alternating): $exe --init sedov" \
    "-n $side -s $steps --threads 2 [--double-precision]"
echo
echo "| derived fields | particle-steps/s | peak RSS B/particle | momentum_energy s/step |"
echo "|---|---|---|---|"
for mode in float double; do
    out="$tmp/$mode"
    printf "| %s | %s | %s | %s |\n" "$mode" "$(value 'particle-steps/s ([0-9.e+-]+),')" \
        "$(value 'peak RSS ([0-9.]+) B')" "$(phase momentum_energy)"
done
