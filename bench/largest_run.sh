#!/usr/bin/env bash
# The largest Sedov this machine holds (issue 23): measures the peak memory per particle on a
# probe run (Sedov -n PROBE, 2 steps), picks the largest -n whose peak stays within FRACTION of
# the memory available now (MemAvailable), runs it for STEPS steps on one rank with all threads,
# and prints the particles, the peak RSS per particle, the start-up seconds and the seconds per
# step (the summary's wall over the steps).
# Usage: bench/largest_run.sh [STEPS (2)] [FRACTION (0.8)] [PROBE (100)] [EXTRA ...]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
steps=${1:-2}
fraction=${2:-0.8}
probe=${3:-100}
shift $(($# < 3 ? $# : 3))
exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

bytes_per_particle() { sed -nE 's/.*peak RSS ([0-9.]+) B\/particle.*/\1/p' "$1"; }

"$exe" --init sedov -n "$probe" -s 2 --out "$work/probe" "$@" >"$work/probe.log" 2>&1 ||
    { tail -3 "$work/probe.log" >&2; exit 1; }
probe_bpp=$(bytes_per_particle "$work/probe.log")
avail_kb=$(awk '/^MemAvailable:/ {print $2}' /proc/meminfo)
# the largest side whose particles fit (the per-particle peak falls with size: a safe estimate)
side=$(awk -v a="$avail_kb" -v f="$fraction" -v b="$probe_bpp" \
    'BEGIN {n = f * a * 1024 / b; s = int(exp(log(n) / 3)); while ((s + 1) ^ 3 <= n) s++;
            while (s ^ 3 > n) s--; print s}')
echo "probe -n $probe: $probe_bpp B/particle; $((avail_kb / 1024)) MiB available, using" \
    "$fraction of it: -n $side ($((side * side * side)) particles)"
t0=$(date +%s.%N)
"$exe" --init sedov -n "$side" -s "$steps" --out "$work/big" "$@" >"$work/big.log" 2>&1 ||
    { tail -3 "$work/big.log" >&2; exit 1; }
t1=$(date +%s.%N)
grep -E '^case |^done:|^particle-steps|^seconds per step' "$work/big.log"
wall=$(sed -nE 's/^done: .* wall ([0-9.]+) s.*/\1/p' "$work/big.log")
awk -v t0="$t0" -v t1="$t1" -v w="$wall" -v s="$steps" -v n="$side" \
    -v b="$(bytes_per_particle "$work/big.log")" \
    'BEGIN {printf "largest run: -n %d, %d particles, %.1f B/particle peak, start-up %.0f s, " \
            "%.1f s per step\n", n, n ^ 3, b, t1 - t0 - w, w / s}'
