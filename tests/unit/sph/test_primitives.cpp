// Issue 59: the launchers' data-parallel primitives (sph/primitives.hpp), on which the
// device-resident domain is to be written: exclusive scan (in place too), a stable sort by key
// with a permutation, gather and scatter, each against a serial std:: answer, on the CPU
// launcher and the GPU path's host launcher, at one and at every thread.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/sph/launch.hpp"

using namespace exasph;

namespace {

// A scrambled but reproducible sequence: (i * 2654435761) mod 2^32, reduced to `range`.
std::vector<std::uint64_t> scrambled(std::size_t n, std::uint64_t range) {
    std::vector<std::uint64_t> v(n);
    for (std::size_t i = 0; i < n; ++i)
        v[i] = (std::uint64_t(i) * 2654435761u % 4294967296u) % range;
    return v;
}

template <class L>
void expect_scan(std::size_t n) {
    const auto raw = scrambled(n, 1000);
    const std::vector<std::uint32_t> in(raw.begin(), raw.end());
    std::vector<std::uint32_t> want(n);
    std::exclusive_scan(in.begin(), in.end(), want.begin(), std::uint32_t(0));
    const std::uint32_t total = std::accumulate(in.begin(), in.end(), std::uint32_t(0));
    std::vector<std::uint32_t> out(n, 7);
    EXPECT_EQ(L::exclusive_scan(in.data(), out.data(), n), total) << n;
    EXPECT_EQ(out, want) << n;
    std::vector<std::uint32_t> same = in; // in place
    EXPECT_EQ(L::exclusive_scan(same.data(), same.data(), n), total) << n;
    EXPECT_EQ(same, want) << n;
}

template <class L>
void expect_stable_sort(std::size_t n) {
    std::vector<std::uint64_t> keys = scrambled(n, 97); // many equal keys: stability shows
    std::vector<ParticleIndex> order(n);
    std::iota(order.begin(), order.end(), ParticleIndex(0));
    std::vector<ParticleIndex> want = order;
    std::stable_sort(want.begin(), want.end(),
                     [&](ParticleIndex a, ParticleIndex b) { return keys[a] < keys[b]; });
    const std::vector<std::uint64_t> unsorted = keys;
    L::sort_by_key(keys.data(), order.data(), n);
    EXPECT_EQ(order, want) << n;
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(keys[i], unsorted[order[i]]) << i;
}

template <class L>
void expect_gather_and_scatter(std::size_t n) {
    std::vector<double> field(n);
    for (std::size_t i = 0; i < n; ++i) field[i] = 0.5 * double(i) - 3.0;
    std::vector<ParticleIndex> order(n);
    std::iota(order.begin(), order.end(), ParticleIndex(0));
    std::reverse(order.begin(), order.end());
    std::rotate(order.begin(), order.begin() + n / 3, order.end());
    std::vector<double> gathered(n), back(n);
    L::gather(order.data(), field.data(), gathered.data(), n);
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(gathered[i], field[order[i]]) << i;
    L::scatter(order.data(), gathered.data(), back.data(), n); // the inverse permutation
    EXPECT_EQ(back, field);
}

template <class L>
void expect_primitives() {
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(5), std::size_t(100003)}) {
        expect_scan<L>(n);
        expect_stable_sort<L>(n);
        if (n > 0) expect_gather_and_scatter<L>(n);
    }
}

} // namespace

TEST(Primitives, OnTheCpuLauncher) {
    expect_primitives<OmpLauncher>();
}

TEST(Primitives, OnTheGpuPathsHostLauncher) {
    expect_primitives<GpuHostLauncher>();
}

TEST(Primitives, SameOnOneThread) {
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    expect_primitives<OmpLauncher>();
    omp_set_num_threads(threads);
#else
    expect_primitives<OmpLauncher>();
#endif
}

TEST(Primitives, ScanOfSixtyFourBitCountsKeepsTheCarry) {
    const std::size_t n = 4097;
    std::vector<std::uint64_t> counts(n, std::uint64_t(1) << 40);
    std::vector<std::uint64_t> offsets(n);
    EXPECT_EQ(OmpLauncher::exclusive_scan(counts.data(), offsets.data(), n), std::uint64_t(n)
                                                                                 << 40);
    EXPECT_EQ(offsets[n - 1], std::uint64_t(n - 1) << 40);
}
