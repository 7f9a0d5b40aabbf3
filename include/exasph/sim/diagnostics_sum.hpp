#pragma once
#include <cstddef>
#include <vector>

#include "exasph/domain/box_extent.hpp"
#include "exasph/domain/collectives.hpp"
#include "exasph/domain/control_flags.hpp"
#include "exasph/sim/diagnostics.hpp"

namespace exasph {

// The diagnostics collective (physics.md §10): this rank's sums of its n owned particles, the
// run-control flags, the step's work (StepWork) and the particles' extent, reduced at once; the
// extent fits the open axes of `box` (next step's box without a collective of its own).
// `exact`: the exact solution at the time the step began (its L1 error; after_step: false for
// the initial row, which has none). The particles' terms are reduced by the launcher L.
template <class L, class T>
Diagnostics sum_diagnostics(ParticleSet<T>& ps, std::size_t n, std::size_t n_halo,
                            const ExactDensity::AtTime& exact, bool after_step, double ng0,
                            const StepWork& work, ControlFlags& flags, Box<T>& box,
                            Collectives& coll) {
    std::vector<SumMax> e(kDiagWithExtent + kNumControlFlags + StepWork::kElements);
    work.pack(e.data() + kDiagWithExtent + kNumControlFlags);
    local_diagnostics<L>(ps, n, n_halo, exact, ng0, e.data());
    flags.pack(e.data() + kDiagWithExtent);
    coll.allreduce_sum_max(e);
    flags.unpack(e.data() + kDiagWithExtent);
    Diagnostics d = diagnostics_from(e.data(), coll.size());
    if (exact.valid() && after_step) d.l1_rho = e[11].sum / double(d.n);
    d.work.unpack(e.data() + kDiagWithExtent + kNumControlFlags);
    apply_extent(box, e.data() + kDiagElements);
    return d;
}

} // namespace exasph
