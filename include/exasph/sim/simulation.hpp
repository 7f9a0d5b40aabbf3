#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <string_view>
#include <unistd.h>
#include <vector>

#include "exasph/cases/initial_conditions.hpp"
#include "exasph/domain/domain.hpp"
#include "exasph/gravity/gravity_solver.hpp"
#include "exasph/sim/config.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/sim/sdc.hpp"
#include "exasph/sph/av_switch.hpp"
#include "exasph/sph/hydro.hpp"
#include "exasph/sph/integrator.hpp"
#include "exasph/sph/sinc_kernel.hpp"
#include "exasph/sph/smoothing_length.hpp"
#include "exasph/sph/timestep.hpp"
#include "exasph/tree/neighbour_lists.hpp"
#include "exasph/util/timer.hpp"

namespace exasph {

// Phases of the step. `sync` is migration + SFC sort + trees + halo discovery and exchange;
// `eos` and `iad` include the halo exchanges that follow them.
enum Phase : std::size_t {
    kSync,
    kNeighbours,
    kDensity,
    kEos,
    kIad,
    kMomentumEnergy,
    kGravity,
    kTimeStep,
    kUpdate,
    kSmoothingLength,
    kDiagnostics,
    kNumPhases
};
inline constexpr std::array<std::string_view, kNumPhases> kPhaseNames{
    "sync",    "neighbours", "density", "eos",      "iad",        "momentum_energy",
    "gravity", "timestep",   "update",  "h_update", "diagnostics"};

// One SPH simulation: the step pipeline of DESIGN.md, each phase timed. Runs on any number of
// MPI ranks of `comm` (one rank included); results do not depend on ranks or threads beyond
// round-off. Collectives per step: global tree counts (sync), minimum dt, diagnostics; with
// self-gravity one more (the leaf multipoles).
// Where a checkpoint left a run: with these and the particles' state fields a run continues
// exactly (bitwise on the same rank count).
struct RestartState {
    double time = 0;
    std::int64_t step = 0;
    double dt_m1 = 0;
    std::vector<std::uint64_t> leaf_keys; // global tree
};

// Run-control flags every rank learns at the end of a step through the diagnostics collective.
enum ControlFlag : std::size_t { kStopRequested, kCheckpointByClock, kNumControlFlags };

template <class T>
class Simulation {
  public:
    // Restarts from a checkpoint's state.
    Simulation(const Config& cfg, InitialConditions<T> ic, const RestartState& rs,
               MPI_Comm comm = MPI_COMM_WORLD)
        : Simulation(cfg, std::move(ic), comm, &rs) {}

