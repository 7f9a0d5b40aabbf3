#!/usr/bin/env bash
# The sanitize build's end-to-end runs (issue 21): short runs of the program under ASan and
# UBSan, each scheme and path once: Sedov (volume elements, glass), Evrard (tree gravity), the
# square patch (weakly compressible, Tait EOS), Noh (lattice, viscosity switch); with HDF5 also a snapshot, a checkpoint and a restart from it, and a snapshot read
# back as initial conditions. Any sanitizer report ends a run with an error, failing the test.
#   run_cases.sh EXE WORKDIR HAVE_HDF5(0|1)
set -euo pipefail
exe=$1
work=$2
hdf5=${3:-0}
rm -rf "$work"
mkdir -p "$work"
export OMP_NUM_THREADS=2
run() {
    echo "+ exasph $*"
    "$exe" "$@" >"$work/last.log" 2>&1 || { cat "$work/last.log"; exit 1; }
    tail -n 1 "$work/last.log"
}
run --init sedov -n 10 -s 4 --out "$work/sedov"
run --init evrard -n 10 -s 4 --out "$work/evrard"
run --init square-patch -n 12 -s 4 --out "$work/patch"
run --init noh -n 10 --lattice -s 4 --av-switch --out "$work/noh"
if [ "$hdf5" = 1 ] || [ "$hdf5" = ON ]; then
    run --init sedov -n 10 --lattice -s 4 --checkpoint-every 2 -w 2 --out "$work/cp"
    run --restart "$work/cp" -s 6 --out "$work/cp"
    run --init "$work/cp/snapshot_000004.h5" -s 2 --out "$work/from_snapshot"
fi
echo "sanitize runs: no report"
