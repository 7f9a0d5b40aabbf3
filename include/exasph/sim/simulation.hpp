#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include "exasph/cases/initial_conditions.hpp"
#include "exasph/sim/config.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/sim/sfc_order.hpp"
#include "exasph/sph/hydro.hpp"
#include "exasph/sph/integrator.hpp"
#include "exasph/sph/sinc_kernel.hpp"
#include "exasph/sph/smoothing_length.hpp"
#include "exasph/sph/timestep.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/tree/octree.hpp"
#include "exasph/util/timer.hpp"

namespace exasph {

enum Phase : std::size_t {
    kSort,
    kTree,
    kNeighbours,
    kDensity,
    kEos,
    kIad,
    kMomentumEnergy,
    kTimeStep,
    kUpdate,
    kSmoothingLength,
    kDiagnostics,
    kNumPhases
};
inline constexpr std::array<std::string_view, kNumPhases> kPhaseNames{
    "sort",     "tree",   "neighbours", "density",    "eos", "iad", "momentum_energy",
    "timestep", "update", "h_update",   "diagnostics"};

// One SPH simulation on one node: the step pipeline of DESIGN.md, each phase timed.
template <class T>
class Simulation {
  public:
    Simulation(const Config& cfg, InitialConditions<T> ic)
        : cfg_(cfg), ps_(std::move(ic.particles)), box_(ic.box), eos_(ic.eos),
          kernel_(sinc_kernel(cfg.kernel_exponent)), nlists_(std::uint32_t(cfg.ngmax)),
          dt_m1_(ic.dt0), dt0_(ic.dt0) {
        ps_.validate();
        diag_ = measure_conserved(ps_);
    }

    void step() {
        timer_.begin_step();
        timer_.start();
        sort_along_sfc();
        timer_.stop(kSort);
        build_tree();
        timer_.stop(kTree);
        find_neighbours();
        timer_.stop(kNeighbours);
        compute_density(ps_, nlists_, box_, kernel_.view());
        if (step_ == 0 && eos_.kind == EosKind::tait) ps_[Field::rho0] = ps_[Field::rho];
        timer_.stop(kDensity);
        compute_eos(ps_, eos_);
        timer_.stop(kEos);
        compute_iad(ps_, nlists_, box_, kernel_.view());
        timer_.stop(kIad);
        compute_momentum_energy(ps_, nlists_, box_, kernel_.view(), T(cfg_.alpha));
        timer_.stop(kMomentumEnergy);
        double dt = choose_time_step();
        timer_.stop(kTimeStep);
        update_state(dt);
        timer_.stop(kUpdate);
        update_smoothing_lengths();
        timer_.stop(kSmoothingLength);
        time_ += dt;
        dt_m1_ = dt;
        ++step_;
        diag_ = measure_conserved(ps_);
        diag_.step = step_;
        diag_.time = time_;
        diag_.dt = dt;
        timer_.stop(kDiagnostics);
        timer_.end_step();
    }

    // Steps are shortened so that the run ends exactly at t_end.
    void set_end_time(double t_end) { t_end_ = t_end; }

    const Diagnostics& diagnostics() const { return diag_; }
    const ParticleSet<T>& particles() const { return ps_; }
    const Box<T>& box() const { return box_; }
    double time() const { return time_; }
    std::int64_t step_count() const { return step_; }
    // Longest neighbour list of the last step (symmetric criterion); above ngmax is reported.
    std::uint32_t max_list_length() const { return max_list_; }
    const std::array<double, kNumPhases>& phase_times() const { return timer_.step_times(); }
    const std::array<double, kNumPhases>& total_phase_times() const { return timer_.total_times(); }

  private:
    void sort_along_sfc() {
        fit_open_axes(box_, ps_);
        keys_ = sort_along_curve(ps_, box_, cfg_.curve);
    }

    void build_tree() {
        tree_.build(keys_.data(), std::uint32_t(ps_.size()), std::uint32_t(cfg_.bucket_size));
        tree_.update_bounds(ps_.data(Field::x), ps_.data(Field::y), ps_.data(Field::z),
                            ps_.data(Field::h));
    }

    void find_neighbours() {
        SearchView<T> sv{ps_.data(Field::x), ps_.data(Field::y), ps_.data(Field::z),
                         ps_.data(Field::h)};
        auto res = nlists_.build(tree_, sv, box_, NeighbourCriterion::symmetric,
                                 std::uint32_t(ps_.size()));
        max_list_ = res.max_count;
    }

    // SPEC 7: Courant limit over all particles, at most 1.1 x the previous step; the first step
    // is the case's dt0 (or less, if the Courant limit demands it).
    double choose_time_step() {
        const T *h = ps_.data(Field::h), *vs = ps_.data(Field::vsig_max), *c = ps_.data(Field::c);
        const auto n = static_cast<std::int64_t>(ps_.size());
        const T courant = T(cfg_.courant);
        double dt_min = std::numeric_limits<double>::max();
#pragma omp parallel for schedule(static) reduction(min : dt_min)
        for (std::int64_t i = 0; i < n; ++i)
            dt_min = std::min(dt_min, double(courant_time_step(h[i], vs[i], c[i], courant)));
        double dt = step_ == 0 ? std::min(dt0_, dt_min) : limit_time_step(dt_min, dt_m1_);
        if (t_end_ > 0 && time_ + dt > t_end_) dt = std::max(t_end_ - time_, 0.0);
        return dt;
    }

    // SPEC 7: Press scheme for x and v, Adams-Bashforth for u, periodic wrap of x and x_{n-1}.
    void update_state(double dt_d) {
        auto p = make_view(ps_);
        const auto n = static_cast<std::int64_t>(ps_.size());
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

    void update_smoothing_lengths() {
        T* h = ps_.data(Field::h);
        const T* nc = ps_.data(Field::nc);
        const auto n = static_cast<std::int64_t>(ps_.size());
        const T ng0 = T(cfg_.ng0);
#pragma omp parallel for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) h[i] = update_smoothing_length(h[i], nc[i], ng0);
    }

    Config cfg_;
    ParticleSet<T> ps_;
    Box<T> box_;
    EosParams eos_;
    KernelTable<T> kernel_;
    Octree<T> tree_;
    NeighbourLists<T> nlists_;
    std::vector<std::uint64_t> keys_;
    PhaseTimer<kNumPhases> timer_;
    Diagnostics diag_;
    double time_ = 0.0;
    double dt_m1_;
    double dt0_;
    double t_end_ = -1.0;
    std::int64_t step_ = 0;
    std::uint32_t max_list_ = 0;
};

} // namespace exasph
