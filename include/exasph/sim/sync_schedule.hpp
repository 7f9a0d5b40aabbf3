#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "exasph/domain/collectives.hpp"
#include "exasph/domain/control_flags.hpp"
#include "exasph/sim/global_step.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/util/error.hpp"
#include "exasph/util/field_memory.hpp"

namespace exasph {

// The time step's collective with votes: the smallest dt_min (in and out), each rank's largest
// skin use (in: this rank's; out: the largest) and the run-control flags, in one reduction.
inline void reduce_step_votes(Collectives& coll, double& dt_min, double& skin_used,
                              ControlFlags& flags) {
    std::vector<SumMax> e(2 + kNumControlFlags);
    e[0].set_min(dt_min);
    e[1].max = skin_used;
    flags.pack(e.data() + 2);
    coll.allreduce_sum_max(e);
    dt_min = e[0].min();
    skin_used = e[1].max;
    flags.unpack(e.data() + 2);
}

// --sync-every K and --diagnostics-every N (issue 23: a typical step makes one collective, the
// time step's). Which steps sync the domain (global tree counts, balance, migration, halo
// discovery: Domain::count_particles + distribute) and which only refresh it
// (Domain::refresh: halos along the last sync's lists, found with a skin), and which steps sum
// the diagnostics. A sync comes when K steps have passed since the last one, when some particle
// may have used half the skin by the end of the coming step (SkinUseKernel: its path since the
// sync plus the growth of its h), or when asked (rollback points, after a checkpoint or a
// rollback, a restart). Every rank decides the same: the largest use travels in the time step's
// collective, everything else is global already. Results do not depend on K beyond round-off
// (the neighbour sets are the same; only the order of the sums changes).
class SyncSchedule {
  public:
    SyncSchedule(int sync_every, int diagnostics_every)
        : every_(sync_every), diag_every_(diagnostics_every) {}

    // Whether the time step's collective carries the flags and the skin use (else a plain
    // minimum, and every step syncs and sums: the behaviour of K = N = 1).
    bool votes() const { return every_ > 1 || diag_every_ > 1; }
    bool lazy() const { return every_ > 1; }

    bool sync_due() const { return !lazy() || asked_ || since_ >= every_; }
    void ask_sync() { asked_ = true; }
    // A sync of n owned particles happened: their skin use starts again.
    void synced(std::size_t n) {
        used_.assign(n, 0.0f);
        since_ = 0;
        asked_ = false;
        ++syncs_;
    }
    float* skin_used() { return used_.data(); }
    // After the time step's collective: the largest use over the ranks against the skin.
    void skin_vote(double used_max, double skin) {
        if (used_max > 0.5 * skin * (1 - 1e-6)) asked_ = true;
    }
    // The step ends (called after sync_due() was last consulted for it).
    void stepped() { ++since_; }
    std::int64_t syncs() const { return syncs_; }

    // The time step's collective with votes (reduce_step_votes) from this rank's smallest limit:
    // the step the clock makes of the smallest over the ranks. This rank's own bounds the
    // coming step for the skin use (SkinUseKernel).
    template <class L, class T, class D>
    double voted_step(ParticleSet<T>& ps, std::size_t n, double dt_min, const StepClock& clock,
                      double ng0, D& domain, ControlFlags& flags) {
        double used =
            lazy() ? skin_use_max<L>(ps, n, skin_used(), clock.step_from(dt_min), clock.dt_m1, ng0)
                   : 0.0;
        reduce_step_votes(domain.collectives(), dt_min, used, flags);
        skin_vote(used, double(domain.skin()));
        return clock.step_from(dt_min);
    }
    int diagnostics_every() const { return diag_every_; }

    // Whether the step that has just reached `step` sums the diagnostics: every N steps, the
    // step before those when the watchdog compares consecutive steps, before a sync (its box
    // comes from them), and whenever `forced` (outputs, the end, a stop).
    bool diagnose_due(std::int64_t step, bool watchdog, bool forced) const {
        if (forced || diag_every_ == 1 || sync_due()) return true;
        return step % diag_every_ == 0 || (watchdog && (step + 1) % diag_every_ == 0);
    }

  private:
    int every_, diag_every_;
    int since_ = 0;
    bool asked_ = true; // the first step syncs
    std::int64_t syncs_ = 0;
    FieldArray<float> used_;
};

// The options it cannot take: self-gravity's tree takes the leaves of every sync; the stirring's
// energy input is summed every step.
inline void check_sync_options(bool lazy, int diagnostics_every, bool gravity, bool stirring) {
    if (lazy && gravity)
        throw input_error("--sync-every above 1 needs a run without self-gravity", true);
    if (diagnostics_every > 1 && stirring)
        throw input_error("--diagnostics-every above 1 needs a run without stirring", true);
}

// The options it cannot take: self-gravity's tree takes the leaves of every sync; the stirring's
// energy input is summed every step. Returns whether halos need a skin (Domain::use_skin).
inline bool check_sync_options(const SyncSchedule& s, bool gravity, bool stirring) {
    if (s.lazy() && gravity)
        throw input_error("--sync-every above 1 needs a run without self-gravity", true);
    if (s.diagnostics_every() > 1 && stirring)
        throw input_error("--diagnostics-every above 1 needs a run without stirring", true);
    return s.lazy();
}

} // namespace exasph
