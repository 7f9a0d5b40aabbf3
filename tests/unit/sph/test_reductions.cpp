// Issue 59: the launchers reduce what a kernel returns with the kernel's own typed reduction
// (sph/reduction.hpp), the same on every launcher and thread count: no value is encoded to fit
// a minimum of doubles.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "exasph/sph/launch.hpp"

using namespace exasph;

namespace {
// v[i] under reduction R.
template <class V, class R>
struct Values {
    const V* v;
    using Reduction = R;
    V operator()(std::uint32_t i) const { return v[i]; }
};

// The particles whose flag is set.
struct Flagged {
    const std::uint8_t* flag;
    using Reduction = FirstIndexWhere;
    FoundIndex operator()(std::uint32_t i) const {
        return flag[i] ? FoundIndex::at(i) : FoundIndex::none();
    }
};

std::vector<double> values(std::size_t n) {
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = double((i * 7919) % 1009) - 500.25;
    return v;
}

template <class L>
void expect_typed_reductions() {
    const auto v = values(10007);
    EXPECT_EQ(L::reduce(v.size(), Values<double, MinOf<double>>{v.data()}), -500.25);
    EXPECT_EQ(L::reduce(v.size(), Values<double, MaxOf<double>>{v.data()}), 1008 - 500.25);
    EXPECT_EQ(L::reduce(0, Values<double, MinOf<double>>{v.data()}), MinOf<double>::identity());
    const std::vector<std::int64_t> ticks{40, 12, 96, 12, 7, 300};
    EXPECT_EQ(L::reduce(ticks.size(), Values<std::int64_t, MinOf<std::int64_t>>{ticks.data()}), 7);
    std::vector<std::uint8_t> flag(v.size(), 0);
    EXPECT_FALSE(L::reduce(flag.size(), Flagged{flag.data()}).found());
    flag[9001] = flag[4242] = flag[7777] = 1; // several found: the first is named
    EXPECT_EQ(L::reduce(flag.size(), Flagged{flag.data()}).index, 4242u);
    const std::vector<std::uint32_t> some{9001, 7777, 3};
    EXPECT_EQ(L::reduce_of(some.data(), some.size(), Flagged{flag.data()}).index, 7777u);
    // A sum combines the threads' parts in thread order: the same bits every time (here exact).
    const double sum = L::reduce(v.size(), Values<double, SumOf<double>>{v.data()});
    double serial = 0; // every partial sum is a multiple of 1/4 far below 2^53: exact
    for (double x : v) serial += x;
    EXPECT_EQ(sum, serial);
    for (int r = 0; r < 5; ++r)
        EXPECT_EQ(L::reduce(v.size(), Values<double, SumOf<double>>{v.data()}), sum);
}
} // namespace

TEST(Reductions, TypedOnTheCpuLauncher) {
    expect_typed_reductions<OmpLauncher>();
}

TEST(Reductions, TypedOnTheGpuPathsHostLauncher) {
    expect_typed_reductions<GpuHostLauncher>();
}

TEST(Reductions, SameOnOneThread) {
#ifdef _OPENMP
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    expect_typed_reductions<OmpLauncher>();
    omp_set_num_threads(threads);
#else
    expect_typed_reductions<OmpLauncher>();
#endif
}

namespace {
// The tree of sph/reduction.hpp written out: each run of a level folded neighbours first (as
// the CUDA block does it), levels until one value is left.
double tree_sum_reference(std::vector<double> level) {
    if (level.empty()) return 0.0;
    while (level.size() > 1) {
        std::vector<double> next;
        for (std::size_t first = 0; first < level.size(); first += kTreeFan) {
            std::vector<double> run(kTreeFan, 0.0);
            for (std::size_t t = 0; t < kTreeFan && first + t < level.size(); ++t)
                run[t] = level[first + t];
            for (std::size_t s = 1; s < kTreeFan; s *= 2)
                for (std::size_t t = 0; t < kTreeFan; t += 2 * s) run[t] += run[t + s];
            next.push_back(run[0]);
        }
        level = next;
    }
    return level[0];
}

// Values whose sum rounds differently in every order: magnitudes over 12 decades.
std::vector<double> rounding_values(std::size_t n) {
    std::vector<double> v(n);
    std::uint64_t s = 88172645463325252ull;
    for (double& x : v) {
        s ^= s << 13, s ^= s >> 7, s ^= s << 17;
        const double unit = double(s >> 11) * 0x1.0p-53;
        x = (unit - 0.3) * std::pow(10.0, double(s % 13) - 6);
    }
    return v;
}
} // namespace

// Issue 60: reduce_tree's sum has the tree's bits on every launcher and thread count (what the
// diagnostics need to equal the CPU's on the device), and rounds like any order of the sum.
TEST(Reductions, TreeSumHasTheSameBitsOnEveryLauncherAndThreadCount) {
    for (std::size_t n : {std::size_t(0), std::size_t(1), kTreeFan - 1, kTreeFan, kTreeFan + 1,
                          kTreeFan * kTreeFan + 5, std::size_t(100003)}) {
        const auto v = rounding_values(n);
        const Values<double, SumOf<double>> k{v.data()};
        const double expected = tree_sum_reference(v);
        EXPECT_EQ(OmpLauncher::reduce_tree(n, k), expected) << n;
        EXPECT_EQ(GpuHostLauncher::reduce_tree(n, k), expected) << n;
#ifdef _OPENMP
        const int threads = omp_get_max_threads();
        omp_set_num_threads(1);
        EXPECT_EQ(OmpLauncher::reduce_tree(n, k), expected) << n;
        omp_set_num_threads(threads);
#endif
        long double exact = 0;
        double scale = 0;
        for (double x : v) exact += x, scale += std::abs(x);
        EXPECT_LE(std::abs(double(exact) - expected), 1e-14 * scale) << n;
    }
    const auto v = values(10007); // a minimum along the tree is the minimum
    EXPECT_EQ(OmpLauncher::reduce_tree(v.size(), Values<double, MinOf<double>>{v.data()}), -500.25);
}
