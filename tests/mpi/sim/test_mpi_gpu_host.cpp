// Issue 18, acceptance 5: the GPU path (GpuHostLauncher: the device's search and interleaved
// lists, run on the host) on this run's rank count gives the one-rank CPU result to 1e-10 per
// particle: the halos it searches come from the same domain as the CPU path's.
#include <cmath>

#include "exasph/util/mpi.hpp"
#include <gtest/gtest.h>
#include <omp.h>

#include "case_config.hpp"
#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "mpi_gather.hpp"
#include "one_rank_reference.hpp"

using namespace exasph;
using namespace exasph::testref;

class MpiGpuHost : public ::testing::TestWithParam<const char*> {};

TEST_P(MpiGpuHost, MatchesTheOneRankCpuPath) {
    Config cfg = case_config(GetParam(), 16);
    if (cfg.init == "sedov") apply_scheme(cfg, Scheme::std_sph);
    cfg.lattice = true;
    const int steps = 15;
    const OneRankReference ref = one_rank_reference(cfg, steps, 1);
    const auto [rank, nranks] = one_thread_per_rank();
    Simulation<double, GpuHostLauncher> sim(cfg, make_case(cfg));
    for (int s = 0; s < steps; ++s) sim.step();
    auto all = allgather(owned_state(sim), MPI_COMM_WORLD);
    if (rank != 0) return;
    ASSERT_EQ(all.size(), ref.state.size());
    const Differences d = compare_to_reference(all, ref);
    std::printf("%s, GPU path on %d ranks vs CPU on 1: rho %.2e v %.2e u %.2e a %.2e\n", GetParam(),
                nranks, d.rho, d.v, d.u, d.a);
    EXPECT_LT(d.rho, 1e-10);
    EXPECT_LT(d.v, 1e-10);
    EXPECT_LT(d.u, 1e-10);
    EXPECT_LT(d.a, 1e-10);
    EXPECT_NEAR(sim.diagnostics().etot, ref.etot, 1e-12 * std::abs(ref.etot));
}

INSTANTIATE_TEST_SUITE_P(Cases, MpiGpuHost, ::testing::Values("sedov", "square-patch"));
