#pragma once
#include <cmath>

#include "exasph/util/mpi.hpp"

#include "exasph/util/error.hpp"

namespace exasph {

// Young/Daly optimum checkpoint interval (first order): with checkpoint cost C and mean time
// between failures M of the whole run (both in seconds), checkpointing every sqrt(2 C M) seconds
// minimises the expected time lost to checkpoints plus recomputation after a failure.
inline double young_daly_interval(double checkpoint_seconds, double mtbf_seconds) {
    if (!(checkpoint_seconds > 0) || !(mtbf_seconds > 0))
        throw Error("checkpoint interval: cost and MTBF must be positive");
    return std::sqrt(2.0 * checkpoint_seconds * mtbf_seconds);
}

// Number of nodes (shared-memory domains) among the ranks of comm.
inline int count_nodes(MPI_Comm comm) {
    MPI_Comm node;
    MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
    int node_rank = 0;
    MPI_Comm_rank(node, &node_rank);
    MPI_Comm_free(&node);
    int leaders = node_rank == 0 ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &leaders, 1, MPI_INT, MPI_SUM, comm);
    return leaders;
}

// MTBF of a run on `nodes` nodes whose nodes fail independently with MTBF `node_mtbf_hours`.
inline double run_mtbf_seconds(double node_mtbf_hours, int nodes) {
    return node_mtbf_hours * 3600.0 / double(nodes > 0 ? nodes : 1);
}

} // namespace exasph
