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
#include "exasph/sim/block_clock.hpp"
#include "exasph/sim/control_flags.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/sim/global_step.hpp"
#include "exasph/sim/hydro_forces.hpp"
#include "exasph/sim/initial_potential.hpp"
#include "exasph/sim/phases.hpp"
#include "exasph/sim/run_fields.hpp"
#include "exasph/sim/safety.hpp"
#include "exasph/sim/stirring.hpp"
#include "exasph/sph/passes.hpp"
#include "exasph/tree/neighbour_lists.hpp"
#include "exasph/util/timer.hpp"

namespace exasph {

// One SPH simulation: the step pipeline of docs/architecture.md, each phase timed. Runs on any
// number of MPI ranks of `comm` (one rank included); results do not depend on ranks or threads
// beyond round-off. Collectives per step: global tree counts (sync), minimum dt, diagnostics;
// with self-gravity one more (the leaf multipoles). The SPH passes run through the launcher L.
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
          safety_(cfg, domain_.rank()), dt_m1_(ic.dt0), dt0_(ic.dt0), exact_(std::move(ic.exact)) {
        enable_run_fields(ps_, cfg, eos_, domain_.collectives());
        start_gravity(gravity_, ps_, box_, kernel_, cfg, cfg.G >= 0 ? cfg.G : ic.G);
        if (cfg.timesteps == TimeStepping::block) // the case's stirring when not given
            blocks_.emplace(ps_, cfg, cfg.stir_mach < 0 ? ic.stir_mach > 0 : cfg.stir_mach > 0);
        restart ? resume(*restart) : start();
        diagnose(0.0);
        stirring_ =
            start_stirring(box_, eos_, diag_, cfg.stir_mach >= 0 ? cfg.stir_mach : ic.stir_mach,
                           std::uint64_t(cfg.stir_seed), restart);
        if (stirring_) ps_.enable(Field::stir), diag_.e_stir = stirring_->state().energy_in;
        if (stirring_ && L::kBackend == Backend::cuda) // its modes are in host memory
            throw input_error("driven turbulence (--stir-mach) needs --backend cpu", true);
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
        timer_.start();
        recovered_ = false;
        const bool corrupt = safety_.corrupted_before(ps_, n_owned(), box_, step_ + 1, dt_m1_,
                                                      eos_.kind == EosKind::ideal_gas);
        const bool by_cost = cfg_.balance == Balance::cost && blocks_;
        const float* cost = by_cost ? blocks_->costs(ps_, n_owned()) : nullptr;
        if (domain_.count_particles(ps_, box_, corrupt, cost))
            return roll_back("the state check before step " + std::to_string(step_ + 1), step_ + 1);
        point_pending_ |= safety_.point_due(step_); // block steps: waits for a block's end
        if (point_pending_ && at_sync_point())
            safety_.keep_point(ps_, n_owned(), run_point()), point_pending_ = false;
        domain_.distribute(ps_, box_);
        if (blocks_) blocks_->select(ps_, n_owned(), work_);
        timer_.stop(kSync);
        find_neighbours();
        timer_.stop(kNeighbours);
        hydro_forces();
        if (gravity_)
            gravity_->compute(ps_, n_owned(), domain_.assignment(), box_, domain_.curve(),
                              domain_.collectives(), blocks_ ? blocks_->active() : nullptr);
        if (stirring_) add_stirring<L>(ps_, n_owned(), stirring_->modes());
        timer_.stop(kGravity);
        const double dt = choose_time_step();
        timer_.stop(kTimeStep);
        advance(dt);
        const Diagnostics before = diag_;
        diagnose(dt);
        if (const auto by = safety_.verdict_after(ps_, n_owned(), before, diag_, mass0_,
                                                  !gravity_ && !stirring_, flags_[kStateChanged]);
            !by.empty())
            return roll_back(by + " after step " + std::to_string(step_), step_);
        timer_.stop(kDiagnostics);
        timer_.end_step();
    }

