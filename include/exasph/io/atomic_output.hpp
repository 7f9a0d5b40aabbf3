#pragma once
#include <cstdio>
#include <filesystem>
#include <string>

#include "exasph/util/mpi.hpp"

#include "exasph/util/error.hpp"

namespace exasph {

// Output files are written under a temporary name and renamed when complete, so that a run
// never leaves a partial snapshot or checkpoint under a final name (DESIGN: conventions).
inline std::string temporary_name(const std::string& path) {
    return path + ".tmp";
}

// After every rank has closed the temporary file: rank 0 renames it. Collective.
inline void commit_output(const std::string& path, MPI_Comm comm) {
    MPI_Barrier(comm);
    int rank = 0, ok = 1;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) ok = std::rename(temporary_name(path).c_str(), path.c_str()) == 0;
    MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
    if (!ok) throw Error(path + ": cannot rename the completed temporary file into place", 3, true);
}

// Removes a temporary left by a failed write (rank 0; harmless when absent).
inline void discard_output(const std::string& path, MPI_Comm comm) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) {
        std::error_code ec;
        std::filesystem::remove(temporary_name(path), ec);
    }
}

} // namespace exasph
