#pragma once
#include <cstdint>

#include "exasph/util/mpi.hpp"

#include "exasph/config/config.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"

namespace exasph {

// The potential energy of the first n particles of ps where they are now, before any step has
// computed forces: a throw-away domain and gravity pass over a copy of the particles (start-up
// only; the run's own domain is left as it is, so restarts stay exact).
template <class T>
double initial_potential_energy(const ParticleSet<T>& ps, std::size_t n, const Box<T>& box0,
                                const Config& cfg, GravitySolver<T>& gravity, MPI_Comm comm) {
    ParticleSet<T> copy = ps;
    copy.resize(n);
    Box<T> box = box0;
    Domain<T> dom(comm, std::uint32_t(cfg.global_bucket), std::uint32_t(cfg.leaf_size), cfg.curve);
    dom.init(copy, box);
    dom.sync(copy, box);
    gravity.compute(copy, dom.n_owned(), dom.assignment(), box, dom.curve(), dom.collectives());
    double e = 0;
    for (std::size_t i = 0; i < dom.n_owned(); ++i)
        e += 0.5 * double(copy[Field::m][i]) * copy[Field::phi][i];
    MPI_Allreduce(MPI_IN_PLACE, &e, 1, MPI_DOUBLE, MPI_SUM, comm);
    return e;
}

} // namespace exasph
