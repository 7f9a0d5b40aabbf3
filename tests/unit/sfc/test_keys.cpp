// Acceptance 2 (issue 2): SFC keys round-trip and Hilbert neighbours are face-adjacent.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "exasph/domain/sfc_order.hpp"
#include "exasph/sfc/keys.hpp"

using namespace exasph;

namespace {
constexpr std::uint64_t kMaxKey = (std::uint64_t(1) << 63) - 1;
}

TEST(Morton, RoundTrip) {
    std::mt19937_64 rng(1);
    std::uniform_int_distribution<std::uint32_t> u(0, kKeyAxisMax);
    for (int i = 0; i < 100000; ++i) {
        std::uint32_t x = u(rng), y = u(rng), z = u(rng);
        auto d = morton_decode(morton_encode(x, y, z));
        ASSERT_EQ(d[0], x);
        ASSERT_EQ(d[1], y);
        ASSERT_EQ(d[2], z);
    }
    EXPECT_EQ(morton_encode(kKeyAxisMax, kKeyAxisMax, kKeyAxisMax), kMaxKey);
}

TEST(Hilbert, RoundTrip) {
    std::mt19937_64 rng(2);
    std::uniform_int_distribution<std::uint32_t> u(0, kKeyAxisMax);
    for (int i = 0; i < 100000; ++i) {
        std::uint32_t x = u(rng), y = u(rng), z = u(rng);
        std::uint64_t key = hilbert_encode(x, y, z);
        ASSERT_LE(key, kMaxKey);
        auto d = hilbert_decode(key);
        ASSERT_EQ(d[0], x);
        ASSERT_EQ(d[1], y);
        ASSERT_EQ(d[2], z);
    }
}

namespace {
// True when the cells differ by exactly one step along exactly one axis.
bool face_adjacent(const std::array<std::uint32_t, 3>& a, const std::array<std::uint32_t, 3>& b) {
    int steps = 0;
    for (int d = 0; d < 3; ++d) {
        long diff = std::labs(long(a[d]) - long(b[d]));
        if (diff > 1) return false;
        steps += int(diff);
    }
    return steps == 1;
}
} // namespace

TEST(Hilbert, ConsecutiveKeysAreFaceAdjacent) {
    // Every key at the start of the curve, and random keys across the whole range.
    for (std::uint64_t k = 0; k < 100000; ++k)
        ASSERT_TRUE(face_adjacent(hilbert_decode(k), hilbert_decode(k + 1))) << "key " << k;
    std::mt19937_64 rng(3);
    std::uniform_int_distribution<std::uint64_t> u(0, kMaxKey - 1);
    for (int i = 0; i < 200000; ++i) {
        std::uint64_t k = u(rng);
        ASSERT_TRUE(face_adjacent(hilbert_decode(k), hilbert_decode(k + 1))) << "key " << k;
    }
}

TEST(Hilbert, KeyPrefixNamesOneCube) {
    // The octree relies on this: all keys sharing their top 3l bits lie in one cube of level l.
    std::mt19937_64 rng(4);
    std::uniform_int_distribution<std::uint64_t> u(0, kMaxKey);
    for (int level = 1; level <= 6; ++level) {
        int shift = 3 * (kKeyBitsPerAxis - level);
        for (int t = 0; t < 200; ++t) {
            std::uint64_t base = (u(rng) >> shift) << shift;
            auto c0 = hilbert_decode(base);
            for (int s = 0; s < 50; ++s) {
                std::uint64_t k = base | (u(rng) & ((std::uint64_t(1) << shift) - 1));
                auto c = hilbert_decode(k);
                for (int d = 0; d < 3; ++d)
                    ASSERT_EQ(c[d] >> (kKeyBitsPerAxis - level),
                              c0[d] >> (kKeyBitsPerAxis - level));
            }
        }
    }
}

TEST(Keys, CoordinatesClampToTheBox) {
    Box<double> box;
    box.lo = {-1, -1, -1};
    box.hi = {1, 1, 1};
    EXPECT_EQ(key_coordinate(-5.0, box, 0), 0u);
    EXPECT_EQ(key_coordinate(5.0, box, 1), kKeyAxisMax);
    EXPECT_EQ(key_coordinate(0.0, box, 2), 1u << 20);
}

// compute_sfc_keys (blocks of points, vectorised) gives sfc_key's keys for every point, including
// block remainders, points outside the box and NaN.
TEST(Keys, BatchKeysEqualSingleKeys) {
    Box<double> box;
    box.lo = {-1, -2, 0};
    box.hi = {1, 2, 3};
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.2, 3.2);
    const std::size_t n = 3 * kHilbertBlock + 17;
    std::vector<double> x(n), y(n), z(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = u(rng), y[i] = u(rng), z[i] = u(rng);
    x[5] = std::nan("");
    z[n - 1] = -std::numeric_limits<double>::infinity();
    for (CurveKind kind : {CurveKind::hilbert, CurveKind::morton}) {
        std::vector<std::uint64_t> keys(n);
        compute_sfc_keys(x.data(), y.data(), z.data(), n, box, kind, keys.data());
        for (std::size_t i = 0; i < n; ++i)
            ASSERT_EQ(keys[i], sfc_key(x[i], y[i], z[i], box, kind)) << "point " << i;
    }
}
