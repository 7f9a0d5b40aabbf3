#pragma once
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/domain/comm_record.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// How much point-to-point traffic each rank had, reduced over the ranks (the run summary's
// line; an output-time collective).
struct CommSummary {
    double halo_peers_mean = 0, halo_peers_max = 0;
    double halo_bytes_mean = 0, halo_bytes_max = 0; // sent per rank, summed over the steps
    double migration_bytes = 0, gravity_bytes = 0;  // sent, all ranks
    // The SPH passes' halo exchanges, seconds per rank (mean) over the run's steps after the
    // first: spent in them, and in flight while the rank computed (CommRecord::halo_time).
    double halo_exposed = 0, halo_behind_compute = 0;
};

// `before`: the halo seconds (exposed, behind computation) to leave out (the first step's).
inline CommSummary summarise_comm(const CommRecord& rec, MPI_Comm comm,
                                  std::array<double, 2> before = {0, 0}) {
    double sent[kNumTraffic] = {};
    for (int r = 0; r < rec.nranks(); ++r)
        for (int t = 0; t < kNumTraffic; ++t) sent[t] += double(rec.sent_to(r, Traffic(t)).bytes);
    double sums[6] = {double(rec.peers(Traffic::halo)),
                      sent[0],
                      sent[1],
                      sent[2],
                      rec.halo_exposed_seconds() - before[0],
                      rec.halo_behind_compute_seconds() - before[1]};
    double maxima[2] = {sums[0], sums[1]};
    MPI_Allreduce(MPI_IN_PLACE, sums, 6, MPI_DOUBLE, MPI_SUM, comm);
    MPI_Allreduce(MPI_IN_PLACE, maxima, 2, MPI_DOUBLE, MPI_MAX, comm);
    const double n = rec.nranks();
    return {sums[0] / n, maxima[0], sums[1] / n, maxima[1],
            sums[2],     sums[3],   sums[4] / n, sums[5] / n};
}

// --comm-report: OUT/comm_matrix.csv, one row per (rank, peer, kind of traffic) with any traffic:
// messages and bytes sent and received over the `steps` steps of this run, and the bytes sent
// per step. Every rank's rows go to rank 0 (one gather at the end of the run), which writes.
inline void write_comm_matrix(const std::filesystem::path& path, const CommRecord& rec,
                              double steps, MPI_Comm comm) {
    constexpr int kPer = 7; // rank, peer, kind, sent messages, bytes, received messages, bytes
    int me = 0, np = 1;
    MPI_Comm_rank(comm, &me);
    MPI_Comm_size(comm, &np);
    std::vector<double> mine;
    for (int p = 0; p < rec.nranks(); ++p)
        for (int t = 0; t < kNumTraffic; ++t) {
            const MessageCount s = rec.sent_to(p, Traffic(t)), r = rec.received_from(p, Traffic(t));
            if (s.messages + r.messages == 0) continue;
            mine.insert(mine.end(), {double(me), double(p), double(t), double(s.messages),
                                     double(s.bytes), double(r.messages), double(r.bytes)});
        }
    int count = int(mine.size());
    const auto ranks = static_cast<std::size_t>(np);
    std::vector<int> counts(ranks), offsets(ranks + 1, 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
    for (std::size_t r = 0; r < ranks; ++r) offsets[r + 1] = offsets[r] + counts[r];
    std::vector<double> all(me == 0 ? std::size_t(offsets.back()) : 0);
    MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                MPI_DOUBLE, 0, comm);
    if (me != 0) return;
    std::ofstream out(path);
    out << "rank,peer,traffic,sent_messages,sent_bytes,received_messages,received_bytes,"
           "sent_bytes_per_step\n";
    for (std::size_t k = 0; k < all.size(); k += kPer) {
        const double* v = &all[k];
        char per_step[32];
        std::snprintf(per_step, sizeof per_step, "%.6e", steps > 0 ? v[4] / steps : 0.0);
        out << std::uint64_t(v[0]) << "," << std::uint64_t(v[1]) << ","
            << kTrafficNames[std::size_t(v[2])] << "," << std::uint64_t(v[3]) << ","
            << std::uint64_t(v[4]) << "," << std::uint64_t(v[5]) << "," << std::uint64_t(v[6])
            << "," << per_step << "\n";
    }
    out.flush();
    if (!out) throw Error("cannot write " + path.string(), 3);
}

} // namespace exasph
