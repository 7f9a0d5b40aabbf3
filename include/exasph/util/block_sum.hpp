#pragma once
#include <array>
#include <cstddef>
#include <vector>

namespace exasph {

// Sums K per-particle quantities over [0, n) with a result that does not depend on the number of
// OpenMP threads: partial sums over fixed blocks of kBlock particles, then a serial sum over the
// blocks. Needed because diagnostics are compared between thread counts to 1e-10 and better.
template <std::size_t K, class F>
std::array<double, K> block_sum(std::size_t n, F&& per_particle) {
    constexpr std::size_t kBlock = 2048;
    std::size_t nblocks = (n + kBlock - 1) / kBlock;
    std::vector<std::array<double, K>> partial(nblocks);
#pragma omp parallel for schedule(static)
    for (std::size_t b = 0; b < nblocks; ++b) {
        std::array<double, K> acc{};
        std::size_t end = (b + 1) * kBlock < n ? (b + 1) * kBlock : n;
        for (std::size_t i = b * kBlock; i < end; ++i) {
            std::array<double, K> v = per_particle(i);
            for (std::size_t k = 0; k < K; ++k) acc[k] += v[k];
        }
        partial[b] = acc;
    }
    std::array<double, K> total{};
    for (const auto& p : partial)
        for (std::size_t k = 0; k < K; ++k) total[k] += p[k];
    return total;
}

} // namespace exasph
