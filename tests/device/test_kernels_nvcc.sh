#!/usr/bin/env bash
# Issue 15, acceptance 3: the per-particle kernels of sph/ compile as device code for the H200
# (sm_90) with no warning. Usage: test_kernels_nvcc.sh SOURCE_DIR BUILD_DIR [NVCC]
# Exit 77 (CTest: skipped) where no nvcc is installed.
set -u
src=$1
out=$2
nvcc=${3:-}
[ -n "$nvcc" ] && [ -x "$nvcc" ] || nvcc=$(command -v nvcc || true)
[ -n "$nvcc" ] || { [ -x /usr/local/cuda/bin/nvcc ] && nvcc=/usr/local/cuda/bin/nvcc; }
if [ -z "$nvcc" ]; then
    echo "SKIPPED: nvcc not found (install the CUDA toolkit to check the device kernels)"
    exit 77
fi
mkdir -p "$out"
"$nvcc" --version | tail -1
# --expt-relaxed-constexpr: std::array's constexpr accessors in device code (Box).
exec "$nvcc" -std=c++20 -arch=sm_90 --expt-relaxed-constexpr -Werror all-warnings \
    -I"$src/include" -c "$src/tests/device/kernels_device.cu" -o "$out/kernels_device.o"
