#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/io/gadget_layout.hpp"
#include "exasph/io/h5_file.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// This rank's offset in a rank-ordered concatenation, and the global total (output-time
// collectives, not on the step's hot path).
inline std::uint64_t global_offset(std::uint64_t n_local, MPI_Comm comm, std::uint64_t& n_global) {
    std::uint64_t offset = 0;
    MPI_Exscan(&n_local, &offset, 1, MPI_UINT64_T, MPI_SUM, comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) offset = 0;
    MPI_Allreduce(&n_local, &n_global, 1, MPI_UINT64_T, MPI_SUM, comm);
    return offset;
}

// Writes the given fields (and the ids) of particles [0, n_local) as 1-D datasets named after the
// fields; every rank writes its own part (collective, no gather). Returns the global count.
template <class T>
std::uint64_t write_particle_fields(const h5::Group& g, const ParticleSet<T>& ps,
                                    std::size_t n_local, const std::vector<Field>& fields,
                                    bool with_id, MPI_Comm comm) {
    std::uint64_t n_global = 0;
    const std::uint64_t offset = global_offset(n_local, comm, n_global);
    std::vector<double> buf(n_local);
    for (Field f : fields) {
        for (std::size_t i = 0; i < n_local; ++i) buf[i] = ps.value(f, i);
        h5::write_doubles(g, std::string(field_info(f).name), buf.data(), n_local, offset,
                          n_global);
    }
    if (with_id) h5::write_u64(g, "id", ps.id.data(), n_local, offset, n_global);
    return n_global;
}

// Writes the GADGET-layout datasets `sets` (io/gadget_layout.hpp: N x 3 for vectors, stored
// times their scale) and the ids (ParticleIDs) of particles [0, n_local); every rank writes its
// own rows (collective, no gather). Returns the global count.
template <class T>
std::uint64_t write_gadget_datasets(const h5::Group& gas, const ParticleSet<T>& ps,
                                    std::size_t n_local, const std::vector<GadgetDataset>& sets,
                                    MPI_Comm comm) {
    std::uint64_t n_global = 0;
    const std::uint64_t offset = global_offset(n_local, comm, n_global);
    std::vector<double> buf;
    for (const GadgetDataset& d : sets) {
        const auto width = std::size_t(d.width);
        buf.resize(width * n_local);
        for (std::size_t i = 0; i < n_local; ++i)
            for (std::size_t c = 0; c < width; ++c)
                buf[i * width + c] = ps.value(component(d.first, int(c)), i) * d.scale;
        if (width == 1)
            h5::write_doubles(gas, d.name, buf.data(), n_local, offset, n_global);
        else
            h5::write_double_rows(gas, d.name, buf.data(), n_local, width, offset, n_global);
    }
    h5::write_u64(gas, kGadgetIds, ps.id.data(), n_local, offset, n_global);
    return n_global;
}

// Rank r of P reads elements [N r / P, N (r+1) / P) of each dataset: any rank count reads any
// file. `required` fields must exist; `optional` ones default to zero; ids default to the
// position in the file. Every dataset must be 1-D, floating point (ids: integer), of length N.
template <class T>
std::uint64_t
read_particle_fields(const h5::Group& g, ParticleSet<T>& ps, const std::vector<Field>& required,
                     const std::vector<Field>& optional, bool require_id, MPI_Comm comm) {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &nranks);
    const std::string first = std::string(field_info(required.front()).name);
    const std::uint64_t n = h5::dataset_length(g, first);
    auto check_length = [&](const std::string& name, bool integer) {
        std::uint64_t len = h5::dataset_length(g, name, integer);
        if (len != n)
            throw input_error(g.file().path() + ": dataset " + name + " has " +
                              std::to_string(len) + " elements, " + first + " has " +
                              std::to_string(n));
    };
    const std::uint64_t lo = n * std::uint64_t(rank) / std::uint64_t(nranks);
    const std::uint64_t hi = n * std::uint64_t(rank + 1) / std::uint64_t(nranks);
    ps.resize(hi - lo);
    auto read_into = [&](Field f) {
        auto v = h5::read_doubles(g, std::string(field_info(f).name), lo, hi - lo);
        for (std::size_t i = 0; i < v.size(); ++i) ps.set_value(f, i, v[i]);
    };
    for (Field f : required) {
        check_length(std::string(field_info(f).name), false);
        read_into(f);
    }
    for (Field f : optional) {
        if (!h5::has_link(g, std::string(field_info(f).name))) continue;
        check_length(std::string(field_info(f).name), false);
        ps.enable(f);
        read_into(f);
    }
    if (h5::has_link(g, "id")) {
        check_length("id", true);
        const std::vector<std::uint64_t> ids = h5::read_u64(g, "id", lo, hi - lo);
        ps.id.assign(ids.begin(), ids.end());
    } else if (require_id) {
        h5::dataset_length(g, "id", true); // throws: missing dataset
    } else {
        for (std::uint64_t i = lo; i < hi; ++i) ps.id[i - lo] = i;
    }
    return n;
}

// Checks that the state of [0, n) is finite, m > 0 and h > 0, and that positions lie inside the
// box on periodic axes; throws an input error naming the file, field and particle id.
template <class T>
void validate_input_particles(const ParticleSet<T>& ps, const std::string& path,
                              const Box<T>& box) {
    for (const auto& info : kFieldTable) {
        if (!(info.roles & kState) || !ps.enabled(info.field)) continue;
        const auto& f = ps[info.field];
        for (std::size_t i = 0; i < ps.size(); ++i)
            if (!std::isfinite(f[i]))
                throw input_error(path + ": field " + std::string(info.name) + " of particle id " +
                                  std::to_string(ps.id[i]) + " is not finite");
    }
    for (Field fld : {Field::m, Field::h}) {
        const auto& f = ps[fld];
        for (std::size_t i = 0; i < ps.size(); ++i)
            if (!(f[i] > 0))
                throw input_error(path + ": field " + std::string(field_info(fld).name) +
                                  " of particle id " + std::to_string(ps.id[i]) +
                                  " must be positive, is " + std::to_string(f[i]));
    }
    for (int d = 0; d < 3; ++d) {
        if (!box.periodic[d]) continue;
        const auto& f = ps[component(Field::x, d)];
        for (std::size_t i = 0; i < ps.size(); ++i)
            if (!(f[i] >= box.lo[d] && f[i] < box.hi[d]))
                throw input_error(path + ": particle id " + std::to_string(ps.id[i]) + " has " +
                                  std::string(1, "xyz"[d]) + " = " + std::to_string(f[i]) +
                                  " outside the periodic box [" + std::to_string(box.lo[d]) + ", " +
                                  std::to_string(box.hi[d]) + ")");
    }
}

} // namespace exasph

namespace exasph {

// Runs a local check on every rank and makes its failure collective: when any rank throws Error,
// every rank throws the first failing rank's message (start-up/output time only: two
// collectives). Lets one bad particle in an input file end a parallel run cleanly.
template <class F>
void collective_check(MPI_Comm comm, F&& check) {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &nranks);
    std::string msg;
    int code = 0;
    try {
        check();
    } catch (const Error& e) {
        msg = e.what();
        code = e.exit_code();
    }
    int first = msg.empty() ? nranks : rank;
    MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, comm);
    if (first == nranks) return;
    int len = int(msg.size());
    int buf[2] = {code, len};
    MPI_Bcast(buf, 2, MPI_INT, first, comm);
    msg.resize(std::size_t(buf[1]));
    MPI_Bcast(msg.data(), buf[1], MPI_CHAR, first, comm);
    throw Error(msg, buf[0], true);
}

} // namespace exasph
