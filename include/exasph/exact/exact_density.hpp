#pragma once
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "exasph/exact/noh.hpp"
#include "exasph/exact/sedov.hpp"

namespace exasph {

// Exact density rho(r, t) of a case that has an analytic solution, cheap enough to evaluate
// for every particle at every step: the Sedov profile is self-similar, so one table of
// G(xi) = rho / rho_1 on xi = r / R(t) serves all times.
class ExactDensity {
  public:
    static ExactDensity sedov(double gamma, double energy, double rho1) {
        ExactDensity e;
        e.kind_ = Kind::sedov;
        e.xi0_ = SedovSolution(gamma).xi0();
        e.energy_ = energy;
        e.rho1_ = rho1;
        e.table_ = sedov_table(gamma);
        return e;
    }
    static ExactDensity noh(double gamma, double rho0, double v0) {
        ExactDensity e;
        e.kind_ = Kind::noh;
        e.noh_ = {gamma, rho0, v0};
        return e;
    }

    bool valid() const { return kind_ != Kind::none; }

    // rho(r) at one time t: the shock radius R(t) (a power, ~50 ns) once, then per particle a
    // table lookup (the diagnostics evaluate it for every particle at every step).
    class AtTime {
      public:
        double operator()(double r) const {
            if (e_.kind_ == Kind::noh) return e_.noh_.at(r, t_).rho;
            if (rs_ <= 0) return e_.rho1_;
            const double xi = r / rs_;
            if (xi >= 1) return e_.rho1_;
            const double s = xi * kTable;
            const int i = int(s);
            const double f = s - i;
            const std::vector<double>& g = *e_.table_;
            return e_.rho1_ * (g[i] + f * (g[i + 1] - g[i]));
        }

      private:
        friend class ExactDensity;
        AtTime(const ExactDensity& e, double t) : e_(e), t_(t) {
            if (e.kind_ == Kind::sedov && t > 0)
                rs_ = e.xi0_ * std::pow(e.energy_ * t * t / e.rho1_, 0.2);
        }
        const ExactDensity& e_;
        double t_;
        double rs_ = 0; // Sedov's shock radius (0: before the blast, or not Sedov)
    };
    AtTime at(double t) const { return AtTime(*this, t); }

    double operator()(double r, double t) const { return at(t)(r); }

  private:
    enum class Kind { none, sedov, noh };
    static constexpr int kTable = 20000;
    Kind kind_ = Kind::none;
    double xi0_ = 0, energy_ = 0, rho1_ = 1;
    std::shared_ptr<const std::vector<double>> table_;
    NohSolution noh_;

    // G(xi) depends on gamma only; a table takes ~0.1 s to make (20k root solves), which runs
    // that build many simulations (the fault-injection test: 600) paid each time. Made once
    // per gamma per process.
    static std::shared_ptr<const std::vector<double>> sedov_table(double gamma) {
        static std::mutex lock;
        static std::map<double, std::shared_ptr<const std::vector<double>>> made;
        const std::lock_guard<std::mutex> guard(lock);
        auto& table = made[gamma];
        if (table) return table;
        const SedovSolution s(gamma);
        auto g = std::make_shared<std::vector<double>>(kTable + 1, 0.0);
        for (int i = 1; i <= kTable; ++i) (*g)[i] = s.density_ratio(s.v_of_xi(double(i) / kTable));
        return table = g;
    }
};

} // namespace exasph
