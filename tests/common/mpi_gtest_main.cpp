// GoogleTest main for exasph: initialises MPI (the simulation and domain always use it) and,
// under mpirun, lets only rank 0 print while every rank's failures still fail the run.
#include "exasph/util/mpi.hpp"
#include <gtest/gtest.h>

int main(int argc, char** argv) {
    int provided = 0;
    MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
    ::testing::InitGoogleTest(&argc, argv);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) {
        auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
        delete listeners.Release(listeners.default_result_printer());
    }
    int failed = RUN_ALL_TESTS();
    int any_failed = 0;
    MPI_Allreduce(&failed, &any_failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (rank == 0 && any_failed && !failed) std::printf("[  FAILED  ] on another rank\n");
    MPI_Finalize();
    return any_failed;
}
