#!/usr/bin/env bash
# Sets up and builds exasph if needed, then runs every test (unit, validation, command line).
# Extra arguments go to ctest in build/ (e.g. -L unit). Without arguments, three builds:
#  1. build-serial/, without MPI and HDF5 (issue 18: what a GPU node image without them
#     builds): every test it has, the long validation runs included;
#  2. build/, the full build: the tests that need MPI or HDF5 (mpi, io, tools, the ParaView
#     client, fuzz replays) and the command line; the unit and validation tests are neither built nor run a second time
#     (EXASPH_SINGLE_RANK_TESTS=OFF: a single-rank run is the same code and arithmetic in both
#     builds, and test_mpi_cases runs every case under real MPI on 1 and 3 ranks);
#  3. build-mpich/, the same code with MPICH instead of Open MPI (issue 23: supercomputers run
#     MPICH-derived MPI), without HDF5 and CUDA: the MPI tests only;
#  4. build-sanitize/, ASan + UBSan (issue 21): the unit tests, the fuzz corpora, the small MPI
#     tests and short runs of every scheme, label sanitize.
# EXASPH_SKIP_SERIAL=1 / EXASPH_SKIP_MPICH=1 / EXASPH_SKIP_SANITIZE=1 skip builds 1 / 3 / 4 (with
# 1 skipped, build/ runs everything).
# Every build treats compiler warnings as errors (EXASPH_WERROR; nvcc's device code always does),
# so that a new warning fails CI.
# build/ gets the CUDA backend wherever nvcc is found (-UEXASPH_CUDA: CMake's default again, also
# where scripts/run.sh configured build/ without it on a machine without a GPU).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
single_rank=ON # build/ builds and runs the single-rank tests unless build-serial/ runs them
[ $# -eq 0 ] && [ -z "${EXASPH_SKIP_SERIAL:-}" ] && single_rank=OFF
EXASPH_TEST_PACKAGES="python3-paraview python3-yt xvfb python3-pip libmpich-dev mpich universal-ctags" \
    EXASPH_CONFIGURE_ARGS="-DEXASPH_SINGLE_RANK_TESTS=$single_rank -UEXASPH_CUDA -DEXASPH_WERROR=ON" \
    bash "$root/scripts/setup.sh"
full="${EXASPH_BUILD_DIR:-$root/build}"
if [ $# -gt 0 ]; then
    cd "$full"
    exec ctest --output-on-failure -j 2 "$@"
fi

# Configures (once) and builds a second build folder: build_in DIR CMAKE_ARGS...
build_in() {
    local dir=$1
    shift
    if [ ! -f "$dir/CMakeCache.txt" ]; then
        local generator=()
        command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
        cmake -S "$root" -B "$dir" "${generator[@]}" -DEXASPH_BENCH=OFF -DEXASPH_WERROR=ON "$@"
    fi
    cmake --build "$dir" -j "$(nproc)"
}

if [ -z "${EXASPH_SKIP_SERIAL:-}" ]; then
    serial="${EXASPH_SERIAL_BUILD_DIR:-$root/build-serial}"
    echo "exasph test: 1. the build without MPI and HDF5, in $serial"
    build_in "$serial" -DCMAKE_BUILD_TYPE=Release -DEXASPH_MPI=OFF -DEXASPH_HDF5=OFF
    (cd "$serial" && ctest --output-on-failure -j 2)
    echo "exasph test: 2. the full build (unit and validation tests ran above)"
    (cd "$full" && ctest --output-on-failure -j 2 -LE "unit|backend|validation|evrard|resilience")
else
    echo "exasph test: the full build, every test"
    (cd "$full" && ctest --output-on-failure -j 2)
fi
if [ -z "${EXASPH_SKIP_MPICH:-}" ]; then
    mpich="${EXASPH_MPICH_BUILD_DIR:-$root/build-mpich}"
    echo "exasph test: 3. the build with MPICH (MPI tests only), in $mpich"
    if [ ! -f "$mpich/CMakeCache.txt" ]; then
        generator=()
        command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
        cmake -S "$root" -B "$mpich" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DEXASPH_HDF5=OFF \
            -DEXASPH_CUDA=OFF -DEXASPH_BENCH=OFF -DEXASPH_SINGLE_RANK_TESTS=OFF -DEXASPH_WERROR=ON \
            -DMPI_CXX_COMPILER=/usr/bin/mpicxx.mpich -DMPIEXEC_EXECUTABLE=/usr/bin/mpiexec.mpich
    fi
    cmake --build "$mpich" -j "$(nproc)" --target test_mpi_domain test_mpi_square_patch \
        test_mpi_cases test_mpi_gpu_host test_mpi_scale test_mpi_lazy_sync
    (cd "$mpich" && ctest --output-on-failure -j 2 -L mpi)
fi
if [ -z "${EXASPH_SKIP_SANITIZE:-}" ]; then
    sanitize="${EXASPH_SANITIZE_BUILD_DIR:-$root/build-sanitize}"
    echo "exasph test: 4. the sanitize build (ASan + UBSan), in $sanitize"
    build_in "$sanitize" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DEXASPH_SANITIZE=ON \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1"
    cd "$sanitize"
    exec ctest --output-on-failure -j 2 -L sanitize
fi
