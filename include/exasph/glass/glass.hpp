#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/cases/initial_h.hpp"
#include "exasph/cases/unit_cube_points.hpp"
#include "exasph/config/config.hpp"
#include "exasph/io/atomic_output.hpp"
#include "exasph/io/particle_io.hpp"
#include "exasph/sim/simulation.hpp"

namespace exasph {

struct GlassParams {
    int side = 20;
    double ng0 = 100;
    double tolerance = 0.01; // target relative density scatter
    int max_steps = 3000;
    std::uint64_t seed = 1;
};

struct GlassResult {
    ParticleSet<double> particles; // this rank's owned particles, positions in [-0.5, 0.5)^3
    double scatter = 0;            // relative standard deviation of the density
    std::int64_t steps = 0;
};

// Damped SPH: after a step, every particle is stopped where it is and its internal energy
// restored, so that the next step moves particles only along the pressure forces.
template <class T>
void reset_to_rest(ParticleSet<T>& ps, std::size_t n, T u) {
    for (std::size_t i = 0; i < n; ++i) {
        ps[Field::vx][i] = ps[Field::vy][i] = ps[Field::vz][i] = T(0);
        ps[Field::x_m1][i] = ps[Field::x][i];
        ps[Field::y_m1][i] = ps[Field::y][i];
        ps[Field::z_m1][i] = ps[Field::z][i];
        ps[Field::u][i] = u;
        ps[Field::du_m1][i] = T(0);
    }
}

// Relative standard deviation of the densities of the last step over all ranks of comm.
template <class T>
double density_scatter(const ParticleSet<T>& ps, std::size_t n, MPI_Comm comm) {
    double s[3] = {0, 0, double(n)};
    for (std::size_t i = 0; i < n; ++i) {
        const double rho = ps.value(Field::rho, i);
        s[0] += rho;
        s[1] += rho * rho;
    }
    MPI_Allreduce(MPI_IN_PLACE, s, 3, MPI_DOUBLE, MPI_SUM, comm);
    const double mean = s[0] / s[2];
    return std::sqrt(std::max(s[1] / s[2] - mean * mean, 0.0)) / mean;
}

// A periodic glass (physics.md §9): side^3 random points in the unit box relaxed with SPH pressure
// forces of an isothermal gas, fully damped (every particle stopped after each step), until
// the density scatter is below the tolerance. Each rank makes its share of the random points.
inline GlassResult make_glass(const GlassParams& gp, MPI_Comm comm) {
    int rank = 0, nranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &nranks);
    if (gp.side < 8) throw input_error("glass: -n must be at least 8", true);
    InitialConditions<double> ic;
    ic.name = "glass";
    ic.eos = {EosKind::ideal_gas, 5.0 / 3.0, 0.0};
    ic.box.lo = {-0.5, -0.5, -0.5};
    ic.box.hi = {0.5, 0.5, 0.5};
    ic.box.periodic = {true, true, true};
    const std::uint64_t n = std::uint64_t(gp.side) * gp.side * gp.side;
    const std::uint64_t first = n * rank / nranks, last = n * (rank + 1) / nranks;
    const double h0 = initial_smoothing_length(1.0 / gp.side, gp.ng0);
    constexpr double kU = 1.0;
    auto& ps = ic.particles;
    ps.resize(last - first);
    // Random positions as a function of (seed, id, axis) only: the same cloud on any rank count.
    auto uni = [&](std::uint64_t id, std::uint64_t axis) {
        std::uint64_t z = gp.seed * 0x9E3779B97F4A7C15ULL + id * 3 + axis + 1;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL; // splitmix64 finaliser
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        z ^= z >> 31;
        return double(z >> 11) * 0x1.0p-53 - 0.5;
    };
    for (std::size_t s = 0; s < ps.size(); ++s) {
        const std::uint64_t id = first + s;
        ps.id[s] = id;
        ps[Field::x][s] = ps[Field::x_m1][s] = uni(id, 0);
        ps[Field::y][s] = ps[Field::y_m1][s] = uni(id, 1);
        ps[Field::z][s] = ps[Field::z_m1][s] = uni(id, 2);
        ps[Field::m][s] = 1.0 / double(n);
        ps[Field::h][s] = h0;
        ps[Field::u][s] = kU;
    }
    ic.dt0 = 0.2 * h0; // a first step of the order of the Courant limit (c ~ 1)
    Config cfg;
    cfg.ng0 = gp.ng0;
    cfg.ngmax = int(gp.ng0 * 1.5);
    cfg.on_sdc = SdcPolicy::off; // reset_to_rest changes the state between steps on purpose
    Simulation<double> sim(cfg, std::move(ic), comm);
    GlassResult res;
    for (res.steps = 1; res.steps <= gp.max_steps; ++res.steps) {
        sim.step();
        reset_to_rest(sim.particles_to_modify(), sim.n_owned(), kU);
        res.scatter = density_scatter(sim.particles(), sim.n_owned(), comm);
        if (res.scatter < gp.tolerance) break;
    }
    if (res.scatter >= gp.tolerance)
        throw Error("glass: density scatter " + std::to_string(res.scatter) + " after " +
                        std::to_string(gp.max_steps) + " steps (tolerance " +
                        std::to_string(gp.tolerance) + ")",
                    1, true);
    res.particles = sim.particles();
    res.particles.resize(sim.n_owned());
    return res;
}

// Writes a glass in the initial-conditions layout (docs/file-format.md), atomically.
inline void write_glass(const std::string& path, const GlassResult& g, double ng0, MPI_Comm comm) {
    try {
        h5::File file = h5::File::create(temporary_name(path), comm);
        h5::Group root(file, "/", false);
        h5::write_attribute(root, "box_lo", std::vector<double>{-0.5, -0.5, -0.5});
        h5::write_attribute(root, "box_hi", std::vector<double>{0.5, 0.5, 0.5});
        h5::write_attribute(root, "periodic", std::vector<std::int64_t>{1, 1, 1});
        h5::write_attribute(root, "density_scatter", g.scatter);
        h5::write_attribute(root, "relaxation_steps", std::int64_t(g.steps));
        h5::write_attribute(root, "ng0", ng0);
        write_particle_fields(root, g.particles, g.particles.size(),
                              {Field::x, Field::y, Field::z, Field::m, Field::h}, true, comm);
    } catch (...) {
        discard_output(path, comm);
        throw;
    }
    commit_output(path, comm);
}

} // namespace exasph
