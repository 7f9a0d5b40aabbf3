#pragma once
#include <cstdint>
#include <vector>

#include "exasph/tree/neighbour_search.hpp"

namespace exasph::testref {

// O(N^2) reference: sorted neighbour indices of particle i under the given criterion.
inline std::vector<std::uint32_t> brute_force_neighbours(const SearchView<double>& p,
                                                         const Box<double>& box, std::uint32_t n,
                                                         std::uint32_t i, NeighbourCriterion crit) {
    std::vector<std::uint32_t> out;
    for (std::uint32_t j = 0; j < n; ++j)
        if (j != i && is_neighbour(pair_distance2(p, box, i, j), p.h[i], p.h[j], crit))
            out.push_back(j);
    return out;
}

} // namespace exasph::testref
