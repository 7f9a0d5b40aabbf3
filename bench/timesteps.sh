#!/usr/bin/env bash
# Time to solution with global and block time steps (issue 20): runs CASE -n SIDE to T_END with
# --timesteps global and --timesteps block in turn (G B G B ..., ROUNDS rounds, same hour), and
# prints per mode the median wall seconds of the steps (the run's own summary, without start-up
# and output), the steps, the particle updates (sum of diagnostics.csv's `active`), the pair terms
# of one neighbour pass summed over the steps (`pairs`), the last L1(rho) and the energy error
# |E_tot(t_end) - E_tot(0)| / |E_tot(0)|; then the wall-time ratio global / block per round.
# Usage: bench/timesteps.sh [CASE (sedov)] [SIDE (50)] [T_END (0.05)] [ROUNDS (3)] [EXTRA ...]
# e.g.   bench/timesteps.sh sedov 50 0.05 3 --scheme std
#        bench/timesteps.sh evrard 20 1 1
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
case=${1:-sedov}
side=${2:-50}
t_end=${3:-0.05}
rounds=${4:-3}
shift $(($# < 4 ? $# : 4))
exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
. "$root/bench/lib.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run MODE ROUND: one run; prints "wall steps updates pairs l1 energy_error"
run() {
    local mode=$1 dir=$work/$1$2
    shift 2
    "$exe" --init "$case" -n "$side" --t-end "$t_end" --timesteps "$mode" --out "$dir" "$@" \
        >"$dir.log" 2>&1 || { tail -3 "$dir.log" >&2; exit 1; }
    local wall
    wall=$(sed -nE 's/^done: .* wall ([0-9.]+) s.*/\1/p' "$dir.log")
    /usr/bin/python3 - "$dir/diagnostics.csv" "$wall" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
e0, e1 = float(rows[0]["etot"]), float(rows[-1]["etot"])
print(sys.argv[2], len(rows) - 1, sum(float(r["active"]) for r in rows),
      sum(float(r["pairs"]) for r in rows), rows[-1]["l1_rho"], abs(e1 - e0) / abs(e0))
PY
}

for r in $(seq "$rounds"); do
    for mode in global block; do
        run "$mode" "$r" "$@" >"$work/$mode.$r"
    done
done
echo "$case -n $side to t = $t_end, $rounds rounds (global, block alternating), $*"
printf '%-7s %9s %6s %10s %10s %8s %9s\n' mode wall_s steps updates pairs L1 dE/E
for mode in global block; do
    col() { for r in $(seq "$rounds"); do awk -v c="$1" '{print $c}' "$work/$mode.$r"; done | median; }
    printf '%-7s %9.2f %6d %10.3g %10.3g %8.4f %9.2e\n' "$mode" "$(col 1)" "$(col 2)" "$(col 3)" \
        "$(col 4)" "$(col 5)" "$(col 6)"
done
ratios=$(for r in $(seq "$rounds"); do
    awk 'NR == FNR {g = $1; next} {printf "%.2f\n", g / $1}' "$work/global.$r" "$work/block.$r"
done)
echo "time to solution, global / block: median $(echo "$ratios" | median) (rounds: $(echo $ratios))"
