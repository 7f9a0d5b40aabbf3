#pragma once
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <mpi.h>

#include "exasph/cases/initial_h.hpp"
#include "exasph/cases/unit_cube_points.hpp"
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

// A periodic glass (SPEC 9): side^3 random points in the unit box relaxed with SPH pressure
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
    cfg.on_sdc = "off"; // reset_to_rest changes the state between steps on purpose
    Simulation<double> sim(cfg, std::move(ic), comm);
    GlassResult res;
    for (res.steps = 1; res.steps <= gp.max_steps; ++res.steps) {
        sim.step();
        sim.reset_to_rest(kU);
        res.scatter = sim.density_scatter();
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

// Where glass blocks are cached: $EXASPH_GLASS_DIR, else $XDG_CACHE_HOME/exasph, else
// ~/.cache/exasph, else the working directory.
inline std::filesystem::path glass_cache_dir() {
    if (const char* d = std::getenv("EXASPH_GLASS_DIR")) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME")) return std::filesystem::path(d) / "exasph";
    if (const char* d = std::getenv("HOME")) return std::filesystem::path(d) / ".cache" / "exasph";
    return ".";
}

// The glass block of block_side^3 points (positions in [0, 1)^3), from the cache or made now
// (all ranks together) and cached.
inline std::vector<double> glass_block(std::uint64_t block_side, double ng0, MPI_Comm comm,
                                       std::ostream* log) {
    const auto dir = glass_cache_dir();
    const auto path =
        (dir / ("glass_" + std::to_string(block_side) + "_ng" + std::to_string(int(ng0)) + ".h5"))
            .string();
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    int exists = rank == 0 ? std::filesystem::exists(path) : 0;
    MPI_Bcast(&exists, 1, MPI_INT, 0, comm);
    if (!exists) {
        GlassParams gp;
        gp.side = int(block_side);
        gp.ng0 = ng0;
        auto g = make_glass(gp, comm);
        std::error_code ec;
        if (rank == 0) std::filesystem::create_directories(dir, ec);
        write_glass(path, g, ng0, comm);
        if (log && rank == 0)
            *log << "glass " << path << ": " << block_side << "^3 particles, density scatter "
                 << g.scatter << " after " << g.steps << " relaxation steps (cached)\n";
    }
    // Every rank reads the whole (small) block.
    h5::File file = h5::File::open_read(path, MPI_COMM_SELF);
    h5::Group root(file, "/", false);
    ParticleSet<double> ps;
    read_particle_fields(root, ps, {Field::x, Field::y, Field::z}, {}, false, MPI_COMM_SELF);
    if (ps.size() != block_side * block_side * block_side)
        throw input_error(path + ": cached glass has " + std::to_string(ps.size()) +
                              " particles, expected " + std::to_string(block_side) + "^3",
                          true);
    std::vector<double> out(3 * ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) { // in id order, whichever ranks wrote the file
        const std::uint64_t id = ps.id[i];
        if (id >= ps.size()) throw input_error(path + ": glass ids must be 0 .. N-1", true);
        out[3 * id] = ps[Field::x][i] + 0.5;
        out[3 * id + 1] = ps[Field::y][i] + 0.5;
        out[3 * id + 2] = ps[Field::z][i] + 0.5;
    }
    return out;
}

} // namespace exasph
