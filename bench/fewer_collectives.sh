#!/usr/bin/env bash
# What --sync-every and --diagnostics-every save (issue 23, acceptance 2): runs Sedov --lattice
# -n SIDE for STEPS steps on RANKS ranks x 1 thread, every step synced and summed (E) and with
# --sync-every K --diagnostics-every K (L) in turn (E L E L ..., ROUNDS rounds), and prints per
# round and mode the wall seconds, the seconds per step of the sync phase (rank 0: the sync, or
# the refresh of the halos between syncs), the collectives per step, the syncs and the halo ratio;
# then the medians. --on-sdc off, so that rollback points do not bring syncs of their own.
# Usage: bench/fewer_collectives.sh [SIDE (50)] [STEPS (60)] [ROUNDS (3)] [RANKS (4)] [K (20)]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
side=${1:-50}
steps=${2:-60}
rounds=${3:-3}
ranks=${4:-4}
k=${5:-20}
exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
. "$root/bench/lib.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
one_thread_ranks "$ranks"

# run NAME ROUND [OPTIONS]: prints "wall_s sync_s_per_step collectives_per_step syncs halo_ratio"
run() {
    local log=$work/$1$2.log
    shift 2
    "${mpi[@]}" "$exe" --init sedov --lattice -n "$side" -s "$steps" --threads 1 --on-sdc off \
        --out "$work/out" "$@" >"$log" 2>&1 || { tail -3 "$log" >&2; exit 1; }
    local coll syncs
    coll=$(sed -nE 's/^collectives: ([0-9.]+) per step.*/\1/p' "$log")
    syncs=$(sed -nE 's/^collectives: .* domain syncs in ([0-9]+) of.*/\1/p' "$log")
    echo "$(sed -nE 's/^done: .* wall ([0-9.]+) s.*/\1/p' "$log")" \
        "$(sed -nE 's/^seconds per step by phase .* sync ([0-9.e+-]+) .*/\1/p' "$log")" \
        "${coll:-3}" "${syncs:-$steps}" \
        "$(sed -nE 's/^communication: .* halo ratio mean ([0-9.]+) .*/\1/p' "$log")"
}

echo "Sedov --lattice -n $side, $steps steps, $ranks ranks x 1 thread, $rounds rounds" \
    "(every step E, --sync-every $k --diagnostics-every $k L, alternating)"
printf '%-6s %-4s %8s %9s %12s %6s %7s\n' round mode wall_s sync_s coll/step syncs halo
for r in $(seq "$rounds"); do
    read -r we se ce ye he < <(run every "$r")
    read -r wl sl cl yl hl < <(run lazy "$r" --sync-every "$k" --diagnostics-every "$k")
    printf '%-6s %-4s %8.2f %9.4f %12s %6s %7s\n' "$r" E "$we" "$se" "$ce" "$ye" "$he"
    printf '%-6s %-4s %8.2f %9.4f %12s %6s %7s\n' "$r" L "$wl" "$sl" "$cl" "$yl" "$hl"
    echo "$we $se $wl $sl" >>"$work/rows"
done
col() { awk -v c="$1" '{print $c}' "$work/rows" | median; }
printf 'median wall E %.2f s, L %.2f s; sync phase E %.4f s/step, L %.4f s/step\n' \
    "$(col 1)" "$(col 3)" "$(col 2)" "$(col 4)"
