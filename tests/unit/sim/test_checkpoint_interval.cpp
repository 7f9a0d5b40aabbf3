// Issue 8, acceptance 4: the automatic checkpoint interval is the Young/Daly optimum sqrt(2 C M).
#include <cmath>

#include "exasph/util/mpi.hpp"
#include <gtest/gtest.h>

#include "exasph/run/checkpoint_interval.hpp"

using namespace exasph;

TEST(CheckpointInterval, YoungDaly) {
    EXPECT_DOUBLE_EQ(young_daly_interval(2.0, 3600.0), std::sqrt(2.0 * 2.0 * 3600.0));
    EXPECT_DOUBLE_EQ(young_daly_interval(30.0, 86400.0), 2276.8399153212337);
    // Cost 4x -> interval 2x; MTBF / 100 -> interval / 10.
    EXPECT_DOUBLE_EQ(young_daly_interval(4.0, 100.0), 2 * young_daly_interval(1.0, 100.0));
    EXPECT_NEAR(young_daly_interval(1.0, 1.0), young_daly_interval(1.0, 100.0) / 10, 1e-15);
    EXPECT_THROW(young_daly_interval(0.0, 100.0), Error);
    EXPECT_THROW(young_daly_interval(1.0, -1.0), Error);
}

TEST(CheckpointInterval, RunMtbfScalesWithNodes) {
    EXPECT_DOUBLE_EQ(run_mtbf_seconds(24.0, 1), 86400.0);
    EXPECT_DOUBLE_EQ(run_mtbf_seconds(24.0, 1000), 86.4);
    EXPECT_GE(count_nodes(MPI_COMM_WORLD), 1);
}
