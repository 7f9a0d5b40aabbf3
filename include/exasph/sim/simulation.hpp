#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "exasph/cases/initial_conditions.hpp"
#include "exasph/config/config.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/io/output_state.hpp"
#include "exasph/io/restart_state.hpp"
#include "exasph/kernel/sinc_kernel.hpp"
#include "exasph/sim/control_flags.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/sim/eos_requirements.hpp"
#include "exasph/sim/initial_potential.hpp"
#include "exasph/sim/phases.hpp"
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
        enable_fields();
        start_gravity(cfg.G >= 0 ? cfg.G : ic.G);
        restart ? resume(*restart) : start();
        diagnose(0.0);
        stirring_ =
            start_stirring(box_, eos_, diag_, cfg.stir_mach >= 0 ? cfg.stir_mach : ic.stir_mach,
                           std::uint64_t(cfg.stir_seed), restart);
        if (stirring_) ps_.enable(Field::stir), diag_.e_stir = stirring_->state().energy_in;
        if (stirring_ && L::kBackend == Backend::cuda) // its modes are in host memory
            throw input_error("driven turbulence (--stir-mach) needs --backend cpu", true);
        if (gravity_) add_initial_potential_energy(comm);
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
        if (domain_.count_particles(ps_, box_, corrupt))
            return roll_back("the state check before step " + std::to_string(step_ + 1), step_ + 1);
        if (safety_.point_due(step_)) safety_.keep_point(ps_, n_owned(), run_point());
        domain_.distribute(ps_, box_);
        timer_.stop(kSync);
        find_neighbours();
        timer_.stop(kNeighbours);
        hydro_forces();
        if (gravity_)
            gravity_->compute(ps_, n_owned(), domain_.assignment(), box_, domain_.curve(),
                              domain_.collectives());
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
        return {time_, step_, dt_m1_, domain_.global_tree().keys(),
                stirring_ ? stirring_->state() : StirState{}};
    }
    // What snapshots and checkpoints read (io/output_state.hpp).
    OutputState<T> output_state() const {
        return {ps_, n_owned(), box_, eos_, restart_state(), diag_.dt, dt0_};
    }
    const EosParams& eos() const { return eos_; }
    // Gravitational constant of the run (0: no self-gravity).
    double gravitational_constant() const { return gravity_ ? gravity_->G() : 0.0; }
    // Target Mach number of the stirring (0: none).
    double stir_mach() const { return stirring_ ? stirring_->mach() : 0.0; }
    double dt0() const { return dt0_; }

    // Steps are shortened so that the run ends exactly at t_end.
    void set_end_time(double t_end) { t_end_ = t_end; }

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
    // Longest neighbour list of the last step on this rank (symmetric criterion).
    std::uint32_t max_list_length() const { return max_list_; }
    // Owned particles of the most loaded rank over the mean (from the last sync).
    double imbalance() const { return domain_.assignment().imbalance(); }
    const std::array<double, kNumPhases>& phase_times() const { return timer_.step_times(); }
    const std::array<double, kNumPhases>& total_phase_times() const { return timer_.total_times(); }

  private:
    // Optional fields, allocated only for the options that use them.
    void enable_fields() {
        ps_.validate();
        if (cfg_.av_limiter) ps_.enable(kHaloGrad); // the strain rate (24 B/particle)
        if (cfg_.av_switch) ps_.enable(Field::alpha), ps_.enable(Field::divv);
        if (cfg_.volume_elements) ps_.enable(Field::xm), ps_.enable(Field::kx);
        ps_.set_narrow_single(!cfg_.double_precision); // --double-precision
        require_eos_inputs(ps_, ps_.size(), eos_, cfg_.energy_weights, domain_.collectives());
    }

    void start_gravity(double G) {
        if (!(G > 0)) return;
        if (box_.any_periodic())
            throw input_error("self-gravity needs an open box: periodic gravity (Ewald "
                              "summation) is not implemented; run with --G 0",
                              true);
        gravity_.emplace(kernel_, G, cfg_.theta, std::uint32_t(cfg_.gravity_leaf_size));
        ps_.enable(Field::phi), ps_.enable(Field::gsoft);
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
        domain_.restore(ps_, rs.leaf_keys);
        if (stirring_) stirring_->restore(rs.stir);
    }

    void find_neighbours() {
        SearchView<T> sv{ps_.data(Field::x), ps_.data(Field::y), ps_.data(Field::z),
                         ps_.data(Field::h)};
        auto res = nlists_.build(domain_.local_tree(), &domain_.halo_tree(), sv, box_,
                                 NeighbourCriterion::symmetric, std::uint32_t(n_owned()));
        max_list_ = res.max_count;
    }

    // SPEC 3-6: density and EOS (Tait: rho0 from the first step), IAD, momentum and energy.
    void hydro_forces() {
        const auto k = kernel_.view();
        if (step_ == 0 && cfg_.volume_elements)
            settle_volume_weights<L>(ps_, nlists_, box_, k, eos_, n_owned(), cfg_.energy_weights,
                                     [&] { domain_.exchange_halos(ps_, kHaloSync); });
        compute_density<L>(ps_, nlists_, box_, k, eos_, step_ == 0 && eos_.kind == EosKind::tait);
        if (gravity_)
            compute_softening_zeta<L>(ps_, nlists_, gravity_->softening().view(), gravity_->G());
        timer_.stop(kDensity);
        domain_.exchange_halos(ps_, kHaloDensity);
        timer_.stop(kDensityHalos);
        const auto diss = Dissipation<T>::of(cfg_.alpha, cfg_.conductivity, cfg_.av_limiter,
                                             cfg_.ng0, cfg_.tensile_stress, cfg_.torque_free,
                                             cfg_.tensile_exponent, cfg_.tensile_stress_positive);
        compute_iad<L>(ps_, nlists_, box_, k, cfg_.av_limiter, cfg_.torque_free, diss);
        domain_.exchange_halos(ps_, cfg_.av_limiter ? kHaloIad | kHaloGrad : kHaloIad);
        timer_.stop(kIad);
        courant_dt_ = compute_momentum_energy<L>(ps_, nlists_, box_, k, diss, T(cfg_.courant));
        if (gravity_) add_softening_correction<L>(ps_, nlists_, k); // SPEC 8's softening
        nlists_.release(); // not needed again this step: the sync can use their memory
        timer_.stop(kMomentumEnergy);
    }

    // SPEC 7: Courant limit (from the momentum-energy pass; with gravity also the acceleration
    // limit), at most 1.1 x the previous step; the first step is the case's dt0 (or less).
    double choose_time_step() {
        double dt_min = std::min(courant_dt_, std::numeric_limits<double>::max());
        if (gravity_ && cfg_.accel_eps > 0)
            dt_min =
                std::min(dt_min, acceleration_time_step_min<L>(ps_, n_owned(), cfg_.accel_eps));
        dt_min = domain_.collectives().allreduce_min(dt_min);
        double dt = step_ == 0 ? std::min(dt0_, dt_min) : limit_time_step(dt_min, dt_m1_);
        if (t_end_ > 0 && time_ + dt > t_end_) dt = std::max(t_end_ - time_, 0.0);
        return dt;
    }

    // SPEC 7 and 2: the state, the AV switch, h and the volume weights move to the next step
    // (their inputs checked against the step's seals first, sim/step_seals.hpp).
    void advance(double dt) {
        if (safety_.changed_before_update(ps_, n_owned())) flags_.raise(kStateChanged);
        update_state<L>(ps_, n_owned(), box_, dt, dt_m1_);
        if (cfg_.av_switch) update_viscosity<L>(ps_, n_owned(), dt, cfg_.alpha_min, cfg_.alpha);
        timer_.stop(kUpdate);
        if (safety_.changed_before_h_update(ps_, n_owned())) flags_.raise(kStateChanged);
        update_smoothing_lengths<L>(ps_, n_owned(), cfg_.ng0);
        if (cfg_.volume_elements) update_volume_weights<L>(ps_, n_owned(), cfg_.energy_weights);
        if (stirring_) stirring_->advance(step_, dt);
        timer_.stop(kSmoothingLength);
        time_ += dt;
        dt_m1_ = dt;
        ++step_;
    }

    RunPoint<T> run_point() const { return {restart_state(), box_, diag_}; }
    // The first row's E_pot, of the initial positions (sim/initial_potential.hpp).
    void add_initial_potential_energy(MPI_Comm comm) {
        diag_.epot = initial_potential_energy(ps_, n_owned(), box_, cfg_, *gravity_, comm);
        diag_.etot = diag_.ekin + diag_.eint + diag_.epot;
    }

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
        std::vector<SumMax> e(kDiagWithExtent + kNumControlFlags);
        local_diagnostics(ps_, n_owned(), domain_.n_halo(), exact_, time_ - dt, cfg_.ng0, e.data());
        Domain<T>::local_extent(ps_, n_owned(), e.data() + kDiagElements);
        flags_.pack(e.data() + kDiagWithExtent);
        domain_.collectives().allreduce_sum_max(e);
        flags_.unpack(e.data() + kDiagWithExtent);
        diag_ = diagnostics_from(e.data(), domain_.nranks());
        if (exact_.valid() && step_ > 0) diag_.l1_rho = e[11].sum / double(diag_.n);
        diag_.step = step_;
        diag_.time = time_;
        diag_.dt = dt;
        if (stirring_) stirring_->add_energy(dt * diag_.stir_power);
        diag_.e_stir = stirring_ ? stirring_->state().energy_in : 0.0;
        Domain<T>::apply_extent(box_, e.data() + kDiagElements);
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
    bool recovered_ = false;
    ControlFlags flags_;
    ExactDensity exact_;
    std::optional<GravitySolver<T>> gravity_;
    std::optional<Stirring> stirring_;
};

} // namespace exasph
