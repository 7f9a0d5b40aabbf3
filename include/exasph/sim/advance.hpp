#pragma once
#include <cstddef>

#include "exasph/config/config.hpp"
#include "exasph/sim/block_clock.hpp"
#include "exasph/sim/global_step.hpp"
#include "exasph/sim/phases.hpp"
#include "exasph/sph/passes.hpp"

namespace exasph {

// physics.md §7 and 2, the end of a step: the state, the AV switch, h and X move on; with block
// time steps (blocks) every particle drifts and the rest moves on for the active ones only.
// `clock` is the run's before the step (its last step dt_m1, its time); end_phase(p) ends each
// phase (kUpdate, kSmoothingLength). Returns the time the step reaches.
template <class L, class T, class Blocks, class EndPhase>
double advance_state(ParticleSet<T>& ps, std::size_t n, const Box<T>& box, Blocks* blocks,
                     const Config& cfg, double dt, const StepClock& clock, EndPhase end_phase) {
    const ParticleRange own = blocks ? blocks->active_range() : ParticleRange(n);
    const double t_next = blocks ? blocks->drift_to_next(ps, n, box) : clock.time + dt;
    if (!blocks) update_state<L>(ps, n, box, dt, clock.dt_m1);
    if (cfg.av_switch) update_viscosity<L>(ps, own, blocks ? -1.0 : dt, cfg.alpha_min, cfg.alpha);
    end_phase(kUpdate);
    update_smoothing_lengths<L>(ps, own, cfg.ng0);
    if (cfg.volume_elements) update_volume_weights<L>(ps, own, cfg.energy_weights);
    end_phase(kSmoothingLength);
    return t_next;
}

} // namespace exasph
