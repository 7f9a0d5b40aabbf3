#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"
#include "exasph/cases/unit_cube_points.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Evrard collapse (physics.md §9.4): a cold self-gravitating gas sphere at rest with rho = M/(2 pi
// R^2 r) (so M(r) = M r^2 / R^2), u = 0.05 G M / R, gamma = 5/3. -n counts points across the
// diameter of the uniform sphere that is stretched into this profile: a point at radius s (of R)
// moves along its ray to r = R s^(3/2), which maps uniform enclosed mass s^3 onto r^2 / R^2.
struct EvrardParams {
    int side = 30;
    double ng0 = 100;
    double gamma = 5.0 / 3.0;
    double mass = 1.0;
    double radius = 1.0;
    double G = 1.0;
    double u0 = 0.05; // in units of G M / R
    double dt0 = 1e-4;
    double t_end = 3.0;
};

inline double evrard_density(const EvrardParams& ep, double r) {
    return ep.mass / (2 * M_PI * ep.radius * ep.radius * r);
}

// Exact potential energy of the profile: -(2/3) G M^2 / R.
inline double evrard_potential_energy(const EvrardParams& ep) {
    return -2.0 / 3.0 * ep.G * ep.mass * ep.mass / ep.radius;
}

// Each rank makes its share; the particle count is summed over the ranks (start-up collective)
// so that every particle carries M / N.
template <class T>
InitialConditions<T> make_evrard(const EvrardParams& ep, const CaseContext& ctx) {
    if (ep.side < 8) throw input_error("evrard: -n must be at least 8", true);
    InitialConditions<T> ic;
    ic.name = "evrard";
    ic.dt0 = ep.dt0;
    ic.t_end = ep.t_end;
    ic.G = ep.G;
    ic.eos = {EosKind::ideal_gas, ep.gamma, 0.0};
    const T R = T(ep.radius);
    ic.box.lo = {-R, -R, -R};
    ic.box.hi = {R, R, R};
    ic.box.periodic = {false, false, false};
    std::uint64_t first = 0, last = 0;
    const UnitCubePoints points = ctx.points();
    points.share(ctx.rank, ctx.nranks, first, last);
    auto& ps = ic.particles;
    ps.resize(0);
    for (std::uint64_t idx = first; idx < last; ++idx) {
        double p[3];
        points.position(idx, p[0], p[1], p[2]);
        double s2 = 0;
        for (double& c : p) {
            c = 2 * c - 1;
            s2 += c * c;
        }
        if (s2 >= 1.0) continue;
        const double scale = ep.radius * std::pow(s2, 0.25); // r / s = R s^(1/2)
        const std::size_t k = ps.size();
        ps.resize(k + 1);
        set_particle(ps, k, idx, {scale * p[0], scale * p[1], scale * p[2]}, {0.0, 0.0, 0.0},
                     ep.dt0, 0.0, 0.0, ep.u0 * ep.G * ep.mass / ep.radius);
    }
    // (a count, summed exactly in double precision below 2^53)
    const auto total = std::uint64_t(ctx.sum_over_ranks(double(ps.size())));
    const double m = ep.mass / double(total);
    for (std::size_t k = 0; k < ps.size(); ++k) {
        const double x = ps[Field::x][k], y = ps[Field::y][k], z = ps[Field::z][k];
        // h from the density at r, but not closer to the centre than half a point spacing (an odd
        // lattice puts a point at r = 0, where rho diverges).
        const double r = std::max(std::sqrt(x * x + y * y + z * z), ep.radius * points.spacing());
        ps[Field::m][k] = T(m);
        ps[Field::h][k] = T(initial_smoothing_length(std::cbrt(m / evrard_density(ep, r)), ep.ng0));
    }
    return ic;
}

inline const CaseInfo& evrard_case() {
    static const CaseInfo info = case_info<EvrardParams>(
        "evrard",
        "Evrard collapse (docs/physics.md §9.4), a cold self-gravitating gas sphere (G = 1)", true,
        {{"gamma", &EvrardParams::gamma, "adiabatic index"},
         {"mass", &EvrardParams::mass, "mass of the sphere"},
         {"radius", &EvrardParams::radius, "radius of the sphere"},
         {"u0", &EvrardParams::u0, "internal energy in G M / R"},
         {"dt0", &EvrardParams::dt0, "first time step"},
         {"t_end", &EvrardParams::t_end, "end time"}},
        [](const EvrardParams& p, const CaseContext& c) { return make_evrard<double>(p, c); });
    return info;
}

} // namespace exasph
