#pragma once
#include <cstdint>

#include "exasph/util/annotate.hpp"

// Block (individual) time steps, the arithmetic of the rungs: a block of length dt_max is cut
// into 2^kMaxRung ticks; a particle on rung k takes steps of 2^(kMaxRung - k) ticks, so that
// dt_k = dt_max / 2^k, and is active at the ticks that are multiples of its step. All integer,
// so that every rank and every restart agrees on who is active when (docs/design-notes.md).
namespace exasph {

inline constexpr int kMaxRung = 24; // 2^24 ticks per block: 25 rungs

// The length of a step on rung r, in ticks.
EXASPH_HD inline std::int64_t rung_ticks(int r) {
    return std::int64_t(1) << (kMaxRung - r);
}

// Whether a step of rung r may begin or end at `tick`: the rung's synchronisation points.
EXASPH_HD inline bool on_rung_boundary(std::int64_t tick, int r) {
    return tick % rung_ticks(r) == 0;
}

// The first rung r >= from whose synchronisation points include `tick` (tick 0: `from`).
EXASPH_HD inline int aligned_rung(std::int64_t tick, int from) {
    int r = from;
    while (r < kMaxRung && !on_rung_boundary(tick, r)) ++r;
    return r;
}

// The beginning of the step of rung r that ends at or after tick (tick >= 1): t0 < tick <= t0+s.
EXASPH_HD inline std::int64_t rung_step_start(std::int64_t tick, int r) {
    const std::int64_t s = rung_ticks(r);
    return ((tick - 1) / s) * s;
}

// The longest step of the hierarchy no longer than dt: the smallest r with block / 2^r <= dt
// (to 1e-12 relative: the block's length is a difference of times and may exceed by rounding
// the limit it was chosen from). kMaxRung + 1 if even the shortest step is too long.
EXASPH_HD inline int rung_for_step(double dt, double block) {
    int r = 0;
    double len = block;
    while (r <= kMaxRung && len > dt * (1 + 1e-12)) len *= 0.5, ++r;
    return r;
}

} // namespace exasph
