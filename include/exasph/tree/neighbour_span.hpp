#pragma once
#include <cstdint>

#include "exasph/util/annotate.hpp"

namespace exasph {

// One particle's neighbour list: `count` indices, the n-th at index[n * stride]. Stride 1 is a
// contiguous list (the CPU lists); a larger stride reads one particle's column of lists stored
// interleaved (neighbour n of particles i, i + 1, ... side by side, as GPUs read them
// coalesced), so that one kernel serves both layouts.
struct NeighbourSpan {
    const std::uint32_t* index;
    std::uint32_t count;
    std::uint32_t stride = 1;

    EXASPH_HD EXASPH_INLINE std::uint32_t operator[](std::uint32_t n) const {
        return index[n * stride];
    }
};

} // namespace exasph
