#pragma once
#include <cstddef>

// The launch grid of exasph's CUDA kernels: one thread per particle (or list slot), kThreads per
// block.
namespace exasph::cuda {

constexpr unsigned kThreads = 128;

inline unsigned blocks_for(std::size_t n) {
    return unsigned((n + kThreads - 1) / kThreads);
}

} // namespace exasph::cuda
