#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "exasph/cases/initial_conditions.hpp"
#include "exasph/config/config.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/io/output_state.hpp"
#include "exasph/io/restart_state.hpp"
#include "exasph/kernel/sinc_kernel.hpp"
#include "exasph/sim/advance.hpp"
#include "exasph/sim/block_clock.hpp"
#include "exasph/sim/control_flags.hpp"
#include "exasph/sim/diagnostics_sum.hpp"
#include "exasph/sim/hydro_forces.hpp"
#include "exasph/sim/initial_potential.hpp"
#include "exasph/sim/phases.hpp"
#include "exasph/sim/run_fields.hpp"
#include "exasph/sim/safety.hpp"
#include "exasph/sim/stirring.hpp"
#include "exasph/sim/sync_schedule.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/tree/neighbour_lists.hpp"
#include "exasph/util/timer.hpp"

namespace exasph {

// One SPH simulation: the step pipeline of docs/architecture.md, each phase timed. Runs on any
// number of MPI ranks of `comm` (one rank included); results do not depend on ranks or threads
// beyond round-off. Collectives per step: global tree counts (sync), minimum dt, diagnostics
// (with --sync-every and --diagnostics-every a typical step makes only the second,
// sim/sync_schedule.hpp); with self-gravity one more (the leaf multipoles). The SPH passes run
// through the launcher L.
template <class T, class L = DefaultLauncher>
class Simulation {
  public:
    Simulation(const Config& cfg, InitialConditions<T> ic, const RestartState& rs, // restart
               MPI_Comm comm = MPI_COMM_WORLD)
        : Simulation(cfg, std::move(ic), comm, &rs) {}

    Simulation(const Config& cfg, InitialConditions<T> ic, MPI_Comm comm = MPI_COMM_WORLD,
               const RestartState* restart = nullptr)
        : cfg_(cfg), ps_(std::move(ic.particles)), box_(ic.box), eos_(ic.eos),
          kernel_(sinc_kernel(cfg.kernel_exponent)), nlists_(std::uint32_t(cfg.ngmax)),
          domain_(comm, std::uint32_t(cfg.global_bucket), std::uint32_t(cfg.leaf_size), cfg.curve),
          safety_(cfg, domain_.rank()), clock_{ic.dt0, ic.dt0, 0.0, -1.0, 0},
          sched_(cfg.sync_every, cfg.diagnostics_every), exact_(std::move(ic.exact)) {
        enable_run_fields(ps_, cfg, eos_, domain_.collectives());
        start_gravity(gravity_, ps_, box_, kernel_, cfg, cfg.G >= 0 ? cfg.G : ic.G);
        if (cfg.timesteps == TimeStepping::block) // the case's stirring when not given
            blocks_.emplace(ps_, cfg, cfg.stir_mach < 0 ? ic.stir_mach > 0 : cfg.stir_mach > 0);
        if (!restart && cfg_.av_switch)
            std::fill(ps_[Field::alpha].begin(), ps_[Field::alpha].end(), T(cfg_.alpha));
        if (!restart && cfg_.volume_elements) ps_[Field::xm] = ps_[Field::m]; // 1st density's X
        restart ? resume(*restart) : domain_.init(ps_, box_);
        diagnose(0.0);
        stirring_ =
            start_stirring(box_, eos_, diag_, cfg.stir_mach >= 0 ? cfg.stir_mach : ic.stir_mach,
                           std::uint64_t(cfg.stir_seed), restart, L::kBackend == Backend::cuda);
        if (stirring_) ps_.enable(Field::stir), diag_.e_stir = stirring_->state().energy_in;
        domain_.use_skin(check_sync_options(sched_, bool(gravity_), bool(stirring_)));
        if (gravity_) { // the first row's E_pot, of the initial positions
            diag_.epot = initial_potential_energy(ps_, n_owned(), box_, cfg_, *gravity_, comm);
            diag_.etot = diag_.ekin + diag_.eint + diag_.epot;
        }
        mass0_ = diag_.mass;
        safety_.seal(ps_, n_owned());
        timer_.observe([this](std::size_t p) {
            if (safety_.after_phase(p, ps_, n_owned())) flags_.raise(kStateChanged);
        });
    }

