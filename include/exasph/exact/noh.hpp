#pragma once
#include <cmath>

#include "exasph/util/annotate.hpp"

namespace exasph {

// Noh implosion (physics.md §9.3), spherical: cold gas of density rho0 falling in at speed v0. The
// shock moves out at D = (gamma - 1) v0 / 2; behind it the gas is at rest with
// rho = rho0 ((gamma + 1) / (gamma - 1))^3 and u = v0^2 / 2; ahead of it the converging flow
// compresses the gas as rho = rho0 (1 + v0 t / r)^2.
struct NohSolution {
    double gamma = 5.0 / 3.0, rho0 = 1.0, v0 = 1.0;

    struct State {
        double rho, v, p, u;
    };
    EXASPH_HD double shock_radius(double t) const { return 0.5 * (gamma - 1) * v0 * t; }
    EXASPH_HD double post_shock_density() const {
        double k = (gamma + 1) / (gamma - 1);
        return rho0 * k * k * k;
    }
    EXASPH_HD State at(double r, double t) const {
        if (r < shock_radius(t)) {
            double rho = post_shock_density(), u = 0.5 * v0 * v0;
            return {rho, 0.0, (gamma - 1) * rho * u, u};
        }
        double s = 1 + v0 * t / r;
        return {rho0 * s * s, -v0, 0.0, 0.0};
    }
};

} // namespace exasph
