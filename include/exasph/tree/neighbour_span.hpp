#pragma once
#include <cstdint>

#include "exasph/util/annotate.hpp"

namespace exasph {

// One particle's neighbour list: `count` indices starting at `index`.
struct NeighbourSpan {
    const std::uint32_t* index;
    std::uint32_t count;
};

} // namespace exasph
