#!/usr/bin/env bash
# Side by side (issue 19): exasph and a reference binary (sphexa-org/sphexa, built by the user
# outside this repository) on Sedov, run in turn (A B A B ...) so that both see the same state of
# a shared, drifting machine; only ratios measured in one run are quoted. Per run: seconds per
# step over steps 2..STEPS from each code's own per-step timers (bench/step_timings.py), its
# density and momentum-energy phases, and the peak RSS of every rank (GNU time) per particle.
# Prints a Markdown table: medians over the rounds, and the ratio reference / exasph of every
# round with its median. Without a reference binary: exasph's columns only. With BASE_BIN (an
# older exasph binary, e.g. the commit before a change that should not cost speed): it runs in
# the same rounds (exasph, then BASE_BIN, then the reference) and its columns give old / new.
# Usage: bench/compare.sh [REF_BINARY]        (or REF=...; settings from the environment:)
#   SIDES="100 50" (particles per axis)  ROUNDS=3  STEPS=7  CONFIGS="1x2 2x1" (ranks x threads)
#   SCHEMES="std ve" (exasph --scheme std / its default ve; the reference --prop std / its
#   default, ve)  EXASPH_BIN=path (measure this exasph binary as it is, e.g. an older build kept
#   aside; without it scripts/setup.sh builds the tree in $EXASPH_BUILD_DIR or build/)
#   BASE_BIN=path (an older exasph binary measured beside it, same options)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
ref=${1:-${REF:-}}
sides=${SIDES:-"100 50"}
rounds=${ROUNDS:-3}
steps=${STEPS:-7}
configs=${CONFIGS:-"1x2 2x1"}
schemes=${SCHEMES:-"std ve"}
if [ "$steps" -lt 3 ]; then
    echo "compare.sh: STEPS must be at least 3 (steps 2.. are timed)" >&2
    exit 2
fi
. "$root/bench/lib.sh"
beside_reference compare.sh "$ref"
base_bin=${BASE_BIN:-}
if [ -n "$base_bin" ]; then
    [ -x "$base_bin" ] || { echo "compare.sh: BASE_BIN '$base_bin' is not an executable" >&2; exit 2; }
    base_bin=$(cd "$(dirname "$base_bin")" && pwd)/$(basename "$base_bin")
fi
timings=(/usr/bin/python3 "$root/bench/step_timings.py")
mpi=(mpirun --oversubscribe --bind-to none)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# launch DIR RANKS THREADS CMD...: CMD on RANKS ranks in DIR (stdout and stderr to DIR/log),
# every rank under GNU time (DIR/rss.RANK: its peak RSS in KiB).
launch() {
    local dir=$1 ranks=$2 threads=$3
    shift 3
    mkdir -p "$dir"
    (cd "$dir" && OMP_NUM_THREADS=$threads "${mpi[@]}" -x OMP_NUM_THREADS -np "$ranks" \
        sh -c '/usr/bin/time -f %M -o "rss.${OMPI_COMM_WORLD_RANK:-0}" "$@"' sh "$@" >log 2>&1) ||
        { echo "compare.sh: failed: $* (log: $dir/log)" >&2; tail -5 "$dir/log" >&2; exit 1; }
}

