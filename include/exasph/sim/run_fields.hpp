#pragma once
#include <cstdint>
#include <optional>

#include "exasph/config/config.hpp"
#include "exasph/domain/collectives.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/sim/eos_requirements.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// The optional fields a run's options use, allocated only for them (docs/architecture.md, "A
// field"), and the storage precision of the derived fields.
template <class T>
void enable_run_fields(ParticleSet<T>& ps, const Config& cfg, const EosParams& eos,
                       Collectives& coll) {
    ps.validate();
    if (cfg.av_limiter) ps.enable(kHaloGrad); // the strain rate (24 B/particle)
    if (cfg.av_switch) ps.enable(Field::alpha), ps.enable(Field::divv);
    if (cfg.volume_elements) ps.enable(Field::xm), ps.enable(Field::kx);
    ps.set_narrow_single(!cfg.double_precision); // --double-precision
    require_eos_inputs(ps, ps.size(), eos, cfg.energy_weights, coll);
}

// Self-gravity with constant G > 0 (physics.md §8), open or periodic on every axis (the solver
// refuses a box periodic along some axes only), with its fields.
template <class T>
void start_gravity(std::optional<GravitySolver<T>>& gravity, ParticleSet<T>& ps,
                   const KernelTable<T>& kernel, const Config& cfg, double G) {
    if (!(G > 0)) return;
    gravity.emplace(kernel, G, cfg.theta, std::uint32_t(cfg.gravity_leaf_size));
    ps.enable(Field::phi), ps.enable(Field::gsoft);
}

} // namespace exasph
