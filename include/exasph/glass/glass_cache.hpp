#pragma once
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/glass/glass.hpp"

namespace exasph {

// Where glass blocks are cached: $EXASPH_GLASS_DIR, else $XDG_CACHE_HOME/exasph, else
// ~/.cache/exasph, else the working directory.
inline std::filesystem::path glass_cache_dir() {
    if (const char* d = std::getenv("EXASPH_GLASS_DIR")) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME")) return std::filesystem::path(d) / "exasph";
    if (const char* d = std::getenv("HOME")) return std::filesystem::path(d) / ".cache" / "exasph";
    return ".";
}

// A glass block's points in id order, shifted to [0, 1)^3 (`what` names it in errors).
inline std::vector<double> block_points(const ParticleSet<double>& ps, std::uint64_t block_side,
                                        const std::string& what) {
    if (ps.size() != block_side * block_side * block_side)
        throw input_error(what + ": cached glass has " + std::to_string(ps.size()) +
                              " particles, expected " + std::to_string(block_side) + "^3",
                          true);
    std::vector<double> out(3 * ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) { // in id order, whichever ranks wrote the file
        const std::uint64_t id = ps.id[i];
        if (id >= ps.size()) throw input_error(what + ": glass ids must be 0 .. N-1", true);
        out[3 * id] = ps[Field::x][i] + 0.5;
        out[3 * id + 1] = ps[Field::y][i] + 0.5;
        out[3 * id + 2] = ps[Field::z][i] + 0.5;
    }
    return out;
}

inline GlassResult make_glass_block(std::uint64_t block_side, double ng0, MPI_Comm comm,
                                    std::ostream* log, const std::string& where) {
    GlassParams gp;
    gp.side = int(block_side);
    gp.ng0 = ng0;
    auto g = make_glass(gp, comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (log && rank == 0)
        *log << "glass " << where << ": " << block_side << "^3 particles, density scatter "
             << g.scatter << " after " << g.steps << " relaxation steps\n";
    return g;
}

// The glass block of block_side^3 points (positions in [0, 1)^3), from the cache or made now
// (all ranks together) and cached. A build without HDF5 has no cache: its one rank makes the
// block in memory every run.
inline std::vector<double> glass_block(std::uint64_t block_side, double ng0, MPI_Comm comm,
                                       std::ostream* log) {
#if !EXASPH_HAVE_HDF5
    auto g = make_glass_block(block_side, ng0, comm, log, "(not cached: no HDF5 in this build)");
    return block_points(g.particles, block_side, "glass block");
#else
    const auto dir = glass_cache_dir();
    const auto path =
        (dir / ("glass_" + std::to_string(block_side) + "_ng" + std::to_string(int(ng0)) + ".h5"))
            .string();
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    int exists = rank == 0 ? std::filesystem::exists(path) : 0;
    MPI_Bcast(&exists, 1, MPI_INT, 0, comm);
    if (!exists) {
        auto g = make_glass_block(block_side, ng0, comm, log, path + " (cached)");
        std::error_code ec;
        if (rank == 0) std::filesystem::create_directories(dir, ec);
        write_glass(path, g, ng0, comm);
    }
    // Every rank reads the whole (small) block.
    h5::File file = h5::File::open_read(path, MPI_COMM_SELF);
    h5::Group root(file, "/", false);
    ParticleSet<double> ps;
    read_particle_fields(root, ps, {Field::x, Field::y, Field::z}, {}, false, MPI_COMM_SELF);
    return block_points(ps, block_side, path);
#endif
}

} // namespace exasph
