// The compact neighbour lists' building blocks (tree/neighbour_codec.hpp) and the lists' own
// contract: every particle's list, expanded group by group, is the list of the search in the
// search's order, and the storage stays far below a fixed-stride layout.
#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "exasph/domain/sfc_order.hpp"
#include "exasph/tree/neighbour_lists.hpp"
#include "random_particles.hpp"

using namespace exasph;

TEST(NeighbourCodec, VarintRoundTrip) {
    const std::vector<std::uint32_t> values{0,     1,     127,      128,        300,
                                            16383, 16384, 1u << 28, 0xFFFFFFFFu};
    std::vector<std::uint8_t> buf;
    for (auto v : values) codec::put_varint(buf, v);
    EXPECT_EQ(buf.size(), 1u + 1 + 1 + 2 + 2 + 2 + 3 + 5 + 5);
    const std::uint8_t* p = buf.data();
    for (auto v : values) EXPECT_EQ(codec::get_varint(p), v);
    EXPECT_EQ(p, buf.data() + buf.size());
}

TEST(NeighbourCodec, BitsAndMaskExpansion) {
    std::mt19937 rng(5);
    std::vector<std::uint8_t> rec(64 + codec::kReadPad, 0);
    std::vector<int> bit(64 * 8, 0);
    for (int k = 0; k < 300; ++k) {
        auto pos = rng() % (64 * 8);
        codec::set_bit(rec.data(), pos);
        bit[pos] = 1;
    }
    for (std::uint64_t pos = 0; pos + 32 <= 64 * 8; pos += 13)
        for (unsigned n : {1u, 7u, 31u, 32u}) {
            std::uint32_t want = 0;
            for (unsigned k = 0; k < n; ++k) want |= std::uint32_t(bit[pos + k]) << k;
            ASSERT_EQ(codec::load_bits(rec.data(), pos, n), want) << pos << " " << n;
        }
    std::vector<std::uint32_t> out(64);
    for (std::uint32_t mask : {0u, 1u, 0x80000000u, 0xFFFFFFFFu, 0x0001FFFEu, 0xA5A5A5A5u}) {
        std::uint32_t c = codec::expand_mask(mask, 1000, out.data());
        std::vector<std::uint32_t> want;
        for (std::uint32_t k = 0; k < 32; ++k)
            if (mask >> k & 1u) want.push_back(1000 + k);
        ASSERT_EQ(c, want.size());
        EXPECT_TRUE(std::equal(want.begin(), want.end(), out.begin())) << std::hex << mask;
    }
    // The decoder's 16-bit unit: every mask, appended after earlier output (which it must keep).
    for (std::uint32_t mask = 0; mask < (1u << 16); ++mask) {
        out.assign(64, 7u);
        const std::uint32_t c = codec::expand_mask16(mask, 500, out.data() + 3);
        std::vector<std::uint32_t> want(3, 7u);
        for (std::uint32_t k = 0; k < 16; ++k)
            if (mask >> k & 1u) want.push_back(500 + k);
        ASSERT_EQ(c + 3, want.size()) << std::hex << mask;
        ASSERT_TRUE(std::equal(want.begin(), want.end(), out.begin())) << std::hex << mask;
    }
    // The decoder's 32-bit unit (both halves expanded whatever they hold): random masks, with
    // an empty, a sparse or a full upper half, appended after earlier output.
    for (int k = 0; k < 200000; ++k) {
        std::uint32_t mask = rng();
        if (k % 3 == 0) mask &= 0xFFFFu;
        if (k % 3 == 1) mask &= rng() | 0xFFFFu;
        if (k % 5 == 0) mask |= 0xFFFF0000u;
        out.assign(64 + 3, 7u);
        const std::uint32_t c = codec::expand_mask32(mask, 900, out.data() + 3);
        std::vector<std::uint32_t> want(3, 7u);
        for (std::uint32_t b = 0; b < 32; ++b)
            if (mask >> b & 1u) want.push_back(900 + b);
        ASSERT_EQ(c + 3, want.size()) << std::hex << mask;
        ASSERT_TRUE(std::equal(want.begin(), want.end(), out.begin())) << std::hex << mask;
    }
}

