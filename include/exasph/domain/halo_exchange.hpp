#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/domain/comm_record.hpp"
#include "exasph/domain/message_tag.hpp"
#include "exasph/domain/particle_exchange.hpp"
#include "exasph/util/field_memory.hpp"

namespace exasph {

// Who exchanges halos with whom, and which particles. Halo particles are stored after the owned
// ones, grouped by partner rank in ascending order, each group in the sender's (SFC) order.
struct HaloPlan {
    std::vector<int> partners;                    // ascending ranks
    std::vector<std::vector<std::uint32_t>> send; // per partner: owned indices sent there
    std::vector<std::uint64_t> recv_count;        // per partner
    std::vector<std::uint64_t> recv_offset;       // per partner, relative to the first halo
    std::uint64_t n_halo = 0;
};

// Learns how many halos each partner sends (point-to-point with partners only).
inline void exchange_halo_counts(HaloPlan& plan, MPI_Comm comm, MessageTag tag, CommRecord& rec) {
    const std::size_t np = plan.partners.size();
    std::vector<std::uint64_t> send_count(np);
    plan.recv_count.assign(np, 0);
    std::vector<MPI_Request> reqs(2 * np);
    for (std::size_t k = 0; k < np; ++k) {
        send_count[k] = plan.send[k].size();
        MPI_Irecv(&plan.recv_count[k], 1, MPI_UINT64_T, plan.partners[k], mpi_tag(tag), comm,
                  &reqs[k]);
        MPI_Isend(&send_count[k], 1, MPI_UINT64_T, plan.partners[k], mpi_tag(tag), comm,
                  &reqs[np + k]);
        rec.received(plan.partners[k], Traffic::halo, sizeof(std::uint64_t));
        rec.sent(plan.partners[k], Traffic::halo, sizeof(std::uint64_t));
    }
    wait_all(reqs, rec);
    plan.recv_offset.resize(np);
    plan.n_halo = 0;
    for (std::size_t k = 0; k < np; ++k) {
        plan.recv_offset[k] = plan.n_halo;
        plan.n_halo += plan.recv_count[k];
    }
}

// A halo exchange in flight (post_halo_fields): its buffers and requests. Kept between
// exchanges, the buffers keep their memory: a fresh 1 MB buffer costs ~1-7 ms of page faults here,
// more than packing and sending it.
struct PostedHalos {
    FieldSelection sel;
    std::vector<std::vector<double>> recv, send;
    std::vector<MPI_Request> reqs;
    double posted_at = 0; // wall seconds
};

// Resizes a kept buffer, with a quarter more room when it must grow: halo counts drift from step
// to step, and each regrowth copies and touches fresh pages.
inline void grow(std::vector<double>& buf, std::size_t n) {
    if (n > buf.capacity()) buf.reserve(n + n / 4);
    buf.resize(n);
}

// Packs the selected fields of the planned particles for every partner and posts the sends and
// the receives of the partners' halos (MPI_Isend / MPI_Irecv, partners only) in x; returns at
// once.
template <class T>
void post_halo_fields(const ParticleSet<T>& ps, const HaloPlan& plan, const FieldSelection& sel,
                      MPI_Comm comm, MessageTag tag, CommRecord& rec, PostedHalos& x) {
    const std::size_t np = plan.partners.size();
    const std::size_t per = sel.doubles_per_particle();
    x.sel = sel;
    x.recv.resize(np);
    x.send.resize(np);
    x.reqs.clear();
    for (std::size_t k = 0; k < np; ++k) {
        if (plan.recv_count[k] == 0) continue;
        grow(x.recv[k], plan.recv_count[k] * per);
        x.reqs.emplace_back();
        MPI_Irecv(x.recv[k].data(), int(x.recv[k].size()), MPI_DOUBLE, plan.partners[k],
                  mpi_tag(tag), comm, &x.reqs.back());
        rec.received(plan.partners[k], Traffic::halo, x.recv[k].size() * sizeof(double));
    }
    for (std::size_t k = 0; k < np; ++k) {
        if (plan.send[k].empty()) continue;
        grow(x.send[k], plan.send[k].size() * per);
        pack_particles(ps, plan.send[k].data(), plan.send[k].size(), sel, x.send[k].data());
        x.reqs.emplace_back();
        MPI_Isend(x.send[k].data(), int(x.send[k].size()), MPI_DOUBLE, plan.partners[k],
                  mpi_tag(tag), comm, &x.reqs.back());
        rec.sent(plan.partners[k], Traffic::halo, x.send[k].size() * sizeof(double));
    }
    x.posted_at = wall_seconds();
}

// Lets MPI move a posted exchange along (it progresses only inside MPI calls: without this, a
// large message waits for both sides to reach their wait).
inline void progress_halo_fields(PostedHalos& x) {
    int done = 0;
    MPI_Testall(int(x.reqs.size()), x.reqs.data(), &done, MPI_STATUSES_IGNORE);
}

// Waits for a posted exchange and unpacks the halos into [n_owned, n_owned + n_halo).
template <class T>
void finish_halo_fields(ParticleSet<T>& ps, std::size_t n_owned, const HaloPlan& plan,
                        PostedHalos& x, CommRecord& rec) {
    wait_all(x.reqs, rec);
    for (std::size_t k = 0; k < plan.partners.size(); ++k)
        if (plan.recv_count[k] > 0)
            unpack_particles(ps, n_owned + plan.recv_offset[k], plan.recv_count[k], x.sel,
                             x.recv[k].data());
}

// Both at once: the halos of the selected fields, from owners to their copies.
template <class T>
void exchange_halo_fields(ParticleSet<T>& ps, std::size_t n_owned, const HaloPlan& plan,
                          const FieldSelection& sel, MPI_Comm comm, MessageTag tag,
                          CommRecord& rec) {
    PostedHalos x;
    post_halo_fields(ps, plan, sel, comm, tag, rec, x);
    finish_halo_fields(ps, n_owned, plan, x, rec);
}

// The reverse of a halo exchange: every halo's value in v[n_owned, n_owned + n_halo) goes back
// to its owner, which keeps the largest of its own and those that come back (a particle may be a
// halo on several ranks). Block time steps: the limiter's bound on a neighbour's rung.
inline void return_halo_max(FieldArray<int>& v, std::size_t n_owned, const HaloPlan& plan,
                            MPI_Comm comm, MessageTag tag, CommRecord& rec) {
    const std::size_t np = plan.partners.size();
    std::vector<std::vector<int>> recv(np);
    std::vector<MPI_Request> reqs;
    reqs.reserve(2 * np);
    for (std::size_t k = 0; k < np; ++k) {
        if (plan.send[k].empty()) continue;
        recv[k].resize(plan.send[k].size());
        reqs.emplace_back();
        MPI_Irecv(recv[k].data(), int(recv[k].size()), MPI_INT, plan.partners[k], mpi_tag(tag),
                  comm, &reqs.back());
        rec.received(plan.partners[k], Traffic::halo, recv[k].size() * sizeof(int));
    }
    for (std::size_t k = 0; k < np; ++k) {
        if (plan.recv_count[k] == 0) continue;
        reqs.emplace_back();
        MPI_Isend(v.data() + n_owned + plan.recv_offset[k], int(plan.recv_count[k]), MPI_INT,
                  plan.partners[k], mpi_tag(tag), comm, &reqs.back());
        rec.sent(plan.partners[k], Traffic::halo, plan.recv_count[k] * sizeof(int));
    }
    wait_all(reqs, rec);
    for (std::size_t k = 0; k < np; ++k)
        for (std::size_t j = 0; j < recv[k].size(); ++j) {
            int& own = v[plan.send[k][j]];
            own = std::max(own, recv[k][j]);
        }
}

} // namespace exasph
