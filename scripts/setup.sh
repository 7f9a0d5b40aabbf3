#!/usr/bin/env bash
# Installs the Debian packages exasph needs (when run as root), then configures and builds it in
# build/. Sourced by run.sh and test.sh; safe to run again (it only does what is missing).
# EXASPH_CONFIGURE_ARGS: extra CMake arguments for build/ (test.sh sets which tests it builds).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${EXASPH_BUILD_DIR:-$root/build}"

packages=(cmake g++ make ninja-build libgtest-dev libbenchmark-dev libcli11-dev libtomlplusplus-dev
          zlib1g-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev python3 python3-numpy
          python3-h5py python3-matplotlib)
# EXASPH_TEST_PACKAGES: what the tests need beyond the build (scripts/test.sh: ParaView's
# pvpython and Xvfb for the client test, pip for the Python reader's install test).
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
         "Google Benchmark, CLI11, toml++ and MPI are installed" >&2
fi

read -r -a extra <<< "${EXASPH_CONFIGURE_ARGS:-}"
if [ ! -f "$build/CMakeCache.txt" ]; then
    generator=()
    command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
    cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${extra[@]}"
elif [ ${#extra[@]} -gt 0 ]; then
    cmake "$build" "${extra[@]}" >/dev/null
fi
cmake --build "$build" -j "$(nproc)"
