#!/usr/bin/env bash
# Installs the Debian packages exasph needs (when run as root), then configures and builds it in
# build/. Called by run.sh, test.sh, the examples and benchmarks; safe to run again (it only does
# what is missing).
#   EXASPH_TARGETS: what to build (default: everything configured). run.sh sets "exasph": the
#     program alone, with only the packages its build needs.
#   EXASPH_CONFIGURE_ARGS: extra CMake arguments for build/, applied every time (test.sh sets
#     which tests it builds).
#   EXASPH_FIRST_CONFIGURE_ARGS: extra CMake arguments used only when build/ is configured the
#     first time (run.sh: no CUDA backend unless a GPU is visible).
#   EXASPH_TEST_PACKAGES: Debian packages the caller needs beyond the build's.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${EXASPH_BUILD_DIR:-$root/build}"
read -r -a targets <<< "${EXASPH_TARGETS:-}"

# What configuring and building the exasph program needs (CMake finds GoogleTest and Google
# Benchmark at configure time because build/ also holds the tests and benchmarks).
packages=(cmake g++ make ninja-build libgtest-dev libbenchmark-dev libcli11-dev libtomlplusplus-dev
          zlib1g-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev)
# The Python tools (tools/, examples/, bench/) and the tests' scripts.
[ "${targets[*]}" = exasph ] || packages+=(python3 python3-numpy python3-h5py python3-matplotlib)
read -r -a test_packages <<< "${EXASPH_TEST_PACKAGES:-}"
packages+=("${test_packages[@]}")
if command -v dpkg >/dev/null 2>&1; then
    missing=()
    for p in "${packages[@]}"; do
        dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        if [ "$(id -u)" -eq 0 ]; then
            echo "exasph setup: installing ${missing[*]}"
            export DEBIAN_FRONTEND=noninteractive
            apt-get update -q >/dev/null
            apt-get install -y -q --no-install-recommends "${missing[@]}" >/dev/null
        else
            echo "exasph setup: missing Debian packages: ${missing[*]}" >&2
            echo "install them with: sudo apt-get install ${missing[*]}" >&2
            exit 1
        fi
    fi
else
    echo "exasph setup: not a Debian system; assuming cmake, a C++20 compiler, GoogleTest," \
         "Google Benchmark, CLI11, toml++, MPI and parallel HDF5 are installed" >&2
fi

read -r -a extra <<< "${EXASPH_CONFIGURE_ARGS:-}"
if [ ! -f "$build/CMakeCache.txt" ]; then
    read -r -a first <<< "${EXASPH_FIRST_CONFIGURE_ARGS:-}"
    generator=()
    command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
    cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${first[@]}" \
        "${extra[@]}"
elif [ ${#extra[@]} -gt 0 ]; then
    cmake "$build" "${extra[@]}" >/dev/null
fi
target_args=()
[ ${#targets[@]} -gt 0 ] && target_args=(--target "${targets[@]}")
cmake --build "$build" -j "$(nproc)" "${target_args[@]}"
