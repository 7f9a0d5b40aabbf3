#!/usr/bin/env bash
# What the overlap of halo exchanges with the SPH passes hides (issue 23, acceptance 3): runs
# Sedov -n SIDE for STEPS steps on RANKS ranks x 1 thread, with the overlap and with
# --no-halo-overlap in turn (O N O N ..., ROUNDS rounds), and prints per round the seconds per
# step each spent in the passes' halo exchanges (the summary's "halo exchanges" line: packing,
# posting, testing, waiting, unpacking; steps after the first), the wall seconds, and the hidden
# fraction 1 - exposed(overlap) / exposed(no overlap); then the medians.
# Usage: bench/halo_overlap.sh [SIDE (100)] [STEPS (6)] [ROUNDS (3)] [RANKS (2)] [EXTRA ...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
side=${1:-100}
steps=${2:-6}
rounds=${3:-3}
ranks=${4:-2}
shift $(($# < 4 ? $# : 4))
exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
. "$root/bench/lib.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
one_thread_ranks "$ranks"

# run NAME ROUND [OPTIONS]: prints "exposed_s_per_step wall_s"
run() {
    local log=$work/$1$2.log
    shift 2
    "${mpi[@]}" "$exe" --init sedov -n "$side" -s "$steps" --threads 1 --out "$work/out" "$@" \
        >"$log" 2>&1 || { tail -3 "$log" >&2; exit 1; }
    echo "$(sed -nE 's/^halo exchanges of the SPH passes: ([0-9.e+-]+) s per step.*/\1/p' "$log")" \
        "$(sed -nE 's/^done: .* wall ([0-9.]+) s.*/\1/p' "$log")"
}

echo "Sedov -n $side, $steps steps, $ranks ranks x 1 thread, $rounds rounds (overlap, none alternating) $*"
printf '%-6s %14s %14s %9s %9s %8s\n' round exposed_ovl_s exposed_none_s wall_ovl wall_none hidden
for r in $(seq "$rounds"); do
    read -r eo wo < <(run overlap "$r" "$@")
    read -r en wn < <(run none "$r" --no-halo-overlap "$@")
    hidden=$(awk -v o="$eo" -v n="$en" 'BEGIN {printf "%.3f", (n > 0 ? 1 - o / n : 0)}')
    printf '%-6s %14.4g %14.4g %9.2f %9.2f %8s\n' "$r" "$eo" "$en" "$wo" "$wn" "$hidden"
    echo "$eo $en $wo $wn $hidden" >>"$work/rows"
done
col() { awk -v c="$1" '{print $c}' "$work/rows" | median; }
printf '%-6s %14.4g %14.4g %9.2f %9.2f %8s\n' median "$(col 1)" "$(col 2)" "$(col 3)" "$(col 4)" \
    "$(col 5)"
