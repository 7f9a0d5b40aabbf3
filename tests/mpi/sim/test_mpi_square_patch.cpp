// Acceptance 1, 2, 3, 5, 6 (issue 3): square patch -n 24, 20 steps, on every rank count that
// runs this test, against a one-rank reference computed on rank 0 (MPI_COMM_SELF) with two
// OpenMP threads while the distributed run uses one thread per rank.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <gtest/gtest.h>
#include <mpi.h>
#include <omp.h>

#include "exasph/sim/cases.hpp"
#include "exasph/sim/simulation.hpp"
#include "mpi_gather.hpp"

using namespace exasph;

namespace {

constexpr int kSteps = 20;

struct State {
    std::uint64_t id;
    double rho, vx, vy, vz, u;
};

Config patch_config() {
    Config cfg;
    cfg.side = 24;
    return cfg;
}

std::vector<State> owned_state(const Simulation<double>& sim) {
    const auto& ps = sim.particles();
    std::vector<State> out(sim.n_owned());
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = {ps.id[i],         ps[Field::rho][i], ps[Field::vx][i],
                  ps[Field::vy][i], ps[Field::vz][i],  ps[Field::u][i]};
    return out;
}

struct Reference {
    std::map<std::uint64_t, State> state;
    double etot = 0, lz = 0;
};

Reference serial_reference() {
    Reference ref;
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) {
        omp_set_num_threads(2);
        Config cfg = patch_config();
        Simulation<double> sim(cfg, make_case<double>(cfg), MPI_COMM_SELF);
        for (int s = 0; s < kSteps; ++s) sim.step();
        for (const auto& st : owned_state(sim)) ref.state[st.id] = st;
        ref.etot = sim.diagnostics().etot;
        ref.lz = sim.diagnostics().angular_momentum[2];
    }
    MPI_Bcast(&ref.etot, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    MPI_Bcast(&ref.lz, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    return ref;
}

} // namespace

TEST(MpiSquarePatch, MatchesOneRankAndKeepsOwnershipBalanceAndCollectives) {
    Reference ref = serial_reference();
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    omp_set_num_threads(1);
    Config cfg = patch_config();
    Simulation<double> sim(cfg, make_case<double>(cfg, rank, nranks));
    const std::uint64_t n = std::uint64_t(cfg.side) * cfg.side * cfg.side;
    for (int s = 0; s < kSteps; ++s) {
        auto c0 = sim.collective_count();
        sim.step();
        EXPECT_EQ(sim.collective_count() - c0, 3) << "collectives in step " << s;
        // Every particle owned by exactly one rank, none lost (ids gathered for the test only).
        auto all = testref::allgather(owned_state(sim), MPI_COMM_WORLD);
        ASSERT_EQ(all.size(), n) << "step " << s;
        std::set<std::uint64_t> ids;
        for (const auto& st : all) ids.insert(st.id);
        ASSERT_EQ(ids.size(), n) << "step " << s;
        // Imbalance after the sync: at most globalBucketSize particles above the mean.
        const auto& counts = sim.domain().assignment().count;
        for (auto c : counts)
            EXPECT_LE(std::abs(double(c) - double(n) / nranks), double(cfg.global_bucket));
    }
    auto all = testref::allgather(owned_state(sim), MPI_COMM_WORLD);
    if (rank == 0) {
        std::printf("%d ranks: E_tot %.15e (ref %.15e), L_z %.15e (ref %.15e)\n", nranks,
                    sim.diagnostics().etot, ref.etot, sim.diagnostics().angular_momentum[2],
                    ref.lz);
        double vmax = 0, umax = 0;
        for (const auto& [id, st] : ref.state) {
            vmax = std::max({vmax, std::abs(st.vx), std::abs(st.vy), std::abs(st.vz)});
            umax = std::max(umax, std::abs(st.u));
        }
        double worst_rho = 0, worst_v = 0, worst_u = 0;
        for (const auto& st : all) {
            const State& r = ref.state.at(st.id);
            worst_rho = std::max(worst_rho, std::abs(st.rho - r.rho) / r.rho);
            worst_v = std::max({worst_v, std::abs(st.vx - r.vx) / vmax,
                                std::abs(st.vy - r.vy) / vmax, std::abs(st.vz - r.vz) / vmax});
            worst_u = std::max(worst_u, std::abs(st.u - r.u) / umax);
        }
        std::printf("worst relative differences: rho %.2e, v %.2e, u %.2e\n", worst_rho, worst_v,
                    worst_u);
        EXPECT_LT(worst_rho, 1e-10);
        EXPECT_LT(worst_v, 1e-10);
        EXPECT_LT(worst_u, 1e-10);
        EXPECT_NEAR(sim.diagnostics().etot, ref.etot, 1e-12 * std::abs(ref.etot));
        EXPECT_NEAR(sim.diagnostics().angular_momentum[2], ref.lz, 1e-12 * std::abs(ref.lz));
    }
}