// BitWriter (the search's record writer, which stores its low word on every put): fields of 1
// to 32 bits read back with load_bits, nothing written past the record's padding.
TEST(NeighbourCodec, BitWriterRoundTripWithinThePadding) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 2000; ++trial) {
        std::vector<std::pair<std::uint32_t, unsigned>> fields(1 + rng() % 40);
        std::uint64_t total = 0;
        for (auto& [v, n] : fields) {
            n = 1 + rng() % 32;
            v = std::uint32_t(rng()) & std::uint32_t((std::uint64_t(1) << n) - 1);
            total += n;
        }
        const std::size_t bytes = (total + 7) / 8;
        std::vector<std::uint8_t> rec(bytes + codec::kReadPad + 16, 0xCD);
        codec::BitWriter out(rec.data());
        for (const auto& [v, n] : fields) out.put(v, n);
        out.align();
        std::uint64_t pos = 0;
        for (const auto& [v, n] : fields) {
            ASSERT_EQ(codec::load_bits(rec.data(), pos, n), v) << trial << " at bit " << pos;
            pos += n;
        }
        for (std::size_t b = bytes + codec::kReadPad; b < rec.size(); ++b)
            ASSERT_EQ(rec[b], 0xCD)
                << trial << ": byte " << b << " of a " << bytes << "-byte record";
    }
}

TEST(NeighbourCodec, ArenaKeepsRecordsInPlaceAcrossBlocks) {
    codec::Arena arena;
    std::vector<const std::uint8_t*> at;
    std::vector<std::vector<std::uint8_t>> recs;
    std::mt19937 rng(9);
    for (int r = 0; r < 3000; ++r) { // ~3 MB: several blocks, one record larger than a block
        std::vector<std::uint8_t> rec(r == 1500 ? (3u << 20) : rng() % 2000);
        for (auto& b : rec) b = std::uint8_t(rng());
        at.push_back(arena.store(rec));
        recs.push_back(std::move(rec));
    }
    for (std::size_t r = 0; r < recs.size(); ++r)
        ASSERT_TRUE(std::equal(recs[r].begin(), recs[r].end(), at[r])) << r;
    const std::size_t held = arena.bytes();
    arena.reset();
    std::vector<std::uint8_t> small(10, 7);
    arena.store(small);
    arena.reset(); // frees the blocks the second build did not reach
    EXPECT_LT(arena.bytes(), held);
}

// Lists expanded group by group (as the SPH passes do) agree with find_neighbours, the
// per-particle tree walk that visits leaves in the same depth-first order: same indices in the
// same order. (Sets are checked against brute force in test_neighbours.)
TEST(NeighbourLists, GroupExpansionIsTheSearchOrderAndCompact) {
    const std::uint32_t n = 30000;
    ParticleSet<double> ps = testref::random_cube(n, 3, 0.035, 0.05);
    const Box<double> box = testref::unit_box(true);
    auto keys = sort_along_curve(ps, box, CurveKind::hilbert);
    Octree<double> tree;
    tree.build(keys.data(), n, 64);
    SearchView<double> sv{ps.data(Field::x), ps.data(Field::y), ps.data(Field::z),
                          ps.data(Field::h)};
    tree.update_bounds(sv.x, sv.y, sv.z, sv.h);
    for (auto crit : {NeighbourCriterion::gather, NeighbourCriterion::symmetric}) {
        NeighbourLists<double> nl(150);
        auto res = nl.build(tree, sv, box, crit, n);
        ASSERT_EQ(nl.size(), n);
        NeighbourLists<double>::Decoder dec(nl);
        std::vector<std::uint32_t> want(4 * res.max_count + 64);
        std::size_t total = 0;
        std::uint32_t longest = 0;
        for (std::size_t g = 0; g < nl.num_groups(); ++g) {
            dec.start(g);
            for (std::uint32_t i = nl.group_begin(g); i < nl.group_end(g); ++i) {
                ContiguousSpan got = dec.next();
                std::uint32_t c = find_neighbours(tree, sv, box, crit, i, want.data(),
                                                  std::uint32_t(want.size()));
                ASSERT_EQ(got.count, c) << "particle " << i;
                ASSERT_TRUE(std::equal(want.begin(), want.begin() + c, got.index)) << i;
                total += c;
                longest = std::max(longest, c);
            }
        }
        EXPECT_EQ(longest, res.max_count);
        EXPECT_GT(total / n, 60u); // ~100 neighbours: not vacuous
        // A fixed stride of 150 slots takes 600 B per particle; the records about a tenth.
        EXPECT_LT(double(nl.bytes()) / n, 150.0) << nl.bytes();
    }
}