    Simulation(const Config& cfg, InitialConditions<T> ic, MPI_Comm comm = MPI_COMM_WORLD,
               const RestartState* restart = nullptr)
        : cfg_(cfg), ps_(std::move(ic.particles)), box_(ic.box), eos_(ic.eos),
          kernel_(sinc_kernel(cfg.kernel_exponent)), nlists_(std::uint32_t(cfg.ngmax)),
          domain_(comm, std::uint32_t(cfg.global_bucket), std::uint32_t(cfg.bucket_size),
                  cfg.curve),
          dt_m1_(ic.dt0), dt0_(ic.dt0), exact_(std::move(ic.exact)) {
        ps_.validate();
        // Optional fields, allocated only for the options that use them.
        if (cfg.av_limiter) ps_.enable(kHaloGrad); // the velocity gradient (72 B/particle)
        if (cfg.av_switch) ps_.enable(Field::alpha), ps_.enable(Field::divv);
        if (cfg.volume_elements) ps_.enable(Field::xm), ps_.enable(Field::kx);
        if (eos_.kind == EosKind::tait && !(ps_.enabled(Field::rho0) && ps_.enabled(Field::p0)))
            throw input_error("the Tait EOS needs the reference fields rho0 and p0", true);
        if (cfg.on_sdc != "rollback" && cfg.on_sdc != "abort" && cfg.on_sdc != "off")
            throw input_error("--on-sdc must be abort, rollback or off, got " + cfg.on_sdc, true);
        if (cfg.sdc_rollback_store != "memory" && cfg.sdc_rollback_store != "disk")
            throw input_error(
                "--sdc-rollback-store must be memory or disk, got " + cfg.sdc_rollback_store, true);
        if (cfg.sdc_rollback_store == "disk")
            rollback_.state.keep_on_disk(
                (std::filesystem::path(cfg.sdc_rollback_dir.empty() ? cfg.out_dir
                                                                    : cfg.sdc_rollback_dir) /
                 // the process id keeps runs that share a scratch directory apart
                 (".sdc-rollback-rank" + std::to_string(domain_.rank()) + "-" +
                  std::to_string(::getpid()) + ".bin"))
                    .string());
        if (!cfg.inject_fault.empty()) fault_ = parse_fault(cfg.inject_fault);
        const double G = cfg.G >= 0 ? cfg.G : ic.G;
        if (G > 0) {
            if (box_.periodic[0] || box_.periodic[1] || box_.periodic[2])
                throw input_error("self-gravity needs an open box: periodic gravity (Ewald "
                                  "summation) is not implemented; run with --G 0",
                                  true);
            gravity_.emplace(kernel_, G, cfg.theta, std::uint32_t(cfg.gravity_bucket));
            ps_.enable(Field::phi);
        }
        if (restart) {
            time_ = restart->time;
            step_ = restart->step;
            dt_m1_ = restart->dt_m1;
            domain_.restore(ps_, restart->leaf_keys);
        } else {
            if (cfg.av_switch)
                std::fill(ps_[Field::alpha].begin(), ps_[Field::alpha].end(), T(cfg.alpha));
            if (cfg.volume_elements) ps_[Field::xm] = ps_[Field::m]; // weights of the 1st density
            domain_.init(ps_, box_);
        }
        diagnose(0.0);
        if (gravity_) add_initial_potential_energy(comm);
        mass0_ = diag_.mass;
        if (sdc_on()) guard_.seal(ps_, n_owned());
    }

    void step() {
        timer_.begin_step();
        timer_.start();
        recovered_ = false;
        if (fault_.step == step_ + 1 && !fault_done_) {
            inject_fault(ps_, n_owned(), fault_); // on the rank that owns the particle
            fault_done_ = true;                   // once: a rollback replays the step cleanly
        }
        const bool alarm = sdc_on() && !verify_state();
        // Every sdc_rollback_every steps the checked state becomes the rollback point, once the
        // sync's collective has shown that no rank found a problem: it replaces the previous
        // point in place (one copy of the state, not two).
        const bool keep_point =
            cfg_.on_sdc == "rollback" && step_ % std::max(cfg_.sdc_rollback_every, 1) == 0;
        domain_.sync(ps_, box_, alarm, [&] {
            if (keep_point) save_rollback_point();
        });
        if (domain_.alarm())
            return recover("the state check before step " + std::to_string(step_ + 1), step_ + 1);
        timer_.stop(kSync);
        find_neighbours();
        timer_.stop(kNeighbours);
        // density, EOS and the pressure-force coefficient in one pass; the Tait EOS takes its
        // reference density from the first step
        compute_density(ps_, nlists_, box_, kernel_.view(), eos_,
                        step_ == 0 && eos_.kind == EosKind::tait);
        timer_.stop(kDensity);
        domain_.exchange_halos(ps_, kHaloDensity);
        timer_.stop(kEos);
        compute_iad(ps_, nlists_, box_, kernel_.view(), cfg_.av_limiter);
        domain_.exchange_halos(ps_, cfg_.av_limiter ? kHaloIad | kHaloGrad : kHaloIad);
        timer_.stop(kIad);
        courant_dt_ = compute_momentum_energy(ps_, nlists_, box_, kernel_.view(), dissipation(),
                                              T(cfg_.courant));
        nlists_.release(); // not needed again this step: the sync can use their memory
        timer_.stop(kMomentumEnergy);
        if (gravity_)
            gravity_->compute(ps_, n_owned(), domain_.assignment(), box_, domain_.curve(),
                              domain_.collectives());
        timer_.stop(kGravity);
        double dt = choose_time_step();
        timer_.stop(kTimeStep);
        update_state(dt);
        if (cfg_.av_switch) update_viscosity(dt);
        timer_.stop(kUpdate);
        update_smoothing_lengths();
        if (cfg_.volume_elements) update_volume_weights();
        timer_.stop(kSmoothingLength);
        time_ += dt;
        dt_m1_ = dt;
        ++step_;
        const Diagnostics before = diag_;
        diagnose(dt);
        if (sdc_on()) {
            std::string why = conservation_violation(before, diag_, mass0_, !gravity_);
            if (!why.empty()) {
                if (domain_.rank() == 0) sdc_detail_ = "watchdog: " + why;
                return recover("the conservation watchdog after step " + std::to_string(step_),
                               step_);
            }
            guard_.seal(ps_, n_owned());
            press_ok_ = true;
        }
        timer_.stop(kDiagnostics);
        timer_.end_step();
    }

