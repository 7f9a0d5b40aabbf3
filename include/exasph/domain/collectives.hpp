#pragma once
#include <cstdint>
#include <limits>
#include <vector>

#include "exasph/util/mpi.hpp"

#include "exasph/domain/comm_record.hpp"

namespace exasph {

// An element reduced with "sum" on its first member and "max" on its second. Reducing arrays of
// SumMax in one MPI_Allreduce lets one collective carry counts (sum) together with bounds and
// smoothing lengths (max) and minima (set_min, min(): the one place a minimum rides as the
// maximum of its negation, which is exact). The user-defined MPI type keeps the two members
// together, so MPI may segment the buffer without breaking the meaning of an element.
struct SumMax {
    double sum = 0;
    double max = -std::numeric_limits<double>::infinity();

    void set_min(double least) { max = -least; }
    double min() const { return -max; }
};

namespace detail {
inline void sum_max_op(void* in, void* inout, int* len, MPI_Datatype*) {
    const auto* a = static_cast<const SumMax*>(in);
    auto* b = static_cast<SumMax*>(inout);
    for (int i = 0; i < *len; ++i) {
        b[i].sum += a[i].sum;
        b[i].max = a[i].max > b[i].max ? a[i].max : b[i].max;
    }
}
} // namespace detail

// The collectives of the step, counted: the hot path has three per step (global tree counts +
// hmax, minimum time step, conservation sums + next box), a typical step only the second with
// --sync-every and --diagnostics-every (sim/sync_schedule.hpp); tests check the counter.
// It also keeps the record of the point-to-point traffic (record(): halos, migration, gravity),
// filled by the functions that post those messages.
class Collectives {
  public:
    explicit Collectives(MPI_Comm comm) : comm_(comm) {
        MPI_Comm_rank(comm_, &rank_);
        MPI_Comm_size(comm_, &size_);
        MPI_Type_contiguous(2, MPI_DOUBLE, &type_);
        MPI_Type_commit(&type_);
        MPI_Op_create(&detail::sum_max_op, 1, &op_);
        record_ = CommRecord(size_);
    }
    ~Collectives() {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (finalized) return;
        MPI_Op_free(&op_);
        MPI_Type_free(&type_);
    }
    Collectives(const Collectives&) = delete;
    Collectives& operator=(const Collectives&) = delete;

    void allreduce_sum_max(std::vector<SumMax>& v) {
        ++count_;
        const double t0 = wall_seconds();
        MPI_Allreduce(MPI_IN_PLACE, v.data(), int(v.size()), type_, op_, comm_);
        record_.waited(wall_seconds() - t0);
    }
    double allreduce_min(double x) {
        ++count_;
        const double t0 = wall_seconds();
        MPI_Allreduce(MPI_IN_PLACE, &x, 1, MPI_DOUBLE, MPI_MIN, comm_);
        record_.waited(wall_seconds() - t0);
        return x;
    }

    MPI_Comm comm() const { return comm_; }
    int rank() const { return rank_; }
    int size() const { return size_; }
    std::int64_t count() const { return count_; }
    CommRecord& record() { return record_; }
    const CommRecord& record() const { return record_; }

  private:
    MPI_Comm comm_;
    int rank_ = 0, size_ = 1;
    MPI_Datatype type_{};
    MPI_Op op_{};
    std::int64_t count_ = 0;
    CommRecord record_;
};

} // namespace exasph
