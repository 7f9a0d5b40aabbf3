#!/usr/bin/env bash
# End-to-end benchmark (issue 7): Sedov (glass, cached) at 125k and 10^6 particles, as
# 1 rank x 2 threads and 2 ranks x 1 thread; prints a Markdown table of particle-steps/s, per
# core, peak RSS bytes per particle and seconds per step of each phase (medians of REPEATS runs).
# Usage: bench/run.sh [STEPS] [REPEATS] [SIDES]     (defaults: 5, 3, "50 100")
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
steps=${1:-5}
repeats=${2:-3}
sides=${3:-"50 100"}
bash "$root/scripts/setup.sh" >/dev/null
exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
. "$root/bench/lib.sh"
mpi=(mpirun --oversubscribe --bind-to none)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "Sedov, $steps steps, median of $repeats; command: ${mpi[*]} -np R $exe --init sedov -n SIDE -s $steps --threads T"
echo
header=0
for side in $sides; do
    for config in "1 2" "2 1"; do
        set -- $config
        ranks=$1 threads=$2
        out="$tmp/n${side}_${ranks}x${threads}"
        mkdir -p "$out"
        for r in $(seq "$repeats"); do
            OMP_NUM_THREADS=$threads "${mpi[@]}" -x OMP_NUM_THREADS -np "$ranks" "$exe" \
                --init sedov -n "$side" -s "$steps" --threads "$threads" --out "$out/run$r" \
                > "$out/log$r"
        done
        names=$(phase_names)
        if [ $header -eq 0 ]; then
            printf "| particles | ranks x threads | particle-steps/s | per core | peak RSS B/particle |"
            for n in $names; do printf " %s s |" "$n"; done
            printf "\n|---|---|---|---|---|"
            for n in $names; do printf -- "---|"; done
            printf "\n"
            header=1
        fi
        n=$(grep -o '[0-9]* particles' "$out/log1" | head -1 | awk '{print $1}')
        printf "| %s | %s x %s | %s | %s | %s |" "$n" "$ranks" "$threads" \
            "$(value 'particle-steps/s ([0-9.e+-]+),')" "$(value 'per core ([0-9.e+-]+) ')" \
            "$(value 'peak RSS ([0-9.]+) B')"
        for name in $names; do printf " %s |" "$(phase "$name")"; done
        printf "\n"
    done
done