    // Silent-data-corruption handling (sim/safety.hpp): the rollbacks so far, and whether the
    // last step() was one (then diagnostics() are those of the step rolled back to).
    std::int64_t recoveries() const { return safety_.recoveries(); }
    bool recovered() const { return recovered_; }
    const std::string& sdc_detail() const { return safety_.detail(); }
    const std::string& sdc_summary() const { return safety_.summary(); }
    std::string take_sdc_notice() { return safety_.take_notice(); } // budget widened: once
    std::int64_t sdc_detection_step() const { return safety_.detection_step(); }
    // Raises a control flag on this rank; after the next step every rank sees it (flag()).
    void raise_flag(ControlFlag f) { flags_.raise(f); }
    bool flag(ControlFlag f) const { return flags_[f]; }
    RestartState restart_state() const {
        RestartState rs{time_, step_, dt_m1_, domain_.global_tree().keys(), {}, {}};
        if (stirring_) rs.stir = stirring_->state();
        if (blocks_) rs.dt_m1 = blocks_->last_block(), rs.block = blocks_->where();
        return rs;
    }
    // What snapshots and checkpoints read (io/output_state.hpp).
    OutputState<T> output_state() const {
        return {ps_, n_owned(), box_, eos_, restart_state(), diag_.dt, dt0_};
    }
    const EosParams& eos() const { return eos_; }
    double gravitational_constant() const { return gravity_ ? gravity_->G() : 0.0; } // 0: none
    double stir_mach() const { return stirring_ ? stirring_->mach() : 0.0; } // 0: no stirring
    double dt0() const { return dt0_; }
    void set_end_time(double t_end) { t_end_ = t_end; } // the last step ends exactly at t_end
    const Diagnostics& diagnostics() const { return diag_; }
    // Owned particles are [0, n_owned()); halos (if any) follow.
    const ParticleSet<T>& particles() const { return ps_; }
    // For drivers that change the state between steps on purpose (glass relaxation, --on-sdc off).
    ParticleSet<T>& particles_to_modify() { return ps_; }
    std::size_t n_owned() const { return domain_.n_owned(); }
    const Domain<T>& domain() const { return domain_; }
    std::int64_t collective_count() { return domain_.collectives().count(); }
    const Box<T>& box() const { return box_; }
    double time() const { return time_; }
    std::int64_t step_count() const { return step_; }
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
    // Block time steps keep each particle's own Courant limit (Field::dtc) for its rung.
    auto own_limits_if_blocks() {
        return [dtc = blocks_ ? ps_.data(Field::dtc) : nullptr](auto kern) {
            return StoreResultKernel<decltype(kern), T>{kern, dtc};
        };
    }

    void start() {
        if (cfg_.av_switch)
            std::fill(ps_[Field::alpha].begin(), ps_[Field::alpha].end(), T(cfg_.alpha));
        if (cfg_.volume_elements) ps_[Field::xm] = ps_[Field::m]; // weights of the 1st density
        domain_.init(ps_, box_);
    }

    void resume(const RestartState& rs) {
        time_ = rs.time;
        step_ = rs.step;
        dt_m1_ = rs.dt_m1;
        if (blocks_) blocks_->resume(rs.dt_m1, rs.block);
        domain_.restore(ps_, rs.leaf_keys);
        if (stirring_) stirring_->restore(rs.stir);
    }

    void find_neighbours() {
        SearchView<T> sv{ps_.data(Field::x), ps_.data(Field::y), ps_.data(Field::z),
                         ps_.data(Field::h)};
        const auto res = nlists_.build(domain_.local_tree(), &domain_.halo_tree(), sv, box_,
                                       NeighbourCriterion::symmetric, std::uint32_t(n_owned()),
                                       blocks_ ? blocks_->active() : nullptr);
        max_list_ = res.max_count;
        work_.active = double(blocks_ ? blocks_->active_count() : n_owned());
        work_.pairs = double(res.pairs);
    }

    // SPEC 3-6 (sim/hydro_forces.hpp).
    void hydro_forces() {
        courant_dt_ = exasph::hydro_forces<L>(ps_, nlists_, box_, kernel_.view(), eos_, cfg_,
                                              domain_, gravity_ ? &*gravity_ : nullptr, timer_,
                                              step_ == 0, own_limits_if_blocks());
        if (!blocks_) nlists_.release(); // the sync can use their memory
        timer_.stop(kMomentumEnergy);
    }

