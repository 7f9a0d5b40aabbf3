#!/usr/bin/env bash
# The silent-data-corruption defences' false alarms (issue 21, criterion 4): clean runs of every
# case with every scheme at several sizes and rank counts, each for STEPS steps; prints one
# Markdown row per run with its rollbacks (alarms) and the watchdog's budget widenings
# (sim/energy_watchdog.hpp), then the totals. A clean run should have neither.
#   bash bench/false_alarms.sh
# Environment (defaults in brackets): CASES [every case], SCHEMES [std ve wc pe sh; "default":
# the case's own],
# SIDES [8 12 16 24], RANKS [1 3], STEPS [200]; runs use one thread per rank.
set -euo pipefail
cd "$(dirname "$0")/.."
exe=build/exasph
cases=${CASES:-square-patch sedov noh evrard gresho-chan isobaric-cube kelvin-helmholtz wind-cloud turbulence}
schemes=${SCHEMES:-std ve wc pe sh}
sides=${SIDES:-8 12 16 24}
ranks=${RANKS:-1 3}
steps=${STEPS:-200}
mpirun=(mpirun --oversubscribe -x OMP_NUM_THREADS=1)
[ "$(id -u)" -eq 0 ] && mpirun+=(--allow-run-as-root)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "| case | scheme | -n | ranks | steps run | alarms | budget widenings | end |"
echo "|---|---|---|---|---|---|---|---|"
runs=0 alarms=0 widened=0 steps_total=0
for c in $cases; do
    for s in $schemes; do
        for n in $sides; do
            for r in $ranks; do
                log="$work/$c-$s-$n-$r.log"
                cmd=("$exe" --init "$c" -n "$n" -s "$steps" --threads 1 --out "$work/out")
                [ "$s" != default ] && cmd+=(--scheme "$s")
                [ "$r" -gt 1 ] && cmd=("${mpirun[@]}" -np "$r" "${cmd[@]}")
                end=ok
                "${cmd[@]}" > "$log" 2>&1 || end="exit $?: $(grep -m1 'error' "$log" | cut -c1-80)"
                done_steps=$(sed -nE 's/^done: ([0-9]+) steps.*/\1/p' "$log")
                a=$(grep -c '^silent data corruption' "$log" || true)
                w=$(grep -c '^sdc watchdog' "$log" || true)
                echo "| $c | $s | $n | $r | ${done_steps:-0} | $a | $w | $end |"
                runs=$((runs + 1)) alarms=$((alarms + a)) widened=$((widened + w))
                steps_total=$((steps_total + ${done_steps:-0}))
            done
        done
    done
done
echo
echo "$runs runs, $steps_total steps: $alarms alarms, $widened budget widenings"
