#pragma once
#include <cstdint>
#include <vector>

#include "exasph/util/mpi.hpp"

namespace exasph::testref {

// Test-only: gathers every rank's values on every rank, in rank order.
template <class V>
std::vector<V> allgather(const std::vector<V>& local, MPI_Comm comm) {
    int nranks = 1;
    MPI_Comm_size(comm, &nranks);
    int n = int(local.size() * sizeof(V));
    std::vector<int> counts(nranks), displs(nranks, 0);
    MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    for (int r = 1; r < nranks; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    std::vector<V> all(std::size_t(displs.back() + counts.back()) / sizeof(V));
    MPI_Allgatherv(local.data(), n, MPI_BYTE, all.data(), counts.data(), displs.data(), MPI_BYTE,
                   comm);
    return all;
}

} // namespace exasph::testref
