# Shared by the bench scripts: medians over repeated runs of exasph's summary lines.
# Logs are $out/log1 .. $out/log$repeats.

median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

# value REGEX-WITH-ONE-GROUP: the captured number, median over the runs
value() {
    for r in $(seq "$repeats"); do sed -nE "s|.*$1.*|\1|p" "$out/log$r"; done | median
}

# phase NAME: median seconds per step of one phase
phase() {
    for r in $(seq "$repeats"); do
        grep 'seconds per step by phase' "$out/log$r" | sed 's/.*phase[^:]*: //' |
            awk -v k="$1" '{for (i = 1; i < NF; i += 2) if ($i == k) print $(i+1)}'
    done | median
}

phase_names() { grep 'seconds per step by phase' "$out/log1" | sed 's/.*phase[^:]*: //' |
    awk '{for (i = 1; i < NF; i += 2) printf "%s ", $i}'; }

# one_thread_ranks RANKS: sets the array `mpi` to an mpirun of RANKS ranks x 1 thread, unbound
# (Open MPI: oversubscribed, and allowed as root when run as root).
one_thread_ranks() {
    mpi=(mpirun -np "$1" --bind-to none -x OMP_NUM_THREADS=1)
    if mpirun --version 2>&1 | grep -qE 'Open MPI|OpenRTE'; then
        mpi+=(--oversubscribe)
        [ "$(id -u)" = 0 ] && mpi+=(--allow-run-as-root)
    fi
}

# beside_reference SCRIPT REF: for the scripts that run exasph beside a reference binary
# (compare.sh, time_to_solution.sh): checks REF (may be empty: no reference) and sets `exe` to
# exasph: $EXASPH_BIN as it is, else the tree built by scripts/setup.sh in $EXASPH_BUILD_DIR or
# build/ ($root: the repository).
beside_reference() {
    if [ -n "$2" ] && [ ! -x "$2" ]; then
        echo "$1: the reference binary '$2' is not an executable" >&2
        exit 2
    fi
    if [ -n "${EXASPH_BIN:-}" ]; then
        [ -x "$EXASPH_BIN" ] || { echo "$1: EXASPH_BIN '$EXASPH_BIN' is not an executable" >&2; exit 2; }
        exe=$(cd "$(dirname "$EXASPH_BIN")" && pwd)/$(basename "$EXASPH_BIN")
    else
        bash "$root/scripts/setup.sh" >/dev/null
        exe="${EXASPH_BUILD_DIR:-$root/build}/exasph"
    fi
}