    // One step of the pipeline, or a rollback (recovered()) when corruption was found.
    void step() {
        timer_.begin_step();
        recovered_ = false;
        flags_.begin_step();
        const Box<T> fitted = box_fresh_ ? box_ : with_open_axes_unbounded(box_); // to check
        const bool corrupt = safety_.corrupted_before(
            ps_, n_owned(), fitted, clock_.step + 1, clock_.dt_m1, eos_.kind == EosKind::ideal_gas);
        point_pending_ |= safety_.point_due(clock_.step); // block steps: waits for a block's end
        if (point_pending_) sched_.ask_sync();            // a rollback point follows a sync's vote
        if (!sched_.sync_due()) {
            if (corrupt) flags_.raise(kCorruptBefore);
            domain_.refresh(ps_);
        } else if (!sync_domain(corrupt)) {
            return;
        }
        timer_.stop(kSync);
        find_neighbours();
        timer_.stop(kNeighbours);
        courant_dt_ = hydro_forces<L>(ps_, nlists_, box_, kernel_.view(), eos_, cfg_, domain_,
                                      gravity_ ? &*gravity_ : nullptr, timer_, clock_.step == 0,
                                      store_results_in(blocks_ ? ps_.data(Field::dtc) : nullptr));
        if (!blocks_) nlists_.release(); // the sync can use their memory
        timer_.stop(kMomentumEnergy);
        if (gravity_)
            gravity_->compute(ps_, n_owned(), domain_.assignment(), box_, domain_.curve(),
                              domain_.collectives(), blocks_ ? blocks_->active() : nullptr);
        if (stirring_) add_stirring<L>(ps_, n_owned(), stirring_->modes());
        timer_.stop(kGravity);
        const double dt = choose_time_step();
        timer_.stop(kTimeStep);
        if (flags_[kCorruptBefore]) // voted in the time step's collective (no sync this step)
            return roll_back("the state check before step " + std::to_string(clock_.step + 1),
                             clock_.step + 1);
        if (sched_.votes() && flags_[kStateChanged]) // found after the last step's collectives
            return roll_back("the step's seals by step " + std::to_string(clock_.step + 1),
                             clock_.step + 1);
        advance(dt);
        const Diagnostics before = diag_;
        const bool forced = // the run's end, or a stop or a clock checkpoint after the step
            clock_.ends(cfg_.steps) || flags_[kStopRequested] || flags_[kCheckpointByClock];
        summed_ = sched_.diagnose_due(clock_.step, safety_.on(), forced);
        diagnose(dt, summed_);
        const bool consecutive = summed_ && before.step + 1 == diag_.step; // for the watchdog
        if (const auto by =
                safety_.verdict_after(ps_, n_owned(), consecutive ? &before : nullptr, diag_,
                                      mass0_, !gravity_ && !stirring_, flags_[kStateChanged]);
            !by.empty())
            return roll_back(by + " after step " + std::to_string(clock_.step), clock_.step);
        timer_.stop(kDiagnostics);
        timer_.end_step();
    }

