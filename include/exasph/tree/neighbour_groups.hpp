#pragma once
#include <cstdint>
#include <vector>

#include "exasph/tree/neighbour_lists.hpp"

namespace exasph {

// Some groups of a set of neighbour lists. The passes take it where they take the lists, and
// OmpLauncher then runs only these groups: how a pass is split around a halo exchange in flight.
template <class T>
struct NeighbourGroups {
    const NeighbourLists<T>* lists = nullptr;
    std::vector<std::uint32_t> groups;

    std::vector<std::uint32_t> list(std::uint32_t i) const { return lists->list(i); } // messages
    // Part c of `parts` nearly equal parts of these groups.
    NeighbourGroups part(std::size_t c, std::size_t parts) const {
        const std::size_t n = groups.size();
        return {lists,
                {groups.begin() + std::ptrdiff_t(n * c / parts),
                 groups.begin() + std::ptrdiff_t(n * (c + 1) / parts)}};
    }
};

// The parts of the lists for overlapping the halo exchanges with the work (issue 23): the groups
// with a particle that other ranks receive as a halo (`sent`, per owned particle) and the rest;
// the groups whose neighbours include halos and those whose neighbours are all owned.
template <class T>
struct HaloOverlapGroups {
    NeighbourGroups<T> sending, not_sending, reading_halos, owned_only;
};

template <class T>
HaloOverlapGroups<T> split_for_halo_overlap(const NeighbourLists<T>& nl, const std::uint8_t* sent) {
    HaloOverlapGroups<T> parts{{&nl, {}}, {&nl, {}}, {&nl, {}}, {&nl, {}}};
    for (std::uint32_t g = 0; g < nl.num_groups(); ++g) {
        bool sends = false;
        for (std::uint32_t s = nl.group_begin(g); s < nl.group_end(g) && !sends; ++s)
            sends = sent[nl.member(s)] != 0;
        (sends ? parts.sending : parts.not_sending).groups.push_back(g);
        (nl.group_reads_halos(g) ? parts.reading_halos : parts.owned_only).groups.push_back(g);
    }
    return parts;
}

} // namespace exasph
