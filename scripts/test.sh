#!/usr/bin/env bash
# Sets up and builds exasph if needed, then runs every test (unit, validation, command line).
# Extra arguments go to ctest (e.g. -L unit). Without arguments, the build without MPI and HDF5
# (issue 18: what a GPU node image without them builds) is made in build-serial/ and every test
# it has runs there first, the long validation runs included; the full build then runs the rest
# (its MPI, I/O and tools tests) and the short tests again, not the long runs a second time: a
# single-rank run is the same code and arithmetic in both builds, and test_mpi_cases runs every
# case under real MPI on 1 and 3 ranks. EXASPH_SKIP_SERIAL=1 skips the serial build and runs
# everything in the full one.
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
    (cd "$serial" && ctest --output-on-failure -j 2)
    echo "exasph test: the full build (the long validation runs ran above)"
    cd "${EXASPH_BUILD_DIR:-$root/build}"
    exec ctest --output-on-failure -j 2 -LE "validation|evrard|resilience"
fi
cd "${EXASPH_BUILD_DIR:-$root/build}"
exec ctest --output-on-failure -j 2 "$@"
