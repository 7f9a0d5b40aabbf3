#!/usr/bin/env bash
# The device check of the CUDA backend (issue 18), one script for a machine with a GPU and no
# MPI or HDF5 (the device tool's image). In order of value, so that a run cut short still says
# the most: compares GPU against CPU in one process (tests/device/test_cuda_path.cpp: Sedov
# -n 50, 5 steps, the square patch, the ve scheme; per-particle fields within 1e-10 in double),
# times Sedov (standard scheme, lattice) at -n 100, 200 and SIDE_MAX and prints one table:
# particle-steps/s, seconds per phase, device memory per particle (peak of nvidia-smi's
# memory.used over the run, divided by the particles), times the same -n 100 run on the
# machine's CPU cores for the ratio, then runs compute-sanitizer memcheck and racecheck on Sedov
# -n 20 for 2 steps.
# Usage: bench/gpu/check.sh [SIDE_MAX (216: 1.0e7 particles)] [STEPS (10; the figures are over
# all steps, the first with its kernel loading included)]
# EXASPH_GPU_BUILD: the build folder (build-gpu). With EXASPH_CHECK_PREBUILT=1 the folder's
# exasph and tests/test_cuda_path are used as they are (built elsewhere and carried: configure
# with -DEXASPH_NATIVE=OFF and a -march the device's CPU has) and EXASPH_CHECK_LIBS names a
# folder of shared libraries they need (libgomp, libcudart); otherwise the single-rank CUDA
# configuration is built here (needs CLI11 and GoogleTest; EXASPH_GPU_CMAKE_ARGS, e.g.
# -DCLI11_INCLUDE_DIR=... -DGTEST_ROOT=..., is passed to cmake).
# EXASPH_CHECK_BACKEND=cpu runs the same steps on the CPU and EXASPH_CHECK_SIZES="20 30" other
# sizes (to try the script without a GPU). Logs go to $OUT when it is set.
# Budget: about 5 minutes on an H200 with a carried build.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
side_max=${1:-216}
steps=${2:-10}
build=${EXASPH_GPU_BUILD:-$root/build-gpu}
backend=${EXASPH_CHECK_BACKEND:-cuda}
work=$(mktemp -d)
logs=${OUT:-$work}
status=0
fail() { echo "FAIL: $*"; status=1; }

export PATH=/usr/local/cuda/bin:$PATH
[ -n "${EXASPH_CHECK_LIBS:-}" ] && export LD_LIBRARY_PATH=$EXASPH_CHECK_LIBS:${LD_LIBRARY_PATH:-}
nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader || fail "nvidia-smi"
echo "host: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')"
if [ "${EXASPH_CHECK_PREBUILT:-0}" != 1 ]; then
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DEXASPH_MPI=OFF \
        -DEXASPH_HDF5=OFF -DEXASPH_BENCH=OFF -DEXASPH_CUDA=ON ${EXASPH_GPU_CMAKE_ARGS:-} \
        >"$logs/cmake.log" 2>&1 ||
        { tail -20 "$logs/cmake.log"; exit 1; }
    cmake --build "$build" -j "$(nproc)" --target exasph test_cuda_path >"$logs/build.log" 2>&1 ||
        { grep -E "error|warning" "$logs/build.log" | head -30; exit 1; }
fi
exe=$build/exasph
"$exe" --version || { fail "$exe does not start"; exit 1; }

echo "== GPU against CPU"
timeout 300 "$build/tests/test_cuda_path" >"$logs/compare.log" 2>&1 || fail "test_cuda_path"
grep -E "device:|GPU vs CPU|OK \]|FAILED|SKIPPED|Failure|Expected|Which is|rror" \
    "$logs/compare.log" | head -40
if [ "$backend" = cuda ] && grep -q "SKIPPED" "$logs/compare.log"; then
    fail "test_cuda_path saw no device"
fi

echo "== timing (Sedov, std scheme, lattice, $steps steps, the run summary's figures)"
peak_memory() { # runs "$@" while sampling the device memory; prints the exit status, peak MiB
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
printf "%-10s %10s %12s %10s %8s  %s\n" run particles "p-steps/s" "s/step" "B/part" \
    "seconds per phase"
time_run() { # time_run LABEL BACKEND SIDE
    local label=$1 be=$2 n=$3 rc peak
    read -r rc peak < <(peak_memory timeout 240 "$exe" --backend "$be" --scheme std --init sedov \
        --lattice -n "$n" -s "$steps" --out "$work/t$n$be")
    cat "$work/run.log" >>"$logs/timing.log"
    [ "$rc" -eq 0 ] || { tail -5 "$work/run.log"; fail "Sedov -n $n ($be) exited $rc"; return; }
    local np=$((n * n * n)) rate phases sps bpp
    rate=$(grep -oE "particle-steps/s [0-9.e+]+" "$work/run.log" | awk '{print $2}')
    phases=$(grep "seconds per step by phase" "$work/run.log" | sed 's/.*(rank 0): //')
    sps=$(awk -v r="$rate" -v n="$np" 'BEGIN { if (r > 0) printf "%.3f", n / r }')
    bpp=$(awk -v p="$peak" -v b="$base" -v n="$np" 'BEGIN { printf "%.0f", (p - b) * 1048576 / n }')
    [ "$be" = cuda ] || bpp="-"
    printf "%-10s %10s %12s %10s %8s  %s\n" "$label" "$np" "$rate" "$sps" "$bpp" "$phases"
    grep -q "backend: $be" "$work/run.log" || fail "-n $n did not run on $be"
}
for n in ${EXASPH_CHECK_SIZES:-100 200 $side_max}; do time_run "$backend -n $n" "$backend" "$n"; done
n_cpu=$(echo ${EXASPH_CHECK_SIZES:-100} | awk '{print $1}')
time_run "cpu -n $n_cpu" cpu "$n_cpu"

echo "== compute-sanitizer on Sedov -n 20, 2 steps"
for tool in memcheck racecheck; do
    timeout 150 compute-sanitizer --tool "$tool" --error-exitcode 9 "$exe" --backend "$backend" \
        --init sedov --lattice -n 20 -s 2 --out "$work/san" >"$logs/$tool.log" 2>&1
    rc=$?
    summary=$(grep -E "ERROR SUMMARY|RACECHECK SUMMARY" "$logs/$tool.log" | tail -1)
    echo "$tool: exit $rc; $summary"
    [ $rc -eq 0 ] || { tail -15 "$logs/$tool.log"; fail "$tool"; }
done
rm -rf "$work"
[ $status -eq 0 ] && echo "check.sh: all passed" || echo "check.sh: FAILED"
exit $status
