#!/usr/bin/env bash
# Time to solution beside a reference binary (issue 19, criterion 3): Sedov -n SIDE to t = T_END,
# exasph with its default scheme and the reference (sphexa-org/sphexa, built by the user outside
# this repository) with its default (ve), run in turn (A B A B ...) so that both see the same
# state of a shared, drifting machine. Per round: each command's wall time (start-up included),
# exasph's steps and last L1(rho) against the exact solution; then the ratio reference / exasph of
# every round and their median. The reference prints no L1 (issue 19 computed 0.090 from its
# output at -n 50, t = 0.05). Without a reference binary: exasph's rounds only.
# Usage: bench/time_to_solution.sh [REF_BINARY]   (or REF=...; from the environment:)
#   SIDE=50  T_END=0.05  ROUNDS=3  THREADS=2 (one process, OMP_NUM_THREADS=THREADS)
#   EXASPH_BIN=path (this exasph binary as it is; without it scripts/setup.sh builds the tree in
#   $EXASPH_BUILD_DIR or build/)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ref=${1:-${REF:-}}
side=${SIDE:-50}
t_end=${T_END:-0.05}
rounds=${ROUNDS:-3}
threads=${THREADS:-2}
. "$root/bench/lib.sh"
beside_reference time_to_solution.sh "$ref"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# timed DIR LOG CMD...: runs CMD in DIR (output to DIR/LOG) and prints its wall seconds.
timed() {
    local dir=$1 log=$2
    shift 2
    mkdir -p "$dir"
    local t0 t1
    t0=$(date +%s.%N)
    (cd "$dir" && OMP_NUM_THREADS=$threads "$@" >"$log" 2>&1) ||
        { echo "time_to_solution.sh: failed: $* (log: $dir/$log)" >&2; tail -5 "$dir/$log" >&2; exit 1; }
    t1=$(date +%s.%N)
    awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.2f", b - a}'
}

echo "Sedov -n $side to t = $t_end, $threads threads, $rounds rounds (exasph, then the reference, in turn)"
echo "exasph: $exe --init sedov -n $side --t-end $t_end --threads $threads"
[ -n "$ref" ] && echo "reference: OMP_NUM_THREADS=$threads $ref --init sedov -n $side -s $t_end"
echo
echo "| round | exasph s | steps | L1(rho) | reference s | reference / exasph |"
echo "|---|---|---|---|---|---|"
for r in $(seq "$rounds"); do
    d="$tmp/exasph$r"
    te=$(timed "$d" log "$exe" --init sedov -n "$side" --t-end "$t_end" --threads "$threads" --out out)
    steps=$(sed -nE 's/^done: ([0-9]+) steps.*/\1/p' "$d/log")
    l1=$(grep -oE 'L1\(rho\) [0-9.eE+-]+' "$d/log" | tail -1 | awk '{print $2}')
    tr="-" ratio="-"
    if [ -n "$ref" ]; then
        tr=$(timed "$tmp/ref$r" log "$ref" --init sedov -n "$side" -s "$t_end")
        ratio=$(awk -v a="$te" -v b="$tr" 'BEGIN {printf "%.2f", b / a}')
        echo "$ratio" >>"$tmp/ratios"
    fi
    echo "$te" >>"$tmp/exasph_s"
    echo "| $r | $te | $steps | ${l1:--} | $tr | $ratio |"
done
echo
echo "exasph median $(median <"$tmp/exasph_s") s"
if [ -n "$ref" ]; then
    echo "reference / exasph: $(paste -sd' ' "$tmp/ratios"), median **$(median <"$tmp/ratios")**"
fi
