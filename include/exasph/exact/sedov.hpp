#pragma once
#include <cmath>
#include <stdexcept>
#include <vector>

namespace exasph {

// Sedov-Taylor point explosion in a uniform cold gas (physics.md §9.2), spherical, any gamma in (1,
// 7). Landau & Lifshitz (Fluid Mechanics, section 106) reduce the self-similar equations to
// implicit relations in the variable V (v = (2 r / 5 t) V): the radius xi = r / R_shock, the
// density G = rho / rho_1 and Z = (25 t^2 / 4 r^2) c^2 are closed-form functions of V, which runs
// from 2/(gamma+1) at the shock to 1/gamma at the centre. This class inverts xi(V) by bisection and
// obtains xi_0 (R = xi_0 (E t^2 / rho_1)^(1/5)) from the energy integral by quadrature.
class SedovSolution {
  public:
    struct State {
        double rho, v, p, u;
    };

    explicit SedovSolution(double gamma) : g_(gamma) {
        if (!(gamma > 1.0 && gamma < 7.0)) throw std::invalid_argument("Sedov: need 1 < gamma < 7");
        nu1_ = -(13 * g_ * g_ - 7 * g_ + 12) / ((3 * g_ - 1) * (2 * g_ + 1));
        nu2_ = 5 * (g_ - 1) / (2 * g_ + 1);
        nu3_ = 3 / (2 * g_ + 1);
        nu4_ = -nu1_ / (2 - g_);
        nu5_ = -2 / (2 - g_);
        xi0_ = std::pow(25.0 / (16.0 * M_PI * energy_integral()), 0.2);
    }

    double gamma() const { return g_; }
    double xi0() const { return xi0_; }
    double shock_radius(double E, double rho1, double t) const {
        return xi0_ * std::pow(E * t * t / rho1, 0.2);
    }

    // The exact state at radius r and time t > 0 (cold, at rest, outside the shock).
    State at(double r, double t, double E, double rho1) const {
        const double rs = shock_radius(E, rho1, t);
        if (r >= rs) return {rho1, 0.0, 0.0, 0.0};
        const double V = v_of_xi(r / rs);
        const double G = density_ratio(V), Z = z_of(V);
        const double rho = rho1 * G;
        const double v = 2.0 * r / (5.0 * t) * V;
        const double c2 = 4.0 * r * r / (25.0 * t * t) * Z;
        const double p = rho * c2 / g_;
        return {rho, v, p, p / ((g_ - 1) * rho)};
    }

    // xi(V) and G(V) of the implicit solution.
    double xi_of(double V) const {
        double a = 0.5 * (g_ + 1) * V;
        double b = (g_ + 1) / (7 - g_) * (5 - (3 * g_ - 1) * V);
        double c = (g_ + 1) / (g_ - 1) * (g_ * V - 1);
        return std::pow(std::pow(a, -2.0) * std::pow(b, nu1_) * std::pow(c, nu2_), 0.2);
    }
    double density_ratio(double V) const {
        double c = (g_ + 1) / (g_ - 1) * (g_ * V - 1);
        double b = (g_ + 1) / (7 - g_) * (5 - (3 * g_ - 1) * V);
        double e = (g_ + 1) / (g_ - 1) * (1 - V);
        return (g_ + 1) / (g_ - 1) * std::pow(c, nu3_) * std::pow(b, nu4_) * std::pow(e, nu5_);
    }
    double z_of(double V) const { return g_ * (g_ - 1) * (1 - V) * V * V / (2 * (g_ * V - 1)); }

    // V with xi(V) = xi, by bisection between the centre (1/gamma) and the shock (2/(gamma+1)).
    double v_of_xi(double xi) const {
        double lo = 1.0 / g_, hi = 2.0 / (g_ + 1);
        for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
            double mid = 0.5 * (lo + hi);
            (xi_of(mid) < xi ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    }

  private:
    // I = int_0^1 G xi^4 [V^2 / 2 + Z / (gamma (gamma - 1))] dxi, with E = (16 pi / 25) xi_0^5 I
    // for E, rho_1 = 1 (Simpson on 4000 intervals in xi).
    double energy_integral() const {
        const int n = 4000;
        double sum = 0;
        for (int i = 0; i <= n; ++i) {
            double xi = double(i) / n;
            double f = 0;
            if (i > 0) {
                double V = v_of_xi(xi);
                f = density_ratio(V) * std::pow(xi, 4) * (0.5 * V * V + z_of(V) / (g_ * (g_ - 1)));
            }
            sum += (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * f;
        }
        return sum / (3.0 * n);
    }

    double g_;
    double nu1_, nu2_, nu3_, nu4_, nu5_;
    double xi0_;
};

} // namespace exasph
