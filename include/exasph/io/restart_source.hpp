#pragma once
#include <algorithm>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/io/checkpoint.hpp"

namespace exasph {

// Rank 0's list, on every rank (a shared file system may show a directory late on some nodes).
inline std::vector<std::string> broadcast_names(std::vector<std::string> names, MPI_Comm comm) {
    std::string joined;
    for (const auto& n : names) joined += n + '\n';
    int size = int(joined.size());
    MPI_Bcast(&size, 1, MPI_INT, 0, comm);
    joined.resize(std::size_t(size));
    MPI_Bcast(joined.data(), size, MPI_CHAR, 0, comm);
    names.clear();
    for (std::size_t a = 0, b; (b = joined.find('\n', a)) != std::string::npos; a = b + 1)
        names.push_back(joined.substr(a, b - a));
    return names;
}

// --restart FILE reads that checkpoint. --restart DIR reads the newest checkpoint of DIR that
// opens and verifies: a run killed while writing leaves only a temporary file (never a partial
// checkpoint under its final name), and one damaged later falls back to the one before it
// (two are kept). Each skipped file is named with the reason; cfg.restart_file becomes the file
// read. All ranks together.
template <class T>
Checkpoint<T> read_restart(Config& cfg, MPI_Comm comm, std::ostream* log) {
    if (!std::filesystem::is_directory(cfg.restart_file))
        return read_checkpoint<T>(cfg.restart_file, cfg, comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    const std::string dir = cfg.restart_file;
    const auto files = broadcast_names(
        rank == 0 ? checkpoints_newest_first(dir) : std::vector<std::string>{}, comm);
    for (const auto& path : files) {
        try {
            auto cp = read_checkpoint<T>(path, cfg, comm);
            cfg.restart_file = path;
            return cp;
        } catch (const Error& e) {
            if (log && rank == 0) *log << "restart: skipping " << e.what() << "\n";
        }
    }
    throw input_error("--restart " + dir + ": no checkpoint in this directory reads and " +
                          "verifies (checkpoint_*.h5)",
                      true);
}

} // namespace exasph