    // SPEC 7 (sim/global_step.hpp), or the rungs of block time steps (sim/block_clock.hpp).
    double choose_time_step() {
        const double accel = gravity_ ? cfg_.accel_eps : 0.0;
        if (blocks_) { // closing and opening the steps updates the state: check it first
            if (safety_.changed_before_update(ps_, n_owned())) flags_.raise(kStateChanged);
            const double dt = blocks_->choose(ps_, n_owned(), nlists_, domain_,
                                              {step_ == 0, dt0_, accel, time_, t_end_});
            nlists_.release();
            return dt;
        }
        return global_time_step<L>(ps_, n_owned(), courant_dt_, accel, domain_.collectives(),
                                   step_ == 0, dt0_, dt_m1_, time_, t_end_);
    }

    // SPEC 7 and 2: the state, the AV switch, h and X move on (inputs checked against the step's
    // seals first); block time steps drift every particle, the rest only for the active ones.
    void advance(double dt) {
        if (!blocks_ && safety_.changed_before_update(ps_, n_owned())) flags_.raise(kStateChanged);
        const ParticleRange own = blocks_ ? blocks_->active_range() : ParticleRange(n_owned());
        const double t_next = blocks_ ? blocks_->drift_to_next(ps_, n_owned(), box_) : time_ + dt;
        if (!blocks_) update_state<L>(ps_, n_owned(), box_, dt, dt_m1_);
        if (cfg_.av_switch)
            update_viscosity<L>(ps_, own, blocks_ ? -1.0 : dt, cfg_.alpha_min, cfg_.alpha);
        timer_.stop(kUpdate);
        if (safety_.changed_before_h_update(ps_, n_owned())) flags_.raise(kStateChanged);
        update_smoothing_lengths<L>(ps_, own, cfg_.ng0);
        if (cfg_.volume_elements) update_volume_weights<L>(ps_, own, cfg_.energy_weights);
        if (stirring_) stirring_->advance(step_, dt);
        timer_.stop(kSmoothingLength);
        time_ = t_next;
        dt_m1_ = dt;
        ++step_;
    }

    RunPoint<T> run_point() const { return {restart_state(), box_, diag_}; }

    // All ranks, after a detection by `where` in step `step`: back to the last verified state.
    void roll_back(const std::string& where, std::int64_t step) {
        const RunPoint<T>& point = safety_.roll_back(ps_, where, step, step_);
        box_ = point.box;
        diag_ = point.diag;
        resume(point.rs);
        safety_.seal(ps_, n_owned());
        recovered_ = true;
        timer_.end_step();
    }

    // SPEC 10 sums, run-control flags and the particles' extent (next box): one collective.
    void diagnose(double dt) {
        const double waited = domain_.comm_record().waited_in_step(); // compute: the rest
        work_.compute_sum = work_.compute_max = std::max(0.0, timer_.step_total() - waited);
        std::vector<SumMax> e(kDiagWithExtent + kNumControlFlags + StepWork::kElements);
        work_.pack(e.data() + kDiagWithExtent + kNumControlFlags);
        local_diagnostics(ps_, n_owned(), domain_.n_halo(), exact_, time_ - dt, cfg_.ng0, e.data());
        local_extent(ps_, n_owned(), e.data() + kDiagElements);
        flags_.pack(e.data() + kDiagWithExtent);
        domain_.collectives().allreduce_sum_max(e);
        flags_.unpack(e.data() + kDiagWithExtent);
        diag_ = diagnostics_from(e.data(), domain_.nranks());
        if (exact_.valid() && step_ > 0) diag_.l1_rho = e[11].sum / double(diag_.n);
        diag_.work.unpack(e.data() + kDiagWithExtent + kNumControlFlags);
        diag_.step = step_;
        diag_.time = time_;
        diag_.dt = dt;
        if (stirring_) stirring_->add_energy(dt * diag_.stir_power);
        diag_.e_stir = stirring_ ? stirring_->state().energy_in : 0.0;
        apply_extent(box_, e.data() + kDiagElements);
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
    double time_ = 0.0, dt_m1_, dt0_, t_end_ = -1.0, mass0_ = 0;
    double courant_dt_ = 0; // Courant limit of this step's particles (momentum-energy pass)
    std::int64_t step_ = 0;
    std::uint32_t max_list_ = 0;
    bool recovered_ = false, point_pending_ = false;
    ControlFlags flags_;
    ExactDensity exact_;
    std::optional<GravitySolver<T>> gravity_;
    std::optional<Stirring> stirring_;
    std::optional<BlockClock<T, L>> blocks_; // --timesteps block
    StepWork work_;                          // this rank's
};

} // namespace exasph
