#pragma once
#include <cstdint>
#include <cstring>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/domain/comm_record.hpp"
#include "exasph/domain/message_tag.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Which particle data a message carries: fields from the field list and optionally the
// persistent id. The domain moves what it is given and never names a physics field.
struct FieldSelection {
    std::vector<Field> fields;
    bool with_id = false;

    std::size_t doubles_per_particle() const { return fields.size() + (with_id ? 1 : 0); }
};

// Packs particles idx[0, count) field-major into buf (count * doubles_per_particle doubles).
// Values travel as double (exact for float and double fields); ids are bit-copied.
template <class T>
void pack_particles(const ParticleSet<T>& ps, const std::uint32_t* idx, std::size_t count,
                    const FieldSelection& sel, double* buf) {
    std::size_t slot = 0;
    for (Field f : sel.fields) {
        if (ps.stored_single(f)) {
            const float* src = ps.narrow(f);
            for (std::size_t k = 0; k < count; ++k) buf[slot * count + k] = double(src[idx[k]]);
        } else {
            const T* src = ps.data(f);
            for (std::size_t k = 0; k < count; ++k) buf[slot * count + k] = double(src[idx[k]]);
        }
        ++slot;
    }
    if (sel.with_id)
        for (std::size_t k = 0; k < count; ++k)
            std::memcpy(&buf[slot * count + k], &ps.id[idx[k]], sizeof(double));
}

// Writes `count` packed particles to positions [offset, offset + count) of ps.
template <class T>
void unpack_particles(ParticleSet<T>& ps, std::size_t offset, std::size_t count,
                      const FieldSelection& sel, const double* buf) {
    std::size_t slot = 0;
    for (Field f : sel.fields) {
        if (ps.stored_single(f)) {
            float* dst = ps.narrow(f);
            for (std::size_t k = 0; k < count; ++k) dst[offset + k] = float(buf[slot * count + k]);
        } else {
            T* dst = ps.data(f);
            for (std::size_t k = 0; k < count; ++k) dst[offset + k] = T(buf[slot * count + k]);
        }
        ++slot;
    }
    if (sel.with_id)
        for (std::size_t k = 0; k < count; ++k)
            std::memcpy(&ps.id[offset + k], &buf[slot * count + k], sizeof(double));
}

// Moves every particle i with dest[i] != me to rank dest[i] (point-to-point) and receives the
// particles others send here until this rank holds `expected` particles: the global tree counts
// tell every rank its new count, so no extra collective is needed to learn who sends what.
// Returns whether this rank's particles changed (some left or arrived); if not, they are
// untouched, in their old order.
template <class T>
bool migrate_particles(ParticleSet<T>& ps, const std::vector<int>& dest, int me, int nranks,
                       std::uint64_t expected, MPI_Comm comm, MessageTag tag, CommRecord& rec) {
    std::size_t leaving = 0;
#pragma omp parallel for schedule(static) reduction(+ : leaving)
    for (std::size_t i = 0; i < dest.size(); ++i) leaving += dest[i] != me;
    if (leaving == 0 && expected == dest.size()) return false; // the common case on one rank
    FieldSelection sel{ps.fields(ps.carried()), true};
    const std::size_t per = sel.doubles_per_particle();
    std::vector<std::vector<std::uint32_t>> out(nranks);
    std::vector<std::uint32_t> keep;
    for (std::uint32_t i = 0; i < dest.size(); ++i)
        (dest[i] == me ? keep : out[dest[i]]).push_back(i);

    std::vector<std::vector<double>> send_buf(nranks);
    std::vector<MPI_Request> reqs;
    for (int r = 0; r < nranks; ++r) {
        if (out[r].empty()) continue;
        send_buf[r].resize(out[r].size() * per);
        pack_particles(ps, out[r].data(), out[r].size(), sel, send_buf[r].data());
        reqs.emplace_back();
        MPI_Isend(send_buf[r].data(), int(send_buf[r].size()), MPI_DOUBLE, r, mpi_tag(tag), comm,
                  &reqs.back());
        rec.sent(r, Traffic::migration, send_buf[r].size() * sizeof(double));
    }
    const bool changed = keep.size() != dest.size() || expected != keep.size();
    if (keep.size() != dest.size()) ps.permute(keep); // an identity permutation is a plain copy
    if (expected < keep.size()) throw Error("migration: particle count bookkeeping failed");
    std::vector<double> buf;
    while (ps.size() < expected) {
        MPI_Status st;
        const double t0 = wall_seconds();
        MPI_Probe(MPI_ANY_SOURCE, mpi_tag(tag), comm, &st);
        rec.waited(wall_seconds() - t0);
        int ndoubles = 0;
        MPI_Get_count(&st, MPI_DOUBLE, &ndoubles);
        buf.resize(std::size_t(ndoubles));
        MPI_Recv(buf.data(), ndoubles, MPI_DOUBLE, st.MPI_SOURCE, mpi_tag(tag), comm,
                 MPI_STATUS_IGNORE);
        rec.received(st.MPI_SOURCE, Traffic::migration, std::uint64_t(ndoubles) * sizeof(double));
        const std::size_t count = std::size_t(ndoubles) / per;
        const std::size_t offset = ps.size();
        if (offset + count > expected)
            throw Error("migration: received more particles than expected");
        ps.resize(offset + count);
        unpack_particles(ps, offset, count, sel, buf.data());
    }
    wait_all(reqs, rec);
    return changed;
}

} // namespace exasph
