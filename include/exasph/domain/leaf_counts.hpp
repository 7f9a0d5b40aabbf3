#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "exasph/domain/collectives.hpp"

namespace exasph {

// What the sync's one collective gives every rank about the global leaves: particles and
// maximum h per leaf, with --balance cost each leaf's summed cost (else empty), and whether any
// rank raised its vote.
template <class T>
struct LeafCounts {
    std::vector<std::uint64_t> count;
    std::vector<T> hmax; // 0 for an empty leaf
    std::vector<double> cost;
    bool any_vote = false;

    // The smallest maximum h of a non-empty leaf (0 when there is none).
    T smallest_hmax() const {
        T m = 0;
        for (T h : hmax) m = h > 0 && (m == 0 || h < m) ? h : m;
        return m;
    }
};

// The collective itself: leaf[i] is particle i's global leaf (of nl), h its smoothing length,
// cost its expected work (or null).
template <class T>
LeafCounts<T> reduce_leaf_counts(const T* h, const std::vector<std::uint32_t>& leaf, std::size_t nl,
                                 Collectives& coll, bool local_vote = false,
                                 const float* cost = nullptr) {
    std::vector<SumMax> stat(cost ? 2 * nl + 1 : nl + 1);
    stat[nl].max = local_vote ? 1.0 : 0.0;
    for (std::size_t i = 0; i < leaf.size(); ++i) {
        stat[leaf[i]].sum += 1.0;
        stat[leaf[i]].max = std::max(stat[leaf[i]].max, double(h[i]));
        if (cost) stat[nl + 1 + leaf[i]].sum += double(cost[i]);
    }
    coll.allreduce_sum_max(stat);
    LeafCounts<T> lc;
    lc.any_vote = stat[nl].max > 0;
    lc.cost.resize(cost ? nl : 0);
    for (std::size_t l = 0; l < lc.cost.size(); ++l) lc.cost[l] = stat[nl + 1 + l].sum;
    lc.count.resize(nl);
    lc.hmax.resize(nl);
    for (std::size_t l = 0; l < nl; ++l) {
        lc.count[l] = std::uint64_t(stat[l].sum);
        lc.hmax[l] = stat[l].sum > 0 ? T(stat[l].max) : T(0);
    }
    return lc;
}

} // namespace exasph
