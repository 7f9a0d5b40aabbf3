#!/usr/bin/env bash
# Sets up and builds the exasph program if needed, then runs it. Without arguments: the default
# case (rotating square patch, 27,000 particles, to t = 0.02 s). Any arguments are passed to exasph.
# It builds the program alone (the tests and benchmarks are scripts/test.sh's); the first time, it
# leaves out the CUDA backend unless a GPU is visible (nvidia-smi) or EXASPH_CUDA=ON is set:
# compiling the device code takes minutes and a CPU run does not use it.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cuda=()
[ -n "${EXASPH_CUDA:-}" ] && cuda=(-DEXASPH_CUDA="$EXASPH_CUDA")
if [ -z "${EXASPH_CUDA:-}" ] && ! { command -v nvidia-smi && nvidia-smi -L; } >/dev/null 2>&1; then
    cuda=(-DEXASPH_CUDA=OFF) # with a GPU: CMake's default, on where nvcc is found
fi
EXASPH_TARGETS=exasph EXASPH_FIRST_CONFIGURE_ARGS="${cuda[*]}" \
    bash "$root/scripts/setup.sh" >&2
exec "${EXASPH_BUILD_DIR:-$root/build}/exasph" "$@"
