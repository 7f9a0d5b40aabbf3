// Issue 8 / issue 7: the per-particle state hashes, computed a block of particles at a time
// (vectorised), equal the one-particle hash chain, and the guard finds the first changed particle.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "exasph/sim/state_guard.hpp"
#include "exasph/sim/state_store.hpp"

using namespace exasph;

namespace {
ParticleSet<double> random_particles(std::size_t n) {
    ParticleSet<double> ps;
    ps.resize(n);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.1, 0.9);
    for (std::size_t i = 0; i < n; ++i) {
        ps.id[i] = 1000 + 7 * i;
        for (Field f : ps.fields(kState)) ps[f][i] = u(rng);
    }
    return ps;
}
} // namespace

TEST(StateHash, BlocksEqualTheParticleChain) {
    const std::size_t n = 2 * kHashBlock + 5;
    const auto ps = random_particles(n);
    const auto fields = ps.fields(kState);
    std::uint64_t h[kHashBlock];
    for (std::size_t first = 0; first < n; first += kHashBlock) {
        const std::size_t count = std::min(kHashBlock, n - first);
        state_hash_block(ps, fields, first, count, h);
        for (std::size_t k = 0; k < count; ++k)
            ASSERT_EQ(h[k], particle_state_hash(ps, first + k, fields)) << first + k;
    }
}

TEST(StateHash, GuardFindsTheFirstChangedParticle) {
    const std::size_t n = 3 * kHashBlock + 11;
    auto ps = random_particles(n);
    Box<double> box;
    box.lo = {0, 0, 0};
    box.hi = {1, 1, 1};
    StateGuard<double> guard;
    guard.seal(ps, n);
    EXPECT_EQ(guard.check(ps, n, box, 0.0, false, true), "");
    for (std::size_t victim : {n - 1, std::size_t(kHashBlock + 3), std::size_t(0)}) {
        std::uint64_t bits;
        std::memcpy(&bits, &ps[Field::u][victim], 8);
        bits ^= 1ull << 3; // a low mantissa bit: no physics invariant notices it
        std::memcpy(&ps[Field::u][victim], &bits, 8);
        EXPECT_EQ(guard.check(ps, n, box, 0.0, false, true),
                  "particle id " + std::to_string(ps.id[victim]) +
                      ": state changed between steps (hash mismatch)");
    }
}

// Issue 60: the seals' hash sum as a kernel (FieldHashKernel, what the GPU path's launchers run)
// equals the CPU launcher's blocked sum, over wide and single-precision fields.
TEST(StateHash, KernelSumEqualsTheBlockedSum) {
    const std::size_t n = 5 * kHashBlock + 7;
    auto ps = random_particles(n);
    ps.enable(Field::rho), ps.enable(Field::nc); // narrow fields, stored as float
    for (std::size_t i = 0; i < n; ++i) ps.narrow(Field::rho)[i] = float(0.5 + 1e-3 * double(i));
    std::vector<Field> fields = ps.fields(kState);
    fields.push_back(Field::rho), fields.push_back(Field::nc);
    ASSERT_TRUE(ps.stored_single(Field::rho));
    const std::uint64_t blocked = field_hash_sum<OmpLauncher>(ps, fields, n);
    EXPECT_EQ(field_hash_sum<GpuHostLauncher>(ps, fields, n), blocked);
    EXPECT_EQ(OmpLauncher::reduce(n, FieldHashKernel{ps.id.data(), hashed_fields(ps, fields)}),
              blocked);
    ps.narrow(Field::rho)[n / 2] = std::nextafter(ps.narrow(Field::rho)[n / 2], 1.0f);
    EXPECT_NE(field_hash_sum<GpuHostLauncher>(ps, fields, n), blocked); // one bit: another sum
    EXPECT_EQ(field_hash_sum<GpuHostLauncher>(ps, fields, n), field_hash_sum(ps, fields, n));
}

// Issue 60: the guard on the GPU path's launcher (the kernels of sph/state_check_kern.hpp) seals
// the same sum and reports what the CPU launcher's blocked checks report.
TEST(StateHash, GuardKernelsReportWhatTheBlockedChecksReport) {
    const std::size_t n = 3 * kHashBlock + 11;
    auto ps = random_particles(n);
    Box<double> box;
    StateGuard<double> cpu;
    StateGuard<double, GpuHostLauncher> gpu;
    EXPECT_EQ(gpu.seal(ps, n), cpu.seal(ps, n));
    const auto same = [&](bool press_ok) {
        const std::string found = cpu.check(ps, n, box, 1e-3, press_ok, true);
        EXPECT_EQ(gpu.check(ps, n, box, 1e-3, press_ok, true), found);
        return found;
    };
    EXPECT_EQ(same(false), "");
    EXPECT_NE(same(true), "");           // random x, x_m1, v, a: the Press relation does not hold
    ps[Field::u][kHashBlock + 5] = -1.0; // a hash mismatch and a broken invariant at once
    EXPECT_EQ(same(false), "particle id " + std::to_string(ps.id[kHashBlock + 5]) +
                               ": state changed between steps (hash mismatch); particle id " +
                               std::to_string(ps.id[kHashBlock + 5]) + ": u is negative");
    ps[Field::vy][7] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(same(false).find(": vy is not finite"), std::string::npos);
    ps[Field::z][3] = 2.0;
    EXPECT_NE(same(false).find(": position outside the box"), std::string::npos);
}
