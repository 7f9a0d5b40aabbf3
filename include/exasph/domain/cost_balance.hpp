#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "exasph/domain/global_tree.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// --balance cost: no rank holds more than this times the mean particle count. Memory, not work,
// bounds what a rank can take.
inline constexpr double kCostBalanceMemoryBound = 1.5;

// Contiguous leaf ranges of about equal cost (issue 23): costs[l] is the summed expected work of
// global leaf l's particles (any unit), counts[l] its particles. If the cut by cost would give a
// rank more than `bound` times the mean count, the cut balances a blend (1 - f) cost + f count
// of the two (each normalised to its total) instead, with the smallest f in 1/8, 2/8, ... that
// keeps the bound (f = 1: the count cut). Integer weights (2^40 per total) keep the cut the same
// on every rank and independent of the order of the sums.
inline Assignment assign_leaves_by_cost(const std::vector<std::uint64_t>& counts,
                                        const std::vector<double>& costs, int nranks,
                                        double bound = kCostBalanceMemoryBound) {
    double n_total = 0, c_total = 0;
    for (std::size_t l = 0; l < counts.size(); ++l)
        n_total += double(counts[l]), c_total += costs[l];
    std::vector<std::uint64_t> w(counts.size());
    for (int k = 0; k < 8 && c_total > 0; ++k) {
        const double f = k / 8.0;
        for (std::size_t l = 0; l < counts.size(); ++l)
            w[l] = std::uint64_t(std::llround(
                ((1 - f) * costs[l] / c_total + f * double(counts[l]) / n_total) * 0x1p40));
        try {
            Assignment a = assign_leaves(counts, nranks, w);
            const auto most = *std::max_element(a.count.begin(), a.count.end());
            if (double(most) <= bound * n_total / nranks) return a;
        } catch (const Error&) { // a rank without particles: blend more of the counts in
        }
    }
    return assign_leaves(counts, nranks);
}

} // namespace exasph
