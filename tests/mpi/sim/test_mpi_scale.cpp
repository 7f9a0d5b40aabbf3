// Issue 23: the cost-weighted cut and the overlap of halo exchanges with the passes.
// --balance cost: with block time steps the curve is cut by each sub-step's expected
// work (an active particle 1, an inactive one 0.15). On Sedov, where the hot centre steps on short
// rungs, each sub-step's work per rank is then nearly equal where the count cut leaves it to a
// few ranks; no rank holds over 1.5 times the mean count, the results are those of one rank
// (1e-10), and the cost rides in the sync's one collective (the count per step is unchanged).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "exasph/util/mpi.hpp"
#include <gtest/gtest.h>
#include <omp.h>

#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "mpi_gather.hpp"
#include "one_rank_reference.hpp"

using namespace exasph;
using namespace exasph::testref;

namespace {

// Most loaded rank's cost over the mean, for the ranges of `a` over the leaf costs.
double cost_imbalance(const Assignment& a, const std::vector<double>& costs) {
    const int nranks = int(a.first_leaf.size()) - 1;
    double most = 0, total = 0;
    for (int r = 0; r < nranks; ++r) {
        double c = 0;
        for (std::uint32_t l = a.first_leaf[r]; l < a.first_leaf[r + 1]; ++l) c += costs[l];
        most = std::max(most, c);
        total += c;
    }
    return most / (total / nranks);
}

Config sedov_blocks() {
    Config cfg;
    cfg.init = "sedov";
    cfg.side = 16;
    cfg.lattice = true;
    cfg.timesteps = TimeStepping::block;
    cfg.balance = Balance::cost;
    return cfg;
}

} // namespace

TEST(MpiScale, CostCutSpreadsEachSubStepsWorkAndKeepsTheResults) {
    const Config cfg = sedov_blocks();
    const int steps = 100;
    OneRankReference ref = one_rank_reference(cfg, steps, 1);
    const auto [rank, nranks] = one_thread_per_rank();
    Simulation<double> sim(cfg, make_case(cfg));
    double by_cost = 0, by_count = 0, worst_count = 1;
    int partial = 0; // sub-steps with inactive particles
    for (int s = 0; s < steps; ++s) {
        const std::int64_t before = sim.collective_count();
        sim.step();
        const Assignment& a = sim.domain().assignment();
        const auto& costs = sim.domain().leaf_costs();
        ASSERT_EQ(costs.size(), a.leaf_count.size());
        EXPECT_LE(sim.collective_count() - before, 4); // sync, dt, diagnostics (+ block start)
        worst_count = std::max(worst_count, a.imbalance());
        if (sim.diagnostics().work.active == double(sim.diagnostics().n)) continue;
        ++partial;
        by_cost += cost_imbalance(a, costs);
        by_count += cost_imbalance(assign_leaves(a.leaf_count, nranks), costs);
    }
    auto all = allgather(owned_state(sim), MPI_COMM_WORLD);
    if (rank != 0) return;
    ASSERT_GT(partial, steps / 2);
    by_cost /= partial, by_count /= partial;
    std::printf("%d ranks, %d sub-steps with inactive particles: work per rank max/mean %.3f "
                "(the count cut would give %.3f); particles per rank max/mean up to %.3f\n",
                nranks, partial, by_cost, by_count, worst_count);
    EXPECT_LE(worst_count, kCostBalanceMemoryBound + 1e-12);
    if (nranks > 1) { // the work each rank waits for beyond the mean: at least halved
        EXPECT_LT(by_cost, 1.05);
        EXPECT_GT(by_count - 1, 2 * (by_cost - 1));
    }
    Differences d = compare_to_reference(all, ref);
    EXPECT_LT(d.rho, 1e-10);
    EXPECT_LT(d.v, 1e-10);
    EXPECT_LT(d.u, 1e-10);
    EXPECT_NEAR(sim.diagnostics().etot, ref.etot, 1e-12 * std::abs(ref.etot));
}

// Issue 23, overlap: computing the particles that do not need a halo exchange while it is in
// flight changes no particle's arithmetic: the state is bitwise that of the passes in turn, on
// the cases that exercise every halo group (gravity's softening zeta with the density halos,
// the limiter's velocity gradients with the IAD halos, volume elements) and with block steps.
TEST(MpiScale, HaloOverlapLeavesEveryBitAsItWas) {
    struct Variant {
        const char* init;
        bool limiter, blocks;
    };
    for (const Variant v : {Variant{"evrard", false, false}, Variant{"noh", true, false},
                            Variant{"sedov", false, true}}) {
        Config cfg;
        cfg.init = v.init;
        cfg.side = 14;
        cfg.lattice = true;
        cfg.av_limiter = cfg.volume_elements = v.limiter;
        if (v.blocks) cfg.timesteps = TimeStepping::block;
        omp_set_num_threads(1);
        std::vector<std::vector<ParticleState>> states;
        for (bool no_overlap : {false, true}) {
            cfg.no_halo_overlap = no_overlap;
            Simulation<double> sim(cfg, make_case(cfg));
            for (int s = 0; s < 8; ++s) sim.step();
            states.push_back(owned_state(sim));
        }
        ASSERT_EQ(states[0].size(), states[1].size()) << v.init;
        int differing = 0;
        for (std::size_t i = 0; i < states[0].size(); ++i)
            differing += std::memcmp(&states[0][i], &states[1][i], sizeof(ParticleState)) != 0;
        EXPECT_EQ(differing, 0) << v.init << ": particles whose state differs";
    }
}
