// Acceptance 4 (issue 5): the glass maker reaches a density scatter below 1 % and leaves no two
// particles closer than half the mean spacing.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "exasph/glass/glass.hpp"

using namespace exasph;

TEST(Glass, DensityScatterBelowOnePercentAndNoClosePairs) {
    GlassParams gp;
    gp.side = 14;
    auto g = make_glass(gp, MPI_COMM_WORLD);
    std::printf("glass 14^3: density scatter %.4f %% after %lld steps\n", 100 * g.scatter,
                (long long)g.steps);
    RecordProperty("density_scatter", std::to_string(g.scatter));
    EXPECT_LT(g.scatter, 0.01);
    const auto& ps = g.particles;
    ASSERT_EQ(ps.size(), 14u * 14u * 14u);
    Box<double> box;
    box.lo = {-0.5, -0.5, -0.5};
    box.hi = {0.5, 0.5, 0.5};
    box.periodic = {true, true, true};
    double min_d2 = 1e300;
    for (std::size_t i = 0; i < ps.size(); ++i) {
        EXPECT_GE(ps[Field::x][i], -0.5);
        EXPECT_LT(ps[Field::x][i], 0.5);
        for (std::size_t j = i + 1; j < ps.size(); ++j) {
            double dx = box.min_image(ps[Field::x][j] - ps[Field::x][i], 0);
            double dy = box.min_image(ps[Field::y][j] - ps[Field::y][i], 1);
            double dz = box.min_image(ps[Field::z][j] - ps[Field::z][i], 2);
            min_d2 = std::min(min_d2, dx * dx + dy * dy + dz * dz);
        }
    }
    const double spacing = 1.0 / 14;
    std::printf("closest pair %.3f of the mean spacing\n", std::sqrt(min_d2) / spacing);
    EXPECT_GT(std::sqrt(min_d2), 0.5 * spacing);
}

TEST(Glass, BlockSideDividesTheRequestedSide) {
    EXPECT_EQ(glass_block_side(50), 25u);
    EXPECT_EQ(glass_block_side(40), 20u);
    EXPECT_EQ(glass_block_side(37), 37u);
    EXPECT_EQ(glass_block_side(16), 16u);
}
