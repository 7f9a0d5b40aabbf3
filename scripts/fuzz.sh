#!/usr/bin/env bash
# A fuzzing campaign (issue 21): builds the harnesses of fuzz/ with clang and libFuzzer under
# ASan and UBSan (build-fuzz/), then fuzzes one harness for SECONDS from its seed corpus.
#   bash scripts/fuzz.sh HARNESS SECONDS [JOBS]     HARNESS: command_line, initial_conditions,
#                                                   checkpoint
# New inputs go to build-fuzz/corpus/HARNESS (not committed); a finding stops the campaign and
# leaves crash-* in build-fuzz/findings/HARNESS: fix it and keep that input in
# fuzz/regressions/HARNESS, which CTest replays (fuzz_replay_HARNESS). Needs clang-14.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
harness=${1:?harness name}
seconds=${2:?seconds}
jobs=${3:-1}
build="$root/build-fuzz"
if [ ! -f "$build/CMakeCache.txt" ]; then
    san="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined"
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 \
        -DCMAKE_CXX_FLAGS="$san" -DCMAKE_C_FLAGS="$san" \
        -DEXASPH_FUZZ=ON -DEXASPH_TESTS=OFF -DEXASPH_BENCH=OFF -DEXASPH_OPENMP=OFF
fi
cmake --build "$build" --target "fuzz_$harness"
corpus="$build/corpus/$harness"
findings="$build/findings/$harness"
mkdir -p "$corpus" "$findings"
dict=()
[ -f "$root/fuzz/$harness.dict" ] && dict=(-dict="$root/fuzz/$harness.dict")
# OpenMPI and HDF5 keep allocations for the life of the process: leak reports off.
export ASAN_OPTIONS=detect_leaks=0:allocator_may_return_null=1
export EXASPH_FUZZ_DIR=${EXASPH_FUZZ_DIR:-/dev/shm}
cd "$findings"
TIMEFORMAT="fuzz.sh: campaign of $harness: %R s wall, %U s user + %S s system CPU"
time "$build/fuzz/fuzz_$harness" "$corpus" "$root/fuzz/corpus/$harness" "${dict[@]}" \
    -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -jobs="$jobs" -workers="$jobs" \
    -print_final_stats=1
