#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "exasph/domain/collectives.hpp"
#include "exasph/domain/control_flags.hpp"

namespace exasph {

// What the sync's one collective gives every rank about the global leaves: particles and
// maximum h per leaf, with --balance cost each leaf's summed cost (else empty).
template <class T>
struct LeafCounts {
    std::vector<std::uint64_t> count;
    std::vector<T> hmax; // 0 for an empty leaf
    std::vector<double> cost;

    // The smallest maximum h of a non-empty leaf (0 when there is none).
    T smallest_hmax() const {
        T m = 0;
        for (T h : hmax) m = h > 0 && (m == 0 || h < m) ? h : m;
        return m;
    }
};

// The collective itself: leaf[i] is particle i's global leaf (of nl), h its smoothing length,
// cost its expected work (or null). The buffer's sections: [0, nl) count and maximum h per leaf,
// then the run-control flags (when given: they travel with the counts, ControlFlags), then with
// cost [.., + nl) the cost per leaf.
template <class T>
LeafCounts<T> reduce_leaf_counts(const T* h, const std::vector<std::uint32_t>& leaf, std::size_t nl,
                                 Collectives& coll, ControlFlags* flags = nullptr,
                                 const float* cost = nullptr) {
    const std::size_t n_flags = flags ? std::size_t(kNumControlFlags) : 0, cost_at = nl + n_flags;
    std::vector<SumMax> stat(cost_at + (cost ? nl : 0));
    if (flags) flags->pack(stat.data() + nl);
    for (std::size_t i = 0; i < leaf.size(); ++i) {
        stat[leaf[i]].sum += 1.0;
        stat[leaf[i]].max = std::max(stat[leaf[i]].max, double(h[i]));
        if (cost) stat[cost_at + leaf[i]].sum += double(cost[i]);
    }
    coll.allreduce_sum_max(stat);
    if (flags) flags->unpack(stat.data() + nl);
    LeafCounts<T> lc;
    lc.cost.resize(cost ? nl : 0);
    for (std::size_t l = 0; l < lc.cost.size(); ++l) lc.cost[l] = stat[cost_at + l].sum;
    lc.count.resize(nl);
    lc.hmax.resize(nl);
    for (std::size_t l = 0; l < nl; ++l) {
        lc.count[l] = std::uint64_t(stat[l].sum);
        lc.hmax[l] = stat[l].sum > 0 ? T(stat[l].max) : T(0);
    }
    return lc;
}

} // namespace exasph