# run_one CODE DIR RANKS THREADS SIDE SCHEME: one run; appends "s/step density me n B/particle"
# to DIR/../CODE.txt
run_one() {
    local code=$1 dir=$2 ranks=$3 threads=$4 side=$5 scheme=$6
    if [ "$code" = exasph ] || [ "$code" = base ]; then
        local bin=$exe
        [ "$code" = base ] && bin=$base_bin
        launch "$dir" "$ranks" "$threads" "$bin" --init sedov -n "$side" -s "$steps" \
            --scheme "$scheme" --threads "$threads" --out out
    else
        local prop=()
        [ "$scheme" = std ] && prop=(--prop std)
        launch "$dir" "$ranks" "$threads" "$ref" --init sedov -n "$side" -s "$steps" "${prop[@]}"
    fi
    local t
    t=$("${timings[@]}" "$([ "$code" = base ] && echo exasph || echo "$code")" "$dir")
    local n=${t##* }
    echo "$t $(cat "$dir"/rss.* | awk -v n="$n" '{s += $1} END {printf "%.0f", s * 1024 / n}')" \
        >>"$dir/../$code.txt"
}

# col FILE K: median of column K
col() { awk -v k="$2" '{print $k}' "$1" | median; }
# ratios FILE_A FILE_B K: per-round B/A of column K, "r1 r2 ..", then the median
ratios() {
    paste -d' ' <(awk -v k="$3" '{print $k}' "$1") <(awk -v k="$3" '{print $k}' "$2") |
        awk '{printf "%s%.2f", (NR > 1 ? " " : ""), $2 / $1}'
}
ratio_median() {
    paste -d' ' <(awk -v k="$3" '{print $k}' "$1") <(awk -v k="$3" '{print $k}' "$2") |
        awk '{print $2 / $1}' | median
}

echo "Sedov, steps 2..$steps timed, $rounds rounds (exasph${base_bin:+, then BASE_BIN}${ref:+, then the reference}, in turn)"
echo "exasph: ${mpi[*]} -np R $exe --init sedov -n SIDE -s $steps --scheme S --threads T"
[ -n "$base_bin" ] && echo "BASE_BIN: the same with $base_bin"
[ -n "$ref" ] && echo "reference: ${mpi[*]} -np R $ref --init sedov -n SIDE -s $steps [--prop std]"
echo
head="| particles | R x T | scheme | exasph s/step |"
rule="|---|---|---|---|"
if [ -n "$base_bin" ]; then
    head+=" old s/step | old/new per round | median |"
    rule+="---|---|---|"
fi
if [ -n "$ref" ]; then
    head+=" ref s/step | ref/exasph per round | median | density ratio | momentum-energy ratio |"
    head+=" exasph particle-steps/s | B/particle exasph / ref |"
    rule+="---|---|---|---|---|---|---|"
else
    head+=" density s | momentum-energy s | particle-steps/s | B/particle |"
    rule+="---|---|---|---|"
fi
echo "$head"
echo "$rule"
for side in $sides; do
    for config in $configs; do
        ranks=${config%x*} threads=${config#*x}
        for scheme in $schemes; do
            base="$tmp/n${side}_${config}_$scheme"
            mkdir -p "$base"
            for r in $(seq "$rounds"); do
                run_one exasph "$base/exasph$r" "$ranks" "$threads" "$side" "$scheme"
                [ -n "$base_bin" ] && run_one base "$base/base$r" "$ranks" "$threads" "$side" "$scheme"
                [ -n "$ref" ] && run_one ref "$base/ref$r" "$ranks" "$threads" "$side" "$scheme"
            done
            a="$base/exasph.txt" b="$base/ref.txt" o="$base/base.txt"
            n=$(col "$a" 4)
            pst=$(awk -v n="$n" -v s="$(col "$a" 1)" 'BEGIN {printf "%.3g", n / s}')
            row=$(printf "| %s | %s | %s | %.3f |" "$n" "$ranks x $threads" "$scheme" "$(col "$a" 1)")
            if [ -n "$base_bin" ]; then
                row+=$(printf " %.3f | %s | **%.2f** |" "$(col "$o" 1)" "$(ratios "$a" "$o" 1)" \
                    "$(ratio_median "$a" "$o" 1)")
            fi
            if [ -n "$ref" ]; then
                row+=$(printf " %.3f | %s | **%.2f** | %.2f | %.2f | %s | %.0f / %.0f |" \
                    "$(col "$b" 1)" "$(ratios "$a" "$b" 1)" "$(ratio_median "$a" "$b" 1)" \
                    "$(ratio_median "$a" "$b" 2)" "$(ratio_median "$a" "$b" 3)" "$pst" \
                    "$(col "$a" 5)" "$(col "$b" 5)")
            else
                row+=$(printf " %.3f | %.3f | %s | %.0f |" "$(col "$a" 2)" "$(col "$a" 3)" \
                    "$pst" "$(col "$a" 5)")
            fi
            echo "$row"
        done
    done
done
[ -n "$base_bin" ] && echo && echo "old/new: BASE_BIN's seconds per step over exasph's (> 1: the new binary is faster)."
if [ -n "$ref" ]; then
    echo
    echo "Ratios are reference / exasph (> 1: exasph is faster): seconds per step, and the density"
    echo "(reference: Density, or XMass + Normalization & Gradh) and momentum-energy phases."
fi
