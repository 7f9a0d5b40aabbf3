// Issue 18, acceptance 4 (on a machine with a GPU; skipped elsewhere): the CUDA backend against
// the CPU path in the same process. Sedov -n 50 (5 steps, standard scheme, derived fields in
// double) and the square patch (20 steps): every particle's rho, v, u and a within 1e-10 of the
// field's scale, and the conservation sums alike. Run by bench/gpu/check.sh on the device.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "exasph/sph/cuda_launcher.hpp"
#include "exasph/util/cuda_runtime.hpp"
#include "exasph/util/field_memory.hpp"
#include "launcher_comparison.hpp"

using namespace exasph;
using namespace exasph::testref;

namespace {

// The first test to run selects the device and puts the fields in managed memory.
bool have_device() {
    static const bool ok = [] {
        if (cuda::visible_devices() == 0) return false;
        std::printf("device: %s\n", cuda::use_device(0).c_str());
        return true;
    }();
    return ok;
}

// Device-readable arrays (managed memory, once have_device() has installed it).
template <class V>
using Managed = std::vector<V, FieldAllocator<V>>;

void expect_same_run(Config cfg, int steps) {
    cfg.double_precision = true; // the comparison is of the arithmetic, not of float storage
    expect_same_as_cpu<CudaLauncher>(cfg, steps, 1e-10, "GPU");
}

} // namespace

TEST(CudaPath, SedovFiveStepsMatchTheCpuPath) {
    if (!have_device()) GTEST_SKIP() << "no CUDA device visible: " << cuda::no_device_reason();
    Config cfg = case_config("sedov", 50);
    apply_scheme(cfg, Scheme::std_sph);
    cfg.lattice = std::getenv("EXASPH_GLASS_DIR") == nullptr; // no cache: skip the glass
    expect_same_run(cfg, 5);
}

TEST(CudaPath, SquarePatchTwentyStepsMatchTheCpuPath) {
    if (!have_device()) GTEST_SKIP() << "no CUDA device visible: " << cuda::no_device_reason();
    expect_same_run(case_config("square-patch", 20), 20);
}

TEST(CudaPath, VolumeElementsAndTheLimiterMatchTheCpuPath) {
    if (!have_device()) GTEST_SKIP() << "no CUDA device visible: " << cuda::no_device_reason();
    Config cfg = case_config("sedov", 30); // ve: volume elements, AV limiter, conductivity
    cfg.lattice = true;
    expect_same_run(cfg, 5);
}

// Issue 20: block time steps on the device (active-only lists, subset passes, the limiter's
// atomic max in device memory) against the CPU path: Sedov -n 30, 40 sub-steps.
TEST(CudaPath, BlockTimeStepsMatchTheCpuPath) {
    if (!have_device()) GTEST_SKIP() << "no CUDA device visible: " << cuda::no_device_reason();
    Config cfg = case_config("sedov", 30);
    cfg.lattice = true;
    cfg.timesteps = TimeStepping::block;
    expect_same_run(cfg, 40);
}

// Issue 59: the CUDA launcher's primitives (CUB's scan and radix sort, gather, scatter) on
// managed arrays give the CPU launcher's results bit for bit: a million scrambled keys with many
// ties (the sort is stable on both), in-place and out-of-place scans.
TEST(CudaPath, PrimitivesMatchTheCpuLauncher) {
    if (!have_device()) GTEST_SKIP() << "no CUDA device visible: " << cuda::no_device_reason();
    const std::size_t n = 1000003;
    std::vector<std::uint64_t> keys(n);
    std::vector<std::uint32_t> counts(n);
    for (std::size_t i = 0; i < n; ++i) {
        keys[i] = (std::uint64_t(i) * 2654435761u) % 4294967296u % 997;
        counts[i] = std::uint32_t(keys[i] % 61);
    }
    std::vector<ParticleIndex> order(n);
    std::iota(order.begin(), order.end(), ParticleIndex(0));
    Managed<std::uint64_t> dkeys(keys.begin(), keys.end());
    Managed<ParticleIndex> dorder(order.begin(), order.end());
    OmpLauncher::sort_by_key(keys.data(), order.data(), n);
    CudaLauncher::sort_by_key(dkeys.data(), dorder.data(), n);
    EXPECT_TRUE(std::equal(keys.begin(), keys.end(), dkeys.begin()));
    EXPECT_TRUE(std::equal(order.begin(), order.end(), dorder.begin()));

    Managed<std::uint32_t> dcounts(counts.begin(), counts.end()), doffsets(n);
    std::vector<std::uint32_t> offsets(n);
    const auto total = OmpLauncher::exclusive_scan(counts.data(), offsets.data(), n);
    EXPECT_EQ(CudaLauncher::exclusive_scan(dcounts.data(), doffsets.data(), n), total);
    EXPECT_TRUE(std::equal(offsets.begin(), offsets.end(), doffsets.begin()));
    EXPECT_EQ(CudaLauncher::exclusive_scan(dcounts.data(), dcounts.data(), n), total); // in place
    EXPECT_TRUE(std::equal(offsets.begin(), offsets.end(), dcounts.begin()));

    Managed<double> field(n), gathered(n), back(n);
    for (std::size_t i = 0; i < n; ++i) field[i] = 0.25 * double(i);
    CudaLauncher::gather(dorder.data(), field.data(), gathered.data(), n);
    for (std::size_t i = 0; i < n; i += 1009) ASSERT_EQ(gathered[i], field[order[i]]) << i;
    CudaLauncher::scatter(dorder.data(), gathered.data(), back.data(), n);
    EXPECT_TRUE(std::equal(field.begin(), field.end(), back.begin()));
}
