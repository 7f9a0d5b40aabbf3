// Issue 18, acceptance 4 (on a machine with a GPU; skipped elsewhere): the CUDA backend against
// the CPU path in the same process. Sedov -n 50 (5 steps, standard scheme, derived fields in
// double) and the square patch (20 steps): every particle's rho, v, u and a within 1e-10 of the
// field's scale, and the conservation sums alike. Run by bench/gpu/check.sh on the device.
#include <cstdlib>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "exasph/sph/cuda_launcher.hpp"
#include "exasph/util/cuda_runtime.hpp"
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
