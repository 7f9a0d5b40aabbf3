#pragma once
#include <algorithm>
#include <array>
#include <cstddef>

#include "exasph/domain/collectives.hpp"

namespace exasph {

// Run-control flags every rank learns through the step's collectives (the diagnostics', and with
// --sync-every/--diagnostics-every the time step's, sim/global_step.hpp).
// kStateChanged: a rank's seals inside the step found a change (sim/step_seals.hpp).
// kCorruptBefore: a rank's state check before a step without a sync found corruption (a sync
// step carries that vote in the domain's collective instead).
enum ControlFlag : std::size_t {
    kStopRequested,
    kCheckpointByClock,
    kStateChanged,
    kCorruptBefore,
    kNumControlFlags
};

// A flag raised on any rank is seen by all after the next reduction that carries the flags (as
// the maxima of kNumControlFlags SumMax elements), until the next step begins: a step with two
// such reductions sees what either brought.
class ControlFlags {
  public:
    void raise(ControlFlag f) { local_[f] = 1.0; }
    bool operator[](ControlFlag f) const { return seen_[f] > 0; }

    // Into the reduction's elements out[0, kNumControlFlags) ...
    void pack(SumMax* out) const {
        for (std::size_t f = 0; f < kNumControlFlags; ++f) out[f] = {0.0, local_[f]};
    }
    // ... and out of them after it; the local flags are cleared.
    void unpack(const SumMax* in) {
        for (std::size_t f = 0; f < kNumControlFlags; ++f)
            seen_[f] = std::max(seen_[f], in[f].max), local_[f] = 0.0;
    }
    // A new step: what the last one's reductions brought is forgotten.
    void begin_step() { seen_.fill(0.0); }

  private:
    std::array<double, kNumControlFlags> local_{}, seen_{};
};

} // namespace exasph
