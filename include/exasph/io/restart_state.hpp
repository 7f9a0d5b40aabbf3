#pragma once
#include <cstdint>
#include <vector>

namespace exasph {

// Where a run stands besides its particles: with these and the particles' state fields a run
// continues exactly (bitwise on the same rank count). Checkpoints and rollback points hold it.
struct RestartState {
    double time = 0;
    std::int64_t step = 0;
    double dt_m1 = 0;
    std::vector<std::uint64_t> leaf_keys; // global tree
};

} // namespace exasph
