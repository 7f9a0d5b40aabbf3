#pragma once
#if !defined(__CUDA_ARCH__)
#include <atomic>
#endif

#include "exasph/util/annotate.hpp"

namespace exasph {

// *a = max(*a, v), safe against other threads doing the same (several particles raising the
// same neighbour's bound: the block time steps' limiter).
EXASPH_HD inline void atomic_max(int* a, int v) {
#if defined(__CUDA_ARCH__)
    atomicMax(a, v);
#else
    std::atomic_ref<int> ref(*a);
    int seen = ref.load(std::memory_order_relaxed);
    while (seen < v && !ref.compare_exchange_weak(seen, v, std::memory_order_relaxed)) {
    }
#endif
}

} // namespace exasph
