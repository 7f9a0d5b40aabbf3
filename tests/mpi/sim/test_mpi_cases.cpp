// Acceptance 5 (issue 5): Sedov and Noh give the same particles on 1 rank and on this run's rank
// count (to 1e-10), and their L1 density errors agree. Issue 6, acceptance 6: so does the Evrard
// collapse with self-gravity, accelerations and potentials included. "noh-limiter" is Noh with
// the options of its acceptance test (limited viscosity, whose velocity gradients cross ranks as
// halo fields; volume elements; conductivity). Issue 16, acceptance 8: the new cases with their
// default scheme (ve; pe for isobaric-cube; sh, with its per-particle alpha, for kelvin-helmholtz
// and wind-cloud): gresho-chan, isobaric-cube, kelvin-helmholtz, wind-cloud, turbulence (the
// stirring: every rank draws the same modes). Issue 63: the turbulent collapse to its end time.
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

class MpiCases : public ::testing::TestWithParam<const char*> {};

TEST_P(MpiCases, MatchOneRank) {
    const std::string name = GetParam();
    const bool new_case = name == "gresho-chan" || name == "isobaric-cube" ||
                          name == "kelvin-helmholtz" || name == "wind-cloud" ||
                          name == "turbulence" || name == "turbulent-collapse";
    Config cfg = new_case ? case_config(name, 16) : Config{};
    cfg.init = name;
    if (cfg.init == "noh-limiter") {
        cfg.init = "noh";
        cfg.av_limiter = true;
        cfg.volume_elements = true;
        cfg.conductivity = 2.0;
    }
    cfg.side = 16;
    cfg.lattice = true; // the decomposition is under test, not the glass cache
    const int steps = 15;
    OneRankReference ref = one_rank_reference(cfg, steps, 1);
    const auto [rank, nranks] = one_thread_per_rank();
    Simulation<double> sim(cfg, make_case(cfg));
    for (int s = 0; s < steps; ++s) sim.step();
    auto all = allgather(owned_state(sim), MPI_COMM_WORLD);
    if (rank != 0) return;
    ASSERT_EQ(all.size(), ref.state.size());
    Differences d = compare_to_reference(all, ref);
    std::printf("%s on %d ranks: worst differences rho %.2e v %.2e u %.2e a %.2e phi %.2e, "
                "L1 %.6f\n",
                GetParam(), nranks, d.rho, d.v, d.u, d.a, d.phi, sim.diagnostics().l1_rho);
    EXPECT_LT(d.rho, 1e-10);
    EXPECT_LT(d.v, 1e-10);
    EXPECT_LT(d.u, 1e-10);
    EXPECT_LT(d.a, 1e-10);
    EXPECT_LT(d.phi, 1e-10);
    EXPECT_NEAR(sim.diagnostics().etot, ref.etot, 1e-12 * std::abs(ref.etot));
    if (cfg.init == "evrard") {
        EXPECT_GT(sim.gravitational_constant(), 0.0);
        EXPECT_LT(sim.diagnostics().epot, -0.5); // the gravity pass ran
    } else if (!new_case) {
        EXPECT_GE(sim.diagnostics().l1_rho, 0.0); // sedov, noh: their exact solutions
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, MpiCases,
                         ::testing::Values("sedov", "noh", "noh-limiter", "evrard", "gresho-chan",
                                           "isobaric-cube", "kelvin-helmholtz", "wind-cloud",
                                           "turbulence", "turbulent-collapse"));

// Issue 63, acceptance 3 (in part): the turbulent collapse (periodic self-gravity through the
// Ewald sum, the stirring) runs to its end time, t = 0.5, on this run's rank count as on one rank,
// in the same number of steps, and collapses (from a lattice the densest particle reaches 7.8
// times the mean; from the glass, the case's default, about 100). The states there differ by
// 2e-7 on 3 ranks (printed, not asserted): the SPH sums' order follows the decomposition, and the
// collapse amplifies those round-off differences (1e-16 after a step, 1e-12 after 15, which
// MpiCases asserts to 1e-10) by about e every 9 steps.
TEST(MpiCollapse, TurbulentCollapseRunsToItsEndTime) {
    Config cfg = case_config("turbulent-collapse", 16);
    cfg.lattice = true;
    const double t_end = 0.5;
    auto run = [&](Simulation<double>& sim) {
        sim.set_end_time(t_end);
        while (sim.time() < t_end * (1 - 1e-12)) sim.step();
    };
    OneRankReference ref;
    const auto [rank, nranks] = one_thread_per_rank();
    long long ref_steps = 0;
    if (rank == 0) {
        Simulation<double> sim(cfg, make_case(cfg, MPI_COMM_SELF), MPI_COMM_SELF);
        run(sim);
        for (const auto& st : owned_state(sim)) ref.state[st.id] = st;
        ref_steps = sim.step_count();
    }
    Simulation<double> sim(cfg, make_case(cfg));
    run(sim);
    auto all = allgather(owned_state(sim), MPI_COMM_WORLD);
    if (rank != 0) return;
    ASSERT_EQ(all.size(), ref.state.size());
    const Differences d = compare_to_reference(all, ref);
    std::printf("turbulent-collapse on %d ranks: t = %.4f after %lld steps (1 rank: %lld), "
                "rho_max %.2f, E_pot %.4f; differences to 1 rank: rho %.2e v %.2e u %.2e a %.2e "
                "phi %.2e\n",
                nranks, sim.time(), (long long)sim.step_count(), ref_steps,
                sim.diagnostics().rho_max, sim.diagnostics().epot, d.rho, d.v, d.u, d.a, d.phi);
    EXPECT_NEAR(sim.time(), t_end, 1e-12);
    EXPECT_EQ(sim.step_count(), ref_steps);
    EXPECT_GT(sim.diagnostics().rho_max, 5.0); // it collapses
    EXPECT_EQ(sim.safety().recoveries(), 0) << sim.safety().summary();
}