    // Silent-data-corruption handling (sim/safety.hpp); recovered(): the last step() rolled
    // back (then diagnostics() are those of the step rolled back to).
    SafetyNet<T>& safety() { return safety_; }
    const SafetyNet<T>& safety() const { return safety_; }
    bool recovered() const { return recovered_; }
    // Whether the last step summed the diagnostics (else only their step, time and dt are new).
    bool summed() const { return summed_; }
    // The next step syncs (after a checkpoint: as a restart from it does). Syncs so far.
    void sync_next_step() { sched_.ask_sync(); }
    std::int64_t domain_syncs() const { return sched_.syncs(); }
    // Raises a control flag on this rank; after the next step every rank sees it (flag()).
    void raise_flag(ControlFlag f) { flags_.raise(f); }
    bool flag(ControlFlag f) const { return flags_[f]; }
    RestartState restart_state() const {
        RestartState rs{clock_.time, clock_.step, clock_.dt_m1, domain_.global_tree().keys(),
                        {},          {}};
        if (stirring_) rs.stir = stirring_->state();
        if (blocks_) rs.dt_m1 = blocks_->last_block(), rs.block = blocks_->where();
        return rs;
    }
    // What snapshots and checkpoints read (io/output_state.hpp).
    OutputState<T> output_state() const {
        return {ps_, n_owned(), box_, eos_, restart_state(), diag_.dt, clock_.dt0};
    }
    const EosParams& eos() const { return eos_; }
    double gravitational_constant() const { return gravity_ ? gravity_->G() : 0.0; } // 0: none
    double stir_mach() const { return stirring_ ? stirring_->mach() : 0.0; } // 0: no stirring
    double dt0() const { return clock_.dt0; }
    void set_end_time(double t_end) { clock_.t_end = t_end; } // the last step ends exactly at t_end
    const Diagnostics& diagnostics() const { return diag_; }
    // Owned particles are [0, n_owned()); halos (if any) follow.
    const ParticleSet<T>& particles() const { return ps_; }
    // For drivers that change the state between steps on purpose (glass relaxation, --on-sdc off).
    ParticleSet<T>& particles_to_modify() { return ps_; }
    std::size_t n_owned() const { return domain_.n_owned(); }
    const Domain<T>& domain() const { return domain_; }
    std::int64_t collective_count() { return domain_.collectives().count(); }
    const Box<T>& box() const { return box_; }
    double time() const { return clock_.time; }
    std::int64_t step_count() const { return clock_.step; }
    // Block time steps: what the limits allowed (BlockClock::work_bound); none with global steps.
    std::optional<BlockWorkBound> block_work_bound() const {
        return blocks_ ? std::optional(blocks_->work_bound()) : std::nullopt;
    }
    // Block time steps: whether every particle is synchronised (a block's end; rollback points).
    bool at_sync_point() const { return !blocks_ || blocks_->at_boundary(); }
    // Longest neighbour list of the last step on this rank (symmetric criterion).
    std::uint32_t max_list_length() const { return max_list_; }
    // Owned particles of the most loaded rank over the mean (from the last sync).
    double imbalance() const { return domain_.assignment().imbalance(); }
    const std::array<double, kNumPhases>& phase_times() const { return timer_.step_times(); }
    const std::array<double, kNumPhases>& total_phase_times() const { return timer_.total_times(); }

  private:
    // The domain's sync (count, migrate, sort, trees, halos); false after a rollback that the
    // corruption vote in its collective brought. Between diagnostics sums (--sync-every) the
    // box may be older than the positions: its open axes are fitted again first.
    bool sync_domain(bool corrupt) {
        if (!box_fresh_) refit_box_to_particles(ps_, n_owned(), box_, domain_.collectives());
        const bool by_cost = cfg_.balance == Balance::cost && blocks_;
        const float* cost = by_cost ? blocks_->costs(ps_, n_owned()) : nullptr;
        if (domain_.count_particles(ps_, box_, corrupt, cost)) {
            roll_back("the state check before step " + std::to_string(clock_.step + 1),
                      clock_.step + 1);
            return false;
        }
        if (point_pending_ && at_sync_point())
            safety_.keep_point(ps_, n_owned(), run_point()), point_pending_ = false;
        domain_.distribute(ps_, box_);
        if (blocks_) blocks_->select(ps_, n_owned(), work_);
        sched_.synced(n_owned());
        return true;
    }

    void resume(const RestartState& rs) {
        clock_.time = rs.time, clock_.step = rs.step, clock_.dt_m1 = rs.dt_m1;
        if (blocks_) blocks_->resume(rs.dt_m1, rs.block);
        domain_.restore(ps_, rs.leaf_keys);
        if (stirring_) stirring_->restore(rs.stir);
    }

    void find_neighbours() {
        const auto res = build_neighbour_lists(nlists_, domain_, ps_, box_,
                                               blocks_ ? blocks_->active() : nullptr);
        max_list_ = res.max_count;
        work_.active = double(blocks_ ? blocks_->active_count() : n_owned()),
        work_.pairs = double(res.pairs);
    }

