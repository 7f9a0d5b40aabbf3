// Acceptance 3 (issue 2): the tree search returns exactly the brute-force neighbour sets.
#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "brute_force_neighbours.hpp"
#include "exasph/domain/sfc_order.hpp"
#include "exasph/tree/neighbour_lists.hpp"
#include "random_particles.hpp"

using namespace exasph;

namespace {

struct Cloud {
    ParticleSet<double> ps;
    Box<double> box;
    std::vector<std::uint64_t> keys;
};

// 20,000 random particles in the unit cube with h varying by a factor of three.
Cloud random_cloud(bool periodic, CurveKind curve) {
    Cloud c;
    c.ps = testref::random_cube(20000, periodic ? 11 : 12, 0.03, 0.09);
    c.box = testref::unit_box(periodic);
    fit_open_axes(c.box, c.ps);
    c.keys = sort_along_curve(c.ps, c.box, curve);
    return c;
}

void expect_brute_force_sets(bool periodic, CurveKind curve, std::uint32_t bucket) {
    Cloud c = random_cloud(periodic, curve);
    const auto n = std::uint32_t(c.ps.size());
    Octree<double> tree;
    tree.build(c.keys.data(), n, bucket);
    SearchView<double> sv{c.ps.data(Field::x), c.ps.data(Field::y), c.ps.data(Field::z),
                          c.ps.data(Field::h)};
    tree.update_bounds(sv.x, sv.y, sv.z, sv.h);
    for (auto crit : {NeighbourCriterion::gather, NeighbourCriterion::symmetric}) {
        NeighbourLists<double> nl(16); // small on purpose: exceeded, reported, never truncated
        auto res = nl.build(tree, sv, c.box, crit, n);
        EXPECT_TRUE(res.exceeded);
        EXPECT_GT(res.max_count, 16u);
        std::size_t total = 0;
        for (std::uint32_t i = 0; i < n; ++i) {
            std::vector<std::uint32_t> got = nl.list(i);
            std::sort(got.begin(), got.end());
            auto want = testref::brute_force_neighbours(sv, c.box, n, i, crit);
            ASSERT_EQ(got, want) << "particle " << i << (periodic ? " periodic" : " open");
            total += want.size();
        }
        EXPECT_GT(total / n, 20u); // the test is not vacuous
    }
}

} // namespace

TEST(NeighbourSearch, OpenBoxMatchesBruteForce) {
    expect_brute_force_sets(false, CurveKind::hilbert, 64);
}

TEST(NeighbourSearch, PeriodicBoxMatchesBruteForce) {
    expect_brute_force_sets(true, CurveKind::hilbert, 64);
}

TEST(NeighbourSearch, MortonTreeAndSmallLeavesMatchBruteForce) {
    expect_brute_force_sets(true, CurveKind::morton, 8);
}

TEST(Octree, LeavesTileTheParticlesAndRespectBucketSize) {
    Cloud c = random_cloud(false, CurveKind::hilbert);
    Octree<double> tree;
    tree.build(c.keys.data(), std::uint32_t(c.ps.size()), 32);
    std::uint32_t next = 0;
    for (auto l : tree.leaves()) {
        const auto& nd = tree.nodes()[l];
        EXPECT_EQ(nd.begin, next);
        EXPECT_LE(nd.end - nd.begin, 32u);
        next = nd.end;
    }
    EXPECT_EQ(next, c.ps.size());
    // Children partition their parent's range.
    for (const auto& nd : tree.nodes()) {
        if (nd.first_child < 0) continue;
        EXPECT_EQ(tree.nodes()[nd.first_child].begin, nd.begin);
        EXPECT_EQ(tree.nodes()[nd.first_child + nd.num_children - 1].end, nd.end);
    }
}

TEST(NeighbourSearch, RejectsSmoothingLengthTooLargeForPeriod) {
    Box<double> box;
    box.periodic = {true, false, false};
    EXPECT_THROW(check_periodic_reach(box, 0.3), Error);
    EXPECT_NO_THROW(check_periodic_reach(box, 0.2));
}
