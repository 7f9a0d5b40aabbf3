#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "exasph/util/mpi.hpp"
#include <omp.h>

#include "exasph/run/setup.hpp"
#include "exasph/sim/simulation.hpp"
#include "mpi_gather.hpp"

namespace exasph::testref {

struct ParticleState {
    std::uint64_t id;
    double rho, vx, vy, vz, u;
    double ax, ay, az, phi; // of the last step (hydro + gravity), potential 0 without gravity
};

template <class Sim>
std::vector<ParticleState> owned_state(const Sim& sim) {
    const auto& ps = sim.particles();
    std::vector<ParticleState> out(sim.n_owned());
    const bool gravity = ps.enabled(Field::phi);
    for (std::size_t i = 0; i < out.size(); ++i)
        out[i] = {ps.id[i],         ps.value(Field::rho, i),
                  ps[Field::vx][i], ps[Field::vy][i],
                  ps[Field::vz][i], ps[Field::u][i],
                  ps[Field::ax][i], ps[Field::ay][i],
                  ps[Field::az][i], gravity ? ps[Field::phi][i] : 0.0};
    return out;
}

// This rank and the rank count of MPI_COMM_WORLD; the distributed runs of the tests use one
// OpenMP thread per rank.
inline std::pair<int, int> one_thread_per_rank() {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &nranks);
    omp_set_num_threads(1);
    return {rank, nranks};
}

// The state after `steps` steps of a one-rank run (rank 0, MPI_COMM_SELF, `threads` threads).
struct OneRankReference {
    std::map<std::uint64_t, ParticleState> state;
    double etot = 0, lz = 0;
};

inline OneRankReference one_rank_reference(const Config& cfg, int steps, int threads) {
    OneRankReference ref;
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) {
        omp_set_num_threads(threads);
        Simulation<double> sim(cfg, make_case(cfg, MPI_COMM_SELF), MPI_COMM_SELF);
        for (int s = 0; s < steps; ++s) sim.step();
        for (const auto& st : owned_state(sim)) ref.state[st.id] = st;
        ref.etot = sim.diagnostics().etot;
        ref.lz = sim.diagnostics().angular_momentum[2];
    }
    MPI_Bcast(&ref.etot, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    MPI_Bcast(&ref.lz, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    return ref;
}

// Worst per-particle differences of a distributed state against the reference (rank 0 only):
// rho relative to itself, v relative to the largest speed, u relative to the largest u.
struct Differences {
    double rho = 0, v = 0, u = 0, a = 0, phi = 0; // a relative to the largest |a| component
};

inline Differences compare_to_reference(const std::vector<ParticleState>& all,
                                        const OneRankReference& ref) {
    double vmax = 0, umax = 0, amax = 0, phimax = 0;
    for (const auto& [id, st] : ref.state) {
        vmax = std::max({vmax, std::abs(st.vx), std::abs(st.vy), std::abs(st.vz)});
        umax = std::max(umax, std::abs(st.u));
        amax = std::max({amax, std::abs(st.ax), std::abs(st.ay), std::abs(st.az)});
        phimax = std::max(phimax, std::abs(st.phi));
    }
    Differences d;
    for (const auto& st : all) {
        const ParticleState& r = ref.state.at(st.id);
        d.rho = std::max(d.rho, std::abs(st.rho - r.rho) / r.rho);
        d.v = std::max({d.v, std::abs(st.vx - r.vx) / vmax, std::abs(st.vy - r.vy) / vmax,
                        std::abs(st.vz - r.vz) / vmax});
        d.u = std::max(d.u, std::abs(st.u - r.u) / umax);
        d.a = std::max({d.a, std::abs(st.ax - r.ax) / amax, std::abs(st.ay - r.ay) / amax,
                        std::abs(st.az - r.az) / amax});
        if (phimax > 0) d.phi = std::max(d.phi, std::abs(st.phi - r.phi) / phimax);
    }
    return d;
}

} // namespace exasph::testref