    // physics.md §7 (sim/global_step.hpp), or the rungs of block time steps (sim/block_clock.hpp).
    double choose_time_step() {
        const double accel = gravity_ ? cfg_.accel_eps : 0.0;
        if (blocks_) { // closing and opening the steps updates the state: check it first
            if (safety_.changed_before_update(ps_, n_owned())) flags_.raise(kStateChanged);
            const double dt =
                blocks_->choose(ps_, n_owned(), nlists_, domain_,
                                {clock_.step == 0, clock_.dt0, accel, clock_.time, clock_.t_end});
            nlists_.release();
            return dt;
        }
        const double limit = local_time_step_limit<L>(ps_, n_owned(), courant_dt_, accel);
        if (!sched_.votes()) return clock_.step_from(domain_.collectives().allreduce_min(limit));
        return sched_.voted_step<L>(ps_, n_owned(), limit, clock_, cfg_.ng0, domain_, flags_);
    }

    // physics.md §7 and 2 (sim/advance.hpp).
    void advance(double dt) {
        const double t_next =
            advance_state<L>(ps_, n_owned(), box_, blocks_ ? &*blocks_ : nullptr, cfg_, dt,
                             clock_.dt_m1, clock_.time, safety_, flags_, timer_);
        if (stirring_) stirring_->advance(clock_.step, dt);
        clock_.stepped(dt, t_next);
        box_fresh_ = false, sched_.stepped();
    }

    RunPoint<T> run_point() const { return {restart_state(), box_, diag_}; }

    // All ranks, after a detection by `where` in step `step`: back to the last verified state.
    void roll_back(const std::string& where, std::int64_t step) {
        const RunPoint<T>& point = safety_.roll_back(ps_, where, step, clock_.step);
        box_ = point.box, box_fresh_ = true;
        diag_ = point.diag;
        sched_.ask_sync(); // the halos and trees belong to the state left behind
        resume(point.rs);
        safety_.seal(ps_, n_owned());
        recovered_ = true;
        timer_.end_step();
    }

    // physics.md §10 sums, run-control flags and the particles' extent (next box): one collective.
    // A step without it (--diagnostics-every) notes only what every rank knows.
    void diagnose(double dt, bool summed = true) {
        const double waited = domain_.comm_record().waited_in_step(); // compute: the rest
        work_.compute_sum = work_.compute_max = std::max(0.0, timer_.step_total() - waited);
        if (summed)
            diag_ = sum_diagnostics(ps_, n_owned(), domain_.n_halo(), exact_, clock_.time - dt,
                                    clock_.step > 0, cfg_.ng0, work_, flags_, box_,
                                    domain_.collectives());
        diag_.step = clock_.step, diag_.time = clock_.time, diag_.dt = dt;
        if (!summed) return;
        if (stirring_) stirring_->add_energy(dt * diag_.stir_power);
        diag_.e_stir = stirring_ ? stirring_->state().energy_in : 0.0;
        box_fresh_ = true;
    }

    Config cfg_;
    ParticleSet<T> ps_;
    Box<T> box_;
    EosParams eos_;
    KernelTable<T> kernel_;
    typename L::template Lists<T> nlists_; // the launcher's kind of neighbour lists
    Domain<T> domain_;
    SafetyNet<T> safety_;
    PhaseTimer<kNumPhases> timer_;
    Diagnostics diag_;
    double mass0_ = 0;
    StepClock clock_;
    double courant_dt_ = 0; // Courant limit of this step's particles (momentum-energy pass)
    std::uint32_t max_list_ = 0;
    bool recovered_ = false, point_pending_ = false;
    bool box_fresh_ = false, summed_ = true; // box fitted to the positions; diagnostics summed
    SyncSchedule sched_;
    ControlFlags flags_;
    ExactDensity exact_;
    std::optional<GravitySolver<T>> gravity_;
    std::optional<Stirring> stirring_;
    std::optional<BlockClock<T, L>> blocks_; // --timesteps block
    StepWork work_;                          // this rank's
};

} // namespace exasph
