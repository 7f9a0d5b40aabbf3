#!/usr/bin/env bash
# The device check of the CUDA backend (issue 18), one script for a machine with a GPU and no
# MPI or HDF5 (the device tool's image): builds the single-rank CUDA configuration (only the
# targets it runs), runs compute-sanitizer memcheck and racecheck on Sedov -n 20 for 2 steps,
# compares GPU against CPU in one process (tests/device/test_cuda_path.cpp: Sedov -n 50, 5
# steps, the square patch, the ve scheme; per-particle fields within 1e-10 in double), then
# times Sedov (standard scheme, lattice) at -n 100, 200 and SIDE_MAX and prints one table:
# particle-steps/s, seconds per phase, device memory per particle (peak of nvidia-smi's
# memory.used over the run, divided by the particles).
# Usage: bench/gpu/check.sh [SIDE_MAX (216: 1.0e7 particles)] [STEPS (10; the figures are over
# all steps, the first with its kernel loading included)]
# EXASPH_CHECK_BACKEND=cpu runs the same steps on the CPU and EXASPH_CHECK_SIZES="20 30" other
# sizes (to try the script without a GPU).
# Budget: about 5 minutes on an H200 (most of it the build).
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
side_max=${1:-216}
steps=${2:-10}
build=${EXASPH_GPU_BUILD:-$root/build-gpu}
backend=${EXASPH_CHECK_BACKEND:-cuda}
work=$(mktemp -d)
status=0
fail() { echo "FAIL: $*"; status=1; }

export PATH=/usr/local/cuda/bin:$PATH
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader || fail "nvidia-smi"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DEXASPH_MPI=OFF \
    -DEXASPH_HDF5=OFF -DEXASPH_BENCH=OFF -DEXASPH_CUDA=ON >"$work/cmake.log" 2>&1 ||
    { tail -20 "$work/cmake.log"; exit 1; }
cmake --build "$build" -j "$(nproc)" --target exasph test_cuda_path >"$work/build.log" 2>&1 ||
    { grep -E "error|warning" "$work/build.log" | head -30; exit 1; }
echo "ptxas (registers, spills) of the kernels:"
grep -E "Used [0-9]+ registers|spill" "$work/build.log" | sed 's/^ptxas info *: //' | sort | uniq -c |
    sort -rn | head -8
exe=$build/exasph

echo "== compute-sanitizer on Sedov -n 20, 2 steps"
for tool in memcheck racecheck; do
    compute-sanitizer --tool "$tool" --error-exitcode 9 "$exe" --backend "$backend" --init sedov \
        --lattice -n 20 -s 2 --out "$work/san" >"$work/$tool.log" 2>&1
    rc=$?
    summary=$(grep -E "ERROR SUMMARY|RACECHECK SUMMARY" "$work/$tool.log" | tail -1)
    echo "$tool: exit $rc; $summary"
    [ $rc -eq 0 ] || { tail -30 "$work/$tool.log"; fail "$tool"; }
done

echo "== GPU against CPU"
"$build/tests/test_cuda_path" >"$work/compare.log" 2>&1 || fail "test_cuda_path"
grep -E "device:|GPU vs CPU|OK \]|FAILED|SKIPPED|Failure|Expected|Which is" "$work/compare.log"
if [ "$backend" = cuda ] && grep -q "SKIPPED" "$work/compare.log"; then
    fail "test_cuda_path saw no device"
fi

echo "== timing (Sedov, std scheme, lattice, $steps steps, the run summary's figures)"
peak_memory() { # runs "$@" while sampling the device memory; prints the peak MiB
    local peak=0 used
    "$@" >"$work/run.log" 2>&1 &
    local pid=$!
    while kill -0 $pid 2>/dev/null; do
        used=$(nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits | head -1)
        [ "${used:-0}" -gt "$peak" ] && peak=$used
        sleep 0.2
    done
    wait $pid
    echo "$? $peak"
}
base=$(nvidia-smi --query-gpu=memory.used --format=csv,noheader,nounits | head -1)
printf "%-6s %10s %12s %10s %8s  %s\n" side particles "p-steps/s" "s/step" "B/part" \
    "seconds per phase"
for n in ${EXASPH_CHECK_SIZES:-100 200 $side_max}; do
    read -r rc peak < <(peak_memory "$exe" --backend "$backend" --scheme std --init sedov \
        --lattice -n "$n" -s "$steps" --out "$work/t$n")
    [ "$rc" -eq 0 ] || { tail -5 "$work/run.log"; fail "Sedov -n $n exited $rc"; }
    np=$((n * n * n))
    rate=$(grep -oE "particle-steps/s [0-9.e+]+" "$work/run.log" | awk '{print $2}')
    phases=$(grep "seconds per step by phase" "$work/run.log" | sed 's/.*(rank 0): //')
    sps=$(awk -v r="$rate" -v n="$np" 'BEGIN { if (r > 0) printf "%.3f", n / r }')
    bpp=$(awk -v p="$peak" -v b="$base" -v n="$np" 'BEGIN { printf "%.0f", (p - b) * 1048576 / n }')
    printf "%-6s %10s %12s %10s %8s  %s\n" "$n" "$np" "$rate" "$sps" "$bpp" "$phases"
    grep -q "backend: $backend" "$work/run.log" || fail "-n $n did not run on $backend"
done
rm -rf "$work"
[ $status -eq 0 ] && echo "check.sh: all passed" || echo "check.sh: FAILED"
exit $status
