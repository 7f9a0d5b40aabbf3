#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/sim/phases.hpp"
#include "exasph/sim/state_hash.hpp"

namespace exasph {

// Seals inside a step (issue 21's fault map). A bit that flips after a phase has produced a
// value and before the phases that read it have done so escapes the state check between
// steps (the step turns the flipped value into a consistent new state), and flips in derived
// fields (rho, the IAD matrix, the accelerations, ...) escape it altogether. Each set of fields
// below is sealed with an order-free hash sum over the owned particles (field_hash_sum) when
// its producer ends, and compared when its last reader has read it, or just before the phase
// that overwrites it:
//   set            sealed at the end of  compared                 read in between by
//   state          sync                  before the update        neighbours .. timestep
//   accelerations  gravity               before the update        timestep
//   density        density               end of h_update          IAD, momentum, AV switch, h
//   iad            iad                   end of h_update          momentum
//   state          update                before the h update      -
//   state          h_update              the guard's seal (end)   diagnostics
// The first sync-to-update state seal is not taken in step 1, whose density pass sets the
// Tait reference state and the first volume weights. Each costs a pass over its fields, run by
// the launcher L (field_hash_sum: on the GPU path where the fields are).
template <class T, class L = DefaultLauncher>
class StepSeals {
  public:
    // The start of step `step`: no seal of an earlier (or rolled-back) step counts.
    void begin(std::int64_t step) {
        step_ = step;
        armed_.fill(false);
    }

    // The end of phase `phase`: seals what it produced; "" or what changed since its seal.
    std::string phase_ended(std::size_t phase, const ParticleSet<T>& ps, std::size_t n) {
        std::string changed;
        if (phase == kSync && step_ > 1) take(kSettled, ps, state(ps), n);
        if (phase == kDensity) take(kDensitySet, ps, density_fields(ps), n);
        if (phase == kIad) take(kIadSet, ps, iad_fields(ps), n);
        if (phase == kGravity) take(kAccelerations, ps, acceleration_fields(ps), n);
        if (phase == kUpdate) take(kUpdated, ps, state(ps), n);
        if (phase == kSmoothingLength) {
            changed =
                compare(kDensitySet, ps, density_fields(ps), n,
                        "the density pass's fields changed before the h update had read them");
            if (changed.empty())
                changed = compare(kIadSet, ps, iad_fields(ps), n,
                                  "the IAD matrices changed before the h update ended");
            take(kFinal, ps, state(ps), n);
        }
        return changed;
    }

    // Just before the update reads the state and the accelerations.
    std::string before_update(const ParticleSet<T>& ps, std::size_t n) {
        std::string changed = compare(kSettled, ps, state(ps), n,
                                      "the state changed between the sync and the update");
        if (changed.empty())
            changed = compare(kAccelerations, ps, acceleration_fields(ps), n,
                              "the accelerations changed between the gravity phase and the update");
        return changed;
    }

    // Just before the h update (and the volume weights) read the updated state.
    std::string before_h_update(const ParticleSet<T>& ps, std::size_t n) {
        return compare(kUpdated, ps, state(ps), n,
                       "the state changed between the update and the h update");
    }

    // The state guard sealed a state whose hash sum is `sealed`: "" or what changed since the
    // end of the h update.
    std::string at_guard_seal(std::uint64_t sealed) const {
        if (!armed_[kFinal] || sealed == sums_[kFinal]) return "";
        return "the state changed between the h update and the end of the step";
    }

    // The sets of fields sealed (bench/sdc_cost times each).
    static std::vector<Field> state(const ParticleSet<T>& ps) { return ps.fields(kState); }
    static std::vector<Field> density_fields(const ParticleSet<T>& ps) {
        auto f = ps.fields(kHaloDensity);
        f.push_back(Field::nc);
        return f;
    }
    static std::vector<Field> acceleration_fields(const ParticleSet<T>& ps) {
        std::vector<Field> f{Field::ax, Field::ay, Field::az, Field::du};
        if (ps.enabled(Field::divv)) f.push_back(Field::divv);
        return f;
    }
    static std::vector<Field> iad_fields(const ParticleSet<T>& ps) {
        return ps.fields(kHaloIad | kHaloGrad);
    }

  private:
    enum Slot { kSettled, kDensitySet, kIadSet, kAccelerations, kUpdated, kFinal, kSlots };

    void take(Slot s, const ParticleSet<T>& ps, const std::vector<Field>& fields, std::size_t n) {
        sums_[s] = field_hash_sum<L>(ps, fields, n);
        armed_[s] = true;
    }
    std::string compare(Slot s, const ParticleSet<T>& ps, const std::vector<Field>& fields,
                        std::size_t n, const char* what) {
        if (!armed_[s]) return "";
        armed_[s] = false;
        if (field_hash_sum<L>(ps, fields, n) == sums_[s]) return "";
        return what;
    }

    std::int64_t step_ = 0;
    std::array<std::uint64_t, kSlots> sums_{};
    std::array<bool, kSlots> armed_{};
};

} // namespace exasph