    // Silent-data-corruption handling (issue 8). How many times the run was rolled back, and
    // whether the last step() ended in a rollback instead of a step (then diagnostics() are
    // those of the step rolled back to, and the steps after it are computed again).
    std::int64_t recoveries() const { return recoveries_; }
    bool recovered() const { return recovered_; }
    // This rank's description of the last detection ("" if another rank detected it).
    const std::string& sdc_detail() const { return sdc_detail_; }
    const std::string& sdc_summary() const { return sdc_summary_; }
    // The step before which (state check) or in which (watchdog) the last detection happened.
    std::int64_t sdc_detection_step() const { return sdc_step_; }

    // Raises a control flag on this rank; after the next step every rank sees it (flag()).
    void raise_flag(ControlFlag f) { local_flags_[f] = 1.0; }
    bool flag(ControlFlag f) const { return flags_[f] > 0; }

    // For checkpoints: what RestartState and the owned state fields need.
    RestartState restart_state() const {
        return {time_, step_, dt_m1_, domain_.global_tree().keys()};
    }
    const EosParams& eos() const { return eos_; }
    // Gravitational constant of the run (0: no self-gravity).
    double gravitational_constant() const { return gravity_ ? gravity_->G() : 0.0; }
    double dt0() const { return dt0_; }

    // Glass relaxation (damped SPH): after a step, stop every particle where it is and restore
    // the internal energy, so that the next step moves particles only along the pressure forces.
    void reset_to_rest(T u) {
        for (std::size_t i = 0; i < n_owned(); ++i) {
            ps_[Field::vx][i] = ps_[Field::vy][i] = ps_[Field::vz][i] = T(0);
            ps_[Field::x_m1][i] = ps_[Field::x][i];
            ps_[Field::y_m1][i] = ps_[Field::y][i];
            ps_[Field::z_m1][i] = ps_[Field::z][i];
            ps_[Field::u][i] = u;
            ps_[Field::du_m1][i] = T(0);
        }
    }

    // Relative standard deviation of the particle densities of the last step (output-time
    // collective).
    double density_scatter() const {
        double s[3] = {0, 0, double(n_owned())};
        for (std::size_t i = 0; i < n_owned(); ++i) {
            const double rho = ps_.narrow(Field::rho)[i];
            s[0] += rho;
            s[1] += rho * rho;
        }
        MPI_Allreduce(MPI_IN_PLACE, s, 3, MPI_DOUBLE, MPI_SUM, domain_.comm());
        double mean = s[0] / s[2];
        return std::sqrt(std::max(s[1] / s[2] - mean * mean, 0.0)) / mean;
    }

    // Steps are shortened so that the run ends exactly at t_end.
    void set_end_time(double t_end) { t_end_ = t_end; }

