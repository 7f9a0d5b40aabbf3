#!/usr/bin/env bash
# Sets up and builds exasph if needed, then runs every test (unit, validation, command line).
# Extra arguments go to ctest (e.g. -L unit). Without arguments, the build without MPI and HDF5
# (issue 18: what a GPU node image without them builds) is made in build-serial/ and its tests
# run first (of the validation runs only the square patch's, made from a lattice: without the
# HDF5 glass cache the others would each make their glass again, ~15 min more; their code is
# the same in both builds); EXASPH_SKIP_SERIAL=1 skips it.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bash "$root/scripts/setup.sh"
if [ $# -eq 0 ] && [ -z "${EXASPH_SKIP_SERIAL:-}" ]; then
    serial="${EXASPH_SERIAL_BUILD_DIR:-$root/build-serial}"
    echo "exasph test: the build without MPI and HDF5, in $serial"
    if [ ! -f "$serial/CMakeCache.txt" ]; then
        generator=()
        command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
        cmake -S "$root" -B "$serial" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
            -DEXASPH_MPI=OFF -DEXASPH_HDF5=OFF -DEXASPH_BENCH=OFF
    fi
    cmake --build "$serial" -j "$(nproc)"
    (cd "$serial" && ctest --output-on-failure -j 2 -LE "validation|evrard|resilience" &&
        ctest --output-on-failure -j 2 -R '^SquarePatch\.') # lattice: no glass to make
    echo "exasph test: the full build"
fi
cd "${EXASPH_BUILD_DIR:-$root/build}"
exec ctest --output-on-failure -j 2 "$@"
