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

} // namespace exasph::cuda