    const Diagnostics& diagnostics() const { return diag_; }
    // Owned particles are [0, n_owned()); halos (if any) follow.
    const ParticleSet<T>& particles() const { return ps_; }
    std::size_t n_owned() const { return domain_.n_owned(); }
    const Domain<T>& domain() const { return domain_; }
    std::int64_t collective_count() { return domain_.collectives().count(); }
    const Box<T>& box() const { return box_; }
    double time() const { return time_; }
    std::int64_t step_count() const { return step_; }
    // Longest neighbour list of the last step on this rank (symmetric criterion).
    std::uint32_t max_list_length() const { return max_list_; }
    // Owned particles of the most loaded rank over the mean (from the last sync).
    double imbalance() const {
        const auto& c = domain_.assignment().count;
        if (c.empty()) return 1.0;
        double total = 0, mx = 0;
        for (auto v : c) {
            total += double(v);
            mx = std::max(mx, double(v));
        }
        return mx / (total / double(c.size()));
    }
    const std::array<double, kNumPhases>& phase_times() const { return timer_.step_times(); }
    const std::array<double, kNumPhases>& total_phase_times() const { return timer_.total_times(); }

  private:
    void find_neighbours() {
        SearchView<T> sv{ps_.data(Field::x), ps_.data(Field::y), ps_.data(Field::z),
                         ps_.data(Field::h)};
        auto res = nlists_.build(domain_.local_tree(), &domain_.halo_tree(), sv, box_,
                                 NeighbourCriterion::symmetric, std::uint32_t(n_owned()));
        max_list_ = res.max_count;
    }

    // SPEC 4: the Tait reference density is the density measured at step 0, per particle.
    // SPEC 7: Courant limit over all particles (with gravity also the acceleration limit), at
    // most 1.1 x the previous step; the first step is the case's dt0 (or less, if the limits
    // demand it). One collective (min).
    double choose_time_step() {
        const T* h = ps_.data(Field::h);
        const T *ax = ps_.data(Field::ax), *ay = ps_.data(Field::ay), *az = ps_.data(Field::az);
        const auto n = static_cast<std::int64_t>(n_owned());
        const double eps = gravity_ ? cfg_.accel_eps : 0.0;
        // The Courant limit comes from the momentum-energy pass (courant_dt_).
        double dt_min = std::min(courant_dt_, std::numeric_limits<double>::max());
        if (eps > 0) {
#pragma omp parallel for schedule(static) reduction(min : dt_min)
            for (std::int64_t i = 0; i < n; ++i)
                dt_min =
                    std::min(dt_min, acceleration_time_step(double(h[i]), double(ax[i]),
                                                            double(ay[i]), double(az[i]), eps));
        }
        dt_min = domain_.collectives().allreduce_min(dt_min);
        double dt = step_ == 0 ? std::min(dt0_, dt_min) : limit_time_step(dt_min, dt_m1_);
        if (t_end_ > 0 && time_ + dt > t_end_) dt = std::max(t_end_ - time_, 0.0);
        return dt;
    }

    // SPEC 7: Press scheme for x and v, Adams-Bashforth for u, periodic wrap of x and x_{n-1}.
    void update_state(double dt_d) {
        auto p = make_view(ps_);
        const auto n = static_cast<std::int64_t>(n_owned());
        const T dt = T(dt_d), dt_m1 = T(dt_m1_);
        const Field pos[3] = {Field::x, Field::y, Field::z};
        const Field prev[3] = {Field::x_m1, Field::y_m1, Field::z_m1};
        const Field vel[3] = {Field::vx, Field::vy, Field::vz};
        const Field acc[3] = {Field::ax, Field::ay, Field::az};
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) {
            for (int d = 0; d < 3; ++d) {
                T x = p[pos[d]][i];
                auto r = press_update(x, p[prev[d]][i], p[acc[d]][i], dt, dt_m1);
                T shift = box_.wrap_shift(r.x, d);
                p[pos[d]][i] = r.x + shift;
                p[prev[d]][i] = x + shift;
                p[vel[d]][i] = r.v;
            }
            p[Field::u][i] = adams_bashforth_energy(p[Field::u][i], p[Field::du][i],
                                                    p[Field::du_m1][i], dt, dt_m1);
            p[Field::du_m1][i] = p[Field::du][i];
        }
    }

