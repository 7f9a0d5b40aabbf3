#pragma once
#include <cstdint>
#include <vector>

namespace exasph {

// The stirring of driven turbulence (sim/stirring.hpp) where a run stands: its strength, its
// correlation time, the energy it has put in so far and its Fourier coefficients. Empty
// (coeff.size() == 0) for a run without stirring.
struct StirState {
    double accel_rms = 0, t_corr = 0, energy_in = 0;
    std::vector<double> coeff;
};

// Block time steps (sim/block_clock.hpp) inside a block: its start and end times and the tick
// reached (of 2^kMaxRung). tick == 0: at a block's end, where every particle is synchronised.
struct BlockPoint {
    std::int64_t tick = 0;
    double start = 0, end = 0;
};

// Where a run stands besides its particles: with these and the particles' state fields a run
// continues exactly (bitwise on the same rank count). Checkpoints and rollback points hold it.
struct RestartState {
    double time = 0;
    std::int64_t step = 0;
    double dt_m1 = 0;
    std::vector<std::uint64_t> leaf_keys; // global tree
    StirState stir;
    BlockPoint block; // inside a block: its derived fields are part of the state too
};

} // namespace exasph
