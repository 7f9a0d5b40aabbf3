#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "exasph/particles/particle_set.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/branch_free_exp.hpp"

using namespace exasph;

TEST(Box, MinimumImageOnPeriodicAxesOnly) {
    Box<double> b;
    b.lo = {0, 0, 0};
    b.hi = {10, 10, 10};
    b.periodic = {true, false, true};
    EXPECT_DOUBLE_EQ(b.min_image(9.0, 0), -1.0);
    EXPECT_DOUBLE_EQ(b.min_image(-9.0, 2), 1.0);
    EXPECT_DOUBLE_EQ(b.min_image(9.0, 1), 9.0);
    EXPECT_DOUBLE_EQ(b.wrap_shift(10.5, 0), -10.0);
    EXPECT_DOUBLE_EQ(b.wrap_shift(-0.5, 2), 10.0);
    EXPECT_DOUBLE_EQ(b.wrap_shift(-0.5, 1), 0.0);
}

TEST(ParticleSet, PermuteMovesStateFieldsAndIds) {
    ParticleSet<double> ps;
    ps.resize(3);
    for (int i = 0; i < 3; ++i) {
        ps.id[i] = 10 + i;
        ps[Field::x][i] = i;
        ps[Field::h][i] = 1;
        ps[Field::m][i] = 1;
    }
    ps.permute({2, 0, 1});
    EXPECT_EQ(std::vector<std::uint64_t>(ps.id.begin(), ps.id.end()),
              (std::vector<std::uint64_t>{12, 10, 11}));
    EXPECT_EQ(ps[Field::x], (FieldArray<double>{2, 0, 1}));
    EXPECT_NO_THROW(ps.validate());
    ps[Field::m][1] = 0;
    EXPECT_THROW(ps.validate(), Error);
}

namespace {
long g_backend_bytes = 0;
void* counting_allocate(std::size_t bytes) {
    g_backend_bytes += long(bytes);
    return std::malloc(bytes);
}
void counting_release(void* p) {
    std::free(p);
}
} // namespace

// Issue 18: a backend's field memory (the CUDA backend's managed memory) serves every particle
// field and kernel table made after it is installed, and cannot be swapped under live arrays.
TEST(FieldMemory, AnInstalledAllocatorServesTheFieldsAndGuardsLiveArrays) {
    {
        ParticleSet<double> ps;
        ps.resize(10);
        EXPECT_THROW(install_field_memory({counting_allocate, counting_release, "counting"}),
                     std::logic_error);
    }
    install_field_memory({counting_allocate, counting_release, "counting"});
    {
        ParticleSet<double> ps;
        ps.resize(100);
        EXPECT_GE(g_backend_bytes, long(100 * sizeof(double)) * 10);
        EXPECT_STREQ(field_memory().name, "counting");
    }
    install_field_memory({});
    EXPECT_STREQ(field_memory().name, "host");
}

// The limiter's fade exp(-e^2) uses it inside a vectorised pair loop: it must be std::exp to
// within an ulp where the loop reads it, give e^-700 below that, and pass a NaN on.
TEST(BranchFreeExp, WithinOneUlpOfStdExpForNonPositiveArguments) {
    double worst = 0;
    for (int i = 0; i <= 400000; ++i) {
        const double x = -40.0 * i / 400000.0 - 1e-7 * (i % 7);
        const double exact = std::exp(x);
        const double ulp = std::nextafter(exact, 2 * exact) - exact;
        worst = std::max(worst, std::abs(exp_nonpositive(x) - exact) / ulp);
    }
    EXPECT_LE(worst, 1.0);
    EXPECT_EQ(exp_nonpositive(0.0), 1.0);
    EXPECT_EQ(exp_nonpositive(-1e4), std::exp(-700.0));
    EXPECT_TRUE(std::isnan(exp_nonpositive(std::numeric_limits<double>::quiet_NaN())));
}
