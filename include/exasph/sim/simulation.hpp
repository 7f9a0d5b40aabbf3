#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "exasph/cases/initial_conditions.hpp"
#include "exasph/config/config.hpp"
#include "exasph/domain/control_flags.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/io/output_state.hpp"
#include "exasph/io/restart_state.hpp"
#include "exasph/kernel/sinc_kernel.hpp"
#include "exasph/sim/advance.hpp"
#include "exasph/sim/block_clock.hpp"
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

// One SPH simulation: the step pipeline of docs/architecture.md, each phase timed, guarded by the
// safety net (sim/safety.hpp). The SPH passes run through the launcher L.
// Requires: every rank of `comm` (one rank included) constructs it with the same Config and
// calls step() as often as the others (each step makes collectives: global tree counts at a
// sync, minimum dt, diagnostics; with --sync-every and --diagnostics-every a typical step makes
// only the second, sim/sync_schedule.hpp; with self-gravity one more, the leaf multipoles);
// `ic` holds this rank's share of the particles (any share: the first sync balances them).
// Guarantees: after each step() every rank holds a state the net found clean, either the step's
// (diagnostics() of step_count(), summed() or not) or, when any rank detected corruption, the
// last verified one (recovered(), on every rank alike); the owned particles are [0, n_owned())
// in the order of the last sync, halos after them. Results do not depend on ranks or threads
// beyond round-off.
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
          safety_(cfg, domain_.rank()),
          safety_on_(cfg.on_sdc != SdcPolicy::off), clock_{ic.dt0, ic.dt0, 0.0, -1.0, 0},
          sched_(cfg.sync_every, cfg.diagnostics_every), exact_(std::move(ic.exact)),
          exact_table_(exact_.table().begin(), exact_.table().end()) {
        enable_run_fields(ps_, cfg, eos_, domain_.collectives());
        start_gravity(gravity_, ps_, kernel_, cfg, cfg.G >= 0 ? cfg.G : ic.G);
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
    }

    // One step of the pipeline, each phase ended by end_phase(); the safety net's verdict at
    // the end, where a detection on any rank rolls every rank back (recovered()).
    void step() {
        begin_step();
        if (sync_or_refresh()) {
            find_neighbours();
            end_phase(kNeighbours);
            compute_forces();
            const double dt = choose_time_step();
            end_phase(kTimeStep);
            if (!refused_before_update()) advance_and_diagnose(dt);
        }
        conclude();
    }

    // Silent-data-corruption handling (sim/safety.hpp); recovered(): the last step() rolled
    // back (then diagnostics() are those of the step rolled back to).
    SafetyNet<T, L>& safety() { return safety_; }
    const SafetyNet<T, L>& safety() const { return safety_; }
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
    // The step's start: its clock and flags, the safety net's check of the state at rest (its
    // vote travels in the step's first collective that carries the flags).
    void begin_step();
    // The end of a phase: its time, then the safety net's look at what it made (a change it
    // finds is voted as kStateChanged).
    void end_phase(Phase p);
    // The domain's sync (count, migrate, sort, trees, halos) or, between syncs, its refresh;
    // false when the sync's collective brought a rank's corruption vote (the step stops there,
    // the particles not moved). Between diagnostics sums (--sync-every) the box may be older
    // than the positions: its open axes are fitted again first.
    bool sync_or_refresh();
    // physics.md §3-6 and 8: the SPH passes (phases density .. momentum_energy), self-gravity
    // and the stirring force (phase gravity).
    void compute_forces();
    auto phase_ender() {
        return [this](Phase p) { end_phase(p); };
    }
    // Whether a vote seen by now refuses the update: a rank's state check before the step, or,
    // when the time step's collective carries the flags, a rank's seals.
    bool refused_before_update() const {
        return flags_[kCorruptBefore] || (sched_.votes() && flags_[kStateChanged]);
    }
    // The update and the diagnostics of a step no vote has refused so far.
    void advance_and_diagnose(double dt);
    // The one place a step ends: it stands (phase diagnostics ends) or, on every rank alike,
    // rolls back to the last verified state.
    void conclude();
    void resume(const RestartState& rs) {
        clock_.time = rs.time, clock_.step = rs.step, clock_.dt_m1 = rs.dt_m1;
        if (blocks_) blocks_->resume(rs.dt_m1, rs.block);
        domain_.restore(ps_, rs.leaf_keys);
        if (stirring_) stirring_->restore(rs.stir);
    }
    void find_neighbours();
    // physics.md §7 (sim/global_step.hpp), or the rungs of block time steps (sim/block_clock.hpp).
    double choose_time_step();
    // physics.md §7 and 2 (sim/advance.hpp).
    void advance(double dt);
    RunPoint<T> run_point() const { return {restart_state(), box_, diag_}; }
    // physics.md §10 sums, run-control flags and the particles' extent (next box): one collective.
    // A step without it (--diagnostics-every) notes only what every rank knows.
    void diagnose(double dt, bool summed = true);

    Config cfg_;
    ParticleSet<T> ps_;
    Box<T> box_;
    EosParams eos_;
    KernelTable<T> kernel_;
    typename L::template Lists<T> nlists_; // the launcher's kind of neighbour lists
    Domain<T> domain_;
    SafetyNet<T, L> safety_;
    PhaseTimer<kNumPhases> timer_;
    Diagnostics diag_, before_; // before_: the last step's, for the watchdog
    bool advanced_ = false;     // the step in progress has updated the state
    bool safety_on_ = false;    // --on-sdc other than off: the watchdog compares steps
    double mass0_ = 0;
    StepClock clock_;
    double courant_dt_ = 0; // Courant limit of this step's particles (momentum-energy pass)
    std::uint32_t max_list_ = 0;
    bool recovered_ = false, point_pending_ = false;
    bool box_fresh_ = false, summed_ = true; // box fitted to the positions; diagnostics summed
    SyncSchedule sched_;
    ControlFlags flags_;
    ExactDensity exact_;
    FieldArray<double> exact_table_; // exact_'s table where the diagnostics kernel reads it
    std::optional<GravitySolver<T>> gravity_;
    std::optional<Stirring> stirring_;
    std::optional<BlockClock<T, L>> blocks_; // --timesteps block
    StepWork work_;                          // this rank's
};

} // namespace exasph

#include "exasph/sim/simulation_step.hpp"
