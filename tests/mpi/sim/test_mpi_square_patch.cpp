// Acceptance 1, 2, 3, 5, 6 (issue 3): square patch -n 24, 20 steps, on every rank count that
// runs this test, against a one-rank reference computed on rank 0 (MPI_COMM_SELF) with two
// OpenMP threads while the distributed run uses one thread per rank.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <utility>

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

constexpr int kSteps = 20;

Config patch_config() {
    Config cfg;
    cfg.side = 24;
    return cfg;
}

} // namespace

TEST(MpiSquarePatch, MatchesOneRankAndKeepsOwnershipBalanceAndCollectives) {
    OneRankReference ref = one_rank_reference(patch_config(), kSteps, 2);
    const auto [rank, nranks] = one_thread_per_rank();
    Config cfg = patch_config();
    Simulation<double> sim(cfg, make_case(cfg));
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
        Differences d = compare_to_reference(all, ref);
        std::printf("worst relative differences: rho %.2e, v %.2e, u %.2e\n", d.rho, d.v, d.u);
        const double worst_rho = d.rho, worst_v = d.v, worst_u = d.u;
        EXPECT_LT(worst_rho, 1e-10);
        EXPECT_LT(worst_v, 1e-10);
        EXPECT_LT(worst_u, 1e-10);
        EXPECT_NEAR(sim.diagnostics().etot, ref.etot, 1e-12 * std::abs(ref.etot));
        EXPECT_NEAR(sim.diagnostics().angular_momentum[2], ref.lz, 1e-12 * std::abs(ref.lz));
    }
}

// Issue 23: the communication record. What rank i recorded as sent to j is what j recorded as
// received from i, message for message and byte for byte, for every kind of traffic; halo
// traffic goes only to the halo partners of the last sync and their number stays small.
TEST(MpiSquarePatch, CommRecordAgreesBetweenSendersAndReceivers) {
    const auto [rank, nranks] = one_thread_per_rank();
    Config cfg = patch_config();
    Simulation<double> sim(cfg, make_case(cfg));
    for (int s = 0; s < 5; ++s) sim.step();
    const CommRecord& rec = sim.domain().comm_record();
    struct Entry {
        std::uint64_t from, to, kind, messages, bytes, sent;
    };
    std::vector<Entry> mine;
    for (int p = 0; p < nranks; ++p)
        for (int t = 0; t < kNumTraffic; ++t) {
            const MessageCount s = rec.sent_to(p, Traffic(t)), r = rec.received_from(p, Traffic(t));
            if (s.messages)
                mine.push_back({std::uint64_t(rank), std::uint64_t(p), std::uint64_t(t), s.messages,
                                s.bytes, 1});
            if (r.messages)
                mine.push_back({std::uint64_t(p), std::uint64_t(rank), std::uint64_t(t), r.messages,
                                r.bytes, 0});
        }
    EXPECT_EQ(rec.sent_to(rank, Traffic::halo).messages, 0u) << "a rank sent halos to itself";
    auto all = testref::allgather(mine, MPI_COMM_WORLD);
    std::map<std::tuple<std::uint64_t, std::uint64_t, std::uint64_t>, std::pair<Entry, Entry>> by;
    for (const Entry& e : all)
        (e.sent ? by[{e.from, e.to, e.kind}].first : by[{e.from, e.to, e.kind}].second) = e;
    for (const auto& [key, pair] : by) {
        EXPECT_EQ(pair.first.messages, pair.second.messages)
            << std::get<0>(key) << " -> " << std::get<1>(key) << " kind " << std::get<2>(key);
        EXPECT_EQ(pair.first.bytes, pair.second.bytes)
            << std::get<0>(key) << " -> " << std::get<1>(key) << " kind " << std::get<2>(key);
    }
    const int peers = rec.peers(Traffic::halo);
    int most = peers;
    MPI_Allreduce(MPI_IN_PLACE, &most, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (rank == 0) std::printf("%d ranks: at most %d halo peers per rank\n", nranks, most);
    EXPECT_LE(most, std::min(nranks - 1, 26));
    if (nranks > 1) {
        EXPECT_GT(peers, 0) << "rank " << rank << " exchanged no halos";
    }
}
