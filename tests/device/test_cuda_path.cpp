// Issue 18, acceptance 4 (on a machine with a GPU; skipped elsewhere): the CUDA backend against
// the CPU path in the same process. Sedov -n 50 (5 steps, standard scheme, derived fields in
// double) and the square patch (20 steps): every particle's rho, v, u and a within 1e-10 of the
// field's scale, and the conservation sums alike. Run by bench/gpu/check.sh on the device.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "case_config.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "exasph/sph/cuda_launcher.hpp"
#include "exasph/util/cuda_runtime.hpp"
#include "one_rank_reference.hpp"

using namespace exasph;
using namespace exasph::testref;

namespace {

template <class L>
std::vector<ParticleState> run(const Config& cfg, int steps, Diagnostics* diag) {
    Simulation<double, L> sim(cfg, make_case(cfg));
    for (int s = 0; s < steps; ++s) sim.step();
    EXPECT_EQ(sim.recoveries(), 0);
    *diag = sim.diagnostics();
    auto st = owned_state(sim);
    std::sort(st.begin(), st.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
    return st;
}

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
    Diagnostics cpu_diag, gpu_diag;
    const auto cpu = run<OmpLauncher>(cfg, steps, &cpu_diag);
    const auto gpu = run<CudaLauncher>(cfg, steps, &gpu_diag);
    ASSERT_EQ(cpu.size(), gpu.size());
    OneRankReference ref;
    for (const auto& s : cpu) ref.state[s.id] = s;
    const Differences d = compare_to_reference(gpu, ref);
    std::printf("%s -n %d, %d steps: GPU vs CPU: rho %.2e v %.2e u %.2e a %.2e\n",
                cfg.init.c_str(), cfg.side, steps, d.rho, d.v, d.u, d.a);
    EXPECT_LT(d.rho, 1e-10);
    EXPECT_LT(d.v, 1e-10);
    EXPECT_LT(d.u, 1e-10);
    EXPECT_LT(d.a, 1e-10);
    EXPECT_NEAR(gpu_diag.etot, cpu_diag.etot, 1e-10 * std::abs(cpu_diag.etot));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(gpu_diag.momentum[c], cpu_diag.momentum[c], 1e-10 * cpu_diag.momentum_abs);
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
