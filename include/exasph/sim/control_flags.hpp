#pragma once
#include <array>
#include <cstddef>

#include "exasph/domain/collectives.hpp"

namespace exasph {

// Run-control flags every rank learns at the end of a step through the diagnostics collective.
// kStateChanged: a rank's seals inside the step found a change (sim/step_seals.hpp).
enum ControlFlag : std::size_t {
    kStopRequested,
    kCheckpointByClock,
    kStateChanged,
    kNumControlFlags
};

// A flag raised on any rank is seen by all after the next reduction: the flags travel as the
// maxima of kNumControlFlags SumMax elements.
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
        for (std::size_t f = 0; f < kNumControlFlags; ++f) seen_[f] = in[f].max, local_[f] = 0.0;
    }

  private:
    std::array<double, kNumControlFlags> local_{}, seen_{};
};

} // namespace exasph