    // The AV switch: alpha follows the compression of the step (SPEC 6, sph/av_switch.hpp).
    void update_viscosity(double dt) {
        T* alpha = ps_.data(Field::alpha);
        const T *divv = ps_.data(Field::divv), *h = ps_.data(Field::h);
        const float* c = ps_.narrow(Field::c);
        const auto n = static_cast<std::int64_t>(n_owned());
        const T amin = T(cfg_.alpha_min), amax = T(cfg_.alpha), decay = T(cfg_.av_decay);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i)
            alpha[i] = evolve_alpha(alpha[i], divv[i], h[i], T(c[i]), T(dt), amin, amax, decay);
    }

    Dissipation<T> dissipation() const {
        Dissipation<T> d;
        d.alpha = T(cfg_.alpha);
        d.alpha_u = T(cfg_.conductivity);
        d.reconstruct = cfg_.av_limiter;
        // About the mean particle spacing in units of h: (4/3 pi (2h)^3 / ng0)^(1/3) / h.
        d.eta_crit = T(std::cbrt(32.0 * std::numbers::pi / (3.0 * cfg_.ng0)));
        return d;
    }

    // Volume elements: X_a = (m_a / rho_a)^p from this step's density, used by the next step.
    void update_volume_weights() {
        T* xm = ps_.data(Field::xm);
        const T* m = ps_.data(Field::m);
        const float* rho = ps_.narrow(Field::rho);
        const auto n = static_cast<std::int64_t>(n_owned());
        const double pw = cfg_.ve_exponent;
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) xm[i] = T(std::pow(double(m[i] / rho[i]), pw));
    }

    bool sdc_on() const {
        return cfg_.on_sdc != "off";
    }

    // Checks the owned state at rest (hashes sealed at the end of the last step, physics
    // invariants). Returns false on corruption.
    bool verify_state() {
        sdc_detail_ =
            guard_.check(ps_, n_owned(), box_, dt_m1_, press_ok_, eos_.kind == EosKind::ideal_gas);
        return sdc_detail_.empty();
    }

    void save_rollback_point() {
        rollback_.state.save(ps_, n_owned());
        rollback_.rs = restart_state();
        rollback_.box = box_;
        rollback_.diag = diag_;
        rollback_.valid = true;
    }

    // All ranks: after a detection (by `where`, in or before step `step`), roll back to the last
    // verified state (or abort).
    void recover(const std::string& where, std::int64_t step) {
        ++recoveries_;
        sdc_step_ = step;
        const bool can = cfg_.on_sdc == "rollback" && rollback_.valid && recoveries_ <= 100 &&
                         rollback_.rs.step < step_ + 1;
        std::string detail = sdc_detail_.empty() ? "found on another rank" : sdc_detail_;
        if (!can)
            throw Error("silent data corruption detected by " + where + " (" + detail + "); " +
                            (cfg_.on_sdc == "abort" ? "aborting (--on-sdc abort)"
                                                    : "no verified state to roll back to"),
                        1, true);
        sdc_summary_ = "corruption detected by " + where + " (" + detail +
                       "): rolled back to step " + std::to_string(rollback_.rs.step);
        rollback_.state.restore(ps_);
        box_ = rollback_.box;
        time_ = rollback_.rs.time;
        step_ = rollback_.rs.step;
        dt_m1_ = rollback_.rs.dt_m1;
        diag_ = rollback_.diag;
        domain_.restore(ps_, rollback_.rs.leaf_keys);
        guard_.seal(ps_, n_owned());
        press_ok_ = false; // accelerations are not part of the rollback point
        recovered_ = true;
        timer_.end_step();
    }

    // The first diagnostics row needs the potential energy of the initial positions, before any
    // step has computed forces: a throw-away domain and gravity pass over a copy of the particles
    // (start-up only; the run's own domain is left as it is, so restarts stay exact).
    void add_initial_potential_energy(MPI_Comm comm) {
        ParticleSet<T> copy = ps_;
        copy.resize(n_owned());
        Box<T> box = box_;
        Domain<T> dom(comm, std::uint32_t(cfg_.global_bucket), std::uint32_t(cfg_.bucket_size),
                      cfg_.curve);
        dom.init(copy, box);
        dom.sync(copy, box);
        gravity_->compute(copy, dom.n_owned(), dom.assignment(), box, dom.curve(),
                          dom.collectives());
        double e = 0;
        for (std::size_t i = 0; i < dom.n_owned(); ++i)
            e += 0.5 * double(copy[Field::m][i]) * copy[Field::phi][i];
        MPI_Allreduce(MPI_IN_PLACE, &e, 1, MPI_DOUBLE, MPI_SUM, comm);
        diag_.epot = e;
        diag_.etot = diag_.ekin + diag_.eint + diag_.epot;
    }

    void update_smoothing_lengths() {
        T* h = ps_.data(Field::h);
        const float* nc = ps_.narrow(Field::nc);
        const auto n = static_cast<std::int64_t>(n_owned());
        const T ng0 = T(cfg_.ng0);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) h[i] = update_smoothing_length(h[i], T(nc[i]), ng0);
    }

    // SPEC 10 sums, and the extent of the particles for next step's box: one collective.
    void diagnose(double dt) {
        std::vector<SumMax> e(kDiagWithExtent + kNumControlFlags);
        local_diagnostics(ps_, n_owned(), domain_.n_halo(), exact_, time_ - dt, e.data());
        Domain<T>::local_extent(ps_, n_owned(), e.data() + kDiagElements);
        for (std::size_t f = 0; f < kNumControlFlags; ++f)
            e[kDiagWithExtent + f] = {0.0, local_flags_[f]};
        domain_.collectives().allreduce_sum_max(e);
        for (std::size_t f = 0; f < kNumControlFlags; ++f) {
            flags_[f] = e[kDiagWithExtent + f].max;
            local_flags_[f] = 0.0;
        }
        diag_ = diagnostics_from(e.data(), domain_.nranks());
        if (exact_.valid() && step_ > 0) diag_.l1_rho = e[11].sum / double(diag_.n);
        diag_.step = step_;
        diag_.time = time_;
        diag_.dt = dt;
        Domain<T>::apply_extent(box_, e.data() + kDiagElements);
    }

    Config cfg_;
    ParticleSet<T> ps_;
    Box<T> box_;
    EosParams eos_;
    KernelTable<T> kernel_;
    NeighbourLists<T> nlists_;
    Domain<T> domain_;
    PhaseTimer<kNumPhases> timer_;
    Diagnostics diag_;
    double time_ = 0.0;
    double dt_m1_;
    double dt0_;
    double t_end_ = -1.0;
    std::int64_t step_ = 0;
    std::uint32_t max_list_ = 0;
    double courant_dt_ = 0; // Courant limit of this step's particles (momentum-energy pass)
    std::array<double, kNumControlFlags> local_flags_{}, flags_{};
    ExactDensity exact_;
    std::optional<GravitySolver<T>> gravity_;
    // Silent-data-corruption defences (sim/sdc.hpp).
    struct RollbackPoint {
        StateStore<T> state; // in memory, or on disk (--sdc-rollback-store disk)
        RestartState rs;
        Box<T> box;
        Diagnostics diag;
        bool valid = false;
    };
    StateGuard<T> guard_;
    RollbackPoint rollback_;
    FaultSpec fault_;
    bool fault_done_ = false, press_ok_ = false, recovered_ = false;
    double mass0_ = 0;
    std::int64_t recoveries_ = 0, sdc_step_ = -1;
    std::string sdc_detail_, sdc_summary_;
};

} // namespace exasph
