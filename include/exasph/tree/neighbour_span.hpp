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

// A list whose stride is 1 at compile time: what the CPU lists hand the kernels (which are
// templates on the span). With NeighbourSpan's run-time stride GCC versions each pair loop on
// stride == 1, and that version of the density loop was left scalar (2x slower, measured); here
// the indices are one contiguous vector load.
struct ContiguousSpan {
    const std::uint32_t* index;
    std::uint32_t count;
    // Whether some pair may need the periodic minimum image; false (the search found every
    // candidate within half a period of the group): no pair does, and loops may skip it.
    bool wraps = true;

    EXASPH_HD EXASPH_INLINE std::uint32_t operator[](std::uint32_t n) const { return index[n]; }
};

} // namespace exasph
