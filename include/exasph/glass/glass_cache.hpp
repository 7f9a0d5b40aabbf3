#pragma once
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/glass/glass.hpp"
#include "exasph/glass/glass_cache_file.hpp"

namespace exasph {

// Where glass blocks are cached: $EXASPH_GLASS_DIR, else $XDG_CACHE_HOME/exasph, else
// ~/.cache/exasph, else the working directory.
inline std::filesystem::path glass_cache_dir() {
    if (const char* d = std::getenv("EXASPH_GLASS_DIR")) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME")) return std::filesystem::path(d) / "exasph";
    if (const char* d = std::getenv("HOME")) return std::filesystem::path(d) / ".cache" / "exasph";
    return ".";
}

// The whole block's points in id order on every rank, shifted to [0, 1)^3: each rank puts its
// own points in their id's slot of a zero array and the arrays are summed over the ranks (one
// non-zero term per slot, so the sum is exact).
inline std::vector<double> gathered_block_points(const ParticleSet<double>& ps,
                                                 std::uint64_t block_side, MPI_Comm comm) {
    const std::uint64_t n = block_side * block_side * block_side;
    std::uint64_t count = ps.size();
    MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_UINT64_T, MPI_SUM, comm);
    if (count != n)
        throw Error("glass block: " + std::to_string(count) + " particles, expected " +
                        std::to_string(block_side) + "^3",
                    1, true);
    std::vector<double> out(3 * n, 0.0);
    for (std::size_t i = 0; i < ps.size(); ++i) {
        const std::uint64_t id = ps.id[i];
        if (id >= n) throw Error("glass block: ids must be 0 .. N-1", 1, true);
        out[3 * id] = ps[Field::x][i] + 0.5;
        out[3 * id + 1] = ps[Field::y][i] + 0.5;
        out[3 * id + 2] = ps[Field::z][i] + 0.5;
    }
    MPI_Allreduce(MPI_IN_PLACE, out.data(), int(out.size()), MPI_DOUBLE, MPI_SUM, comm);
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

inline std::string glass_cache_path(std::uint64_t block_side, double ng0) {
    return (glass_cache_dir() /
            ("glass_" + std::to_string(block_side) + "_ng" + std::to_string(int(ng0)) + ".bin"))
        .string();
}

// The glass block of block_side^3 points (positions in [0, 1)^3), from the cache
// (glass_cache_file.hpp; rank 0 reads it and broadcasts) or made now by all ranks together and
// cached. A cache that cannot be written costs only the time to make the block again next run.
inline std::vector<double> glass_block(std::uint64_t block_side, double ng0, MPI_Comm comm,
                                       std::ostream* log) {
    const std::string path = glass_cache_path(block_side, ng0);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    std::vector<double> points(3 * block_side * block_side * block_side);
    int cached = 0;
    if (rank == 0)
        if (auto p = read_glass_cache(path, block_side, ng0)) {
            points = std::move(*p);
            cached = 1;
        }
    MPI_Bcast(&cached, 1, MPI_INT, 0, comm);
    if (cached) {
        MPI_Bcast(points.data(), int(points.size()), MPI_DOUBLE, 0, comm);
        return points;
    }
    auto g = make_glass_block(block_side, ng0, comm, log, path + " (cached)");
    points = gathered_block_points(g.particles, block_side, comm);
    if (rank == 0) {
        std::error_code ec;
        std::filesystem::create_directories(glass_cache_dir(), ec);
        if (!write_glass_cache(path, block_side, ng0, points) && log)
            *log << "glass: cannot write the cache file " << path << "; the block is made again "
                 << "next run\n";
    }
    return points;
}

} // namespace exasph
