#pragma once
#include <cmath>
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
        SedovSolution s(gamma);
        e.xi0_ = s.xi0();
        e.energy_ = energy;
        e.rho1_ = rho1;
        e.table_.resize(kTable + 1);
        for (int i = 0; i <= kTable; ++i) {
            double xi = double(i) / kTable;
            e.table_[i] = i == 0 ? 0.0 : s.density_ratio(s.v_of_xi(xi));
        }
        return e;
    }
    static ExactDensity noh(double gamma, double rho0, double v0) {
        ExactDensity e;
        e.kind_ = Kind::noh;
        e.noh_ = {gamma, rho0, v0};
        return e;
    }

    bool valid() const { return kind_ != Kind::none; }

    double operator()(double r, double t) const {
        if (kind_ == Kind::noh) return noh_.at(r, t).rho;
        if (kind_ != Kind::sedov || t <= 0) return rho1_;
        const double rs = xi0_ * std::pow(energy_ * t * t / rho1_, 0.2);
        const double xi = r / rs;
        if (xi >= 1) return rho1_;
        const double s = xi * kTable;
        const int i = int(s);
        const double f = s - i;
        return rho1_ * (table_[i] + f * (table_[i + 1] - table_[i]));
    }

  private:
    enum class Kind { none, sedov, noh };
    static constexpr int kTable = 20000;
    Kind kind_ = Kind::none;
    double xi0_ = 0, energy_ = 0, rho1_ = 1;
    std::vector<double> table_;
    NohSolution noh_;
};

} // namespace exasph
