#pragma once
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "exasph/exact/noh.hpp"
#include "exasph/exact/sedov.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// Exact density rho(r, t) of a case that has an analytic solution, cheap enough to evaluate
// for every particle at every step: the Sedov profile is self-similar, so one table of
// G(xi) = rho / rho_1 on xi = r / R(t) serves all times.
class ExactDensity {
    enum class Kind { none, sedov, noh };
    static constexpr int kTable = 20000;

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

    // rho(r) at one time t, as a value that host and device code evaluate (the diagnostics
    // kernel, every particle at every step): the shock radius R(t) (a power) once, then per
    // particle a table lookup. `table` is G on its kTable + 1 points (table() or a copy of it in
    // memory the device reads); it must outlive the value.
    class AtTime {
      public:
        AtTime() = default; // no exact solution: valid() is false
        EXASPH_HD bool valid() const { return kind_ != Kind::none; }
        EXASPH_HD double operator()(double r) const {
            if (kind_ == Kind::noh) return noh_.at(r, t_).rho;
            if (rs_ <= 0) return rho1_;
            const double xi = r / rs_;
            if (xi >= 1) return rho1_;
            const double s = xi * kTable;
            const int i = int(s);
            const double f = s - i;
            return rho1_ * (g_[i] + f * (g_[i + 1] - g_[i]));
        }

      private:
        friend class ExactDensity;
        AtTime(const ExactDensity& e, double t, const double* table)
            : kind_(e.kind_), t_(t), rho1_(e.rho1_), g_(table), noh_(e.noh_) {
            if (e.kind_ == Kind::sedov && t > 0)
                rs_ = e.xi0_ * std::pow(e.energy_ * t * t / e.rho1_, 0.2);
        }
        Kind kind_ = Kind::none;
        double t_ = 0;
        double rs_ = 0; // Sedov's shock radius (0: before the blast, or not Sedov)
        double rho1_ = 1;
        const double* g_ = nullptr;
        NohSolution noh_;
    };
    AtTime at(double t) const { return AtTime(*this, t, table_ ? table_->data() : nullptr); }
    // The same, reading the Sedov table from `table` (a copy of table(), e.g. in device memory).
    AtTime at(double t, const double* table) const { return AtTime(*this, t, table); }
    // Sedov's G(xi) on kTable + 1 points (empty for other cases).
    const std::vector<double>& table() const { return table_ ? *table_ : kNoTable; }

    double operator()(double r, double t) const { return at(t)(r); }

  private:
    static inline const std::vector<double> kNoTable{};
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
