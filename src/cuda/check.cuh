#pragma once
#include <string>

#include <cuda_runtime.h>

#include "exasph/util/error.hpp"

namespace exasph::cuda {

// A failed CUDA call ends the run with one line naming what was being done (exasph::Error, exit
// 1), never a CUDA error dump.
inline void check(cudaError_t e, const char* what) {
    if (e != cudaSuccess)
        throw Error(std::string("CUDA error while ") + what + ": " + cudaGetErrorString(e));
}

// The end of a launch: its launch error, then the device synchronised (the launchers' calls
// return with their results visible to the host).
inline void finish(const char* what) {
    check(cudaGetLastError(), what);
    check(cudaDeviceSynchronize(), what);
}

} // namespace exasph::cuda
