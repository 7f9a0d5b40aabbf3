#!/usr/bin/env bash
# Time of `exasph render` (issue 22): a slice and a projection of rho at RESOLUTION^2 pixels of a
# SIDE^3-particle Sedov snapshot (lattice, one step), ROUNDS times each, on THREADS threads of
# one rank; prints the median wall seconds of each (GNU time) and the per-round figures.
# Usage: bench/render.sh [SIDE (100: 10^6 particles)] [RESOLUTION (1024)] [ROUNDS (3)] [THREADS (2)]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
side=${1:-100}
res=${2:-1024}
rounds=${3:-3}
threads=${4:-2}
exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
. "$root/bench/lib.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$exe" --init sedov -n "$side" --lattice -s 1 -w 1 --threads "$threads" --out "$work/run" >/dev/null
snap=$work/run/snapshot_000001.h5
for mode in slice projection; do
    extra=()
    [ "$mode" = projection ] && extra=(--project)
    times=$(for r in $(seq "$rounds"); do
        OMP_NUM_THREADS=$threads /usr/bin/time -f "%e" "$exe" render "$snap" --resolution "$res" \
            "${extra[@]}" --out "$work/$mode" 2>&1 >/dev/null | tail -1
    done)
    echo "$mode: $((side * side * side)) particles, ${res}^2 pixels, $threads threads: median" \
        "$(echo "$times" | median) s (rounds: $(echo $times))"
done
