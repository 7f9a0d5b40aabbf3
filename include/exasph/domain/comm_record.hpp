#pragma once
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "exasph/util/mpi.hpp"
#include "exasph/util/timer.hpp"

namespace exasph {

// The kinds of point-to-point traffic: halo exchanges (with their counts and, with block time
// steps, the limiter's returns), particle migration and the gravity tree's remote sources.
enum class Traffic : int { halo, migration, gravity };
inline constexpr int kNumTraffic = 3;
inline constexpr std::array<std::string_view, kNumTraffic> kTrafficNames = {"halo", "migration",
                                                                            "gravity"};

struct MessageCount {
    std::uint64_t messages = 0, bytes = 0;
};

// What this rank sent to and received from every other rank, by kind, summed since the run
// started here (issue 23: the paper's communication matrix; --comm-report writes it). Recorded
// where the messages are posted, so the sum over a matrix's row is what the rank really sent.
class CommRecord {
  public:
    explicit CommRecord(int nranks = 0)
        : sent_(std::size_t(nranks)), received_(std::size_t(nranks)) {}

    void sent(int peer, Traffic t, std::uint64_t bytes) { add(sent_, peer, t, bytes); }
    void received(int peer, Traffic t, std::uint64_t bytes) { add(received_, peer, t, bytes); }
    const MessageCount& sent_to(int peer, Traffic t) const {
        return sent_[std::size_t(peer)][std::size_t(t)];
    }
    const MessageCount& received_from(int peer, Traffic t) const {
        return received_[std::size_t(peer)][std::size_t(t)];
    }
    int nranks() const { return int(sent_.size()); }

    // Seconds this rank has spent blocked in MPI (waits, probes, collectives) since the run
    // started here: a step's wall time less this is its compute time (the per-rank imbalance of
    // the diagnostics, issue 23).
    void waited(double seconds) { wait_seconds_ += seconds; }
    double wait_seconds() const { return wait_seconds_; }
    // The halo exchanges of the SPH passes (Domain::exchange_halos, post_halos, finish_halos):
    // seconds spent in them (packing, posting, waiting, unpacking) and seconds a posted exchange
    // was in flight while the rank computed (issue 23's overlap).
    void halo_time(double exposed, double behind_compute) {
        halo_exposed_ += exposed;
        halo_behind_compute_ += behind_compute;
    }
    double halo_exposed_seconds() const { return halo_exposed_; }
    double halo_behind_compute_seconds() const { return halo_behind_compute_; }
    // The same since the step began (the domain's count_particles() marks it).
    void start_step() { step_start_ = wait_seconds_; }
    double waited_in_step() const { return wait_seconds_ - step_start_; }

    // The ranks this one exchanged traffic of kind t with (either direction).
    int peers(Traffic t) const {
        int n = 0;
        for (std::size_t r = 0; r < sent_.size(); ++r)
            n += sent_[r][std::size_t(t)].messages + received_[r][std::size_t(t)].messages > 0;
        return n;
    }

  private:
    using Row = std::array<MessageCount, kNumTraffic>;
    static void add(std::vector<Row>& m, int peer, Traffic t, std::uint64_t bytes) {
        MessageCount& c = m[std::size_t(peer)][std::size_t(t)];
        ++c.messages;
        c.bytes += bytes;
    }

    std::vector<Row> sent_, received_;
    double wait_seconds_ = 0, step_start_ = 0;
    double halo_exposed_ = 0, halo_behind_compute_ = 0;
};

// MPI_Waitall, its time charged to the record's waiting.
inline void wait_all(std::vector<MPI_Request>& reqs, CommRecord& rec) {
    const double t0 = wall_seconds();
    MPI_Waitall(int(reqs.size()), reqs.data(), MPI_STATUSES_IGNORE);
    rec.waited(wall_seconds() - t0);
}

} // namespace exasph
