#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"
#include "exasph/cases/unit_cube_points.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Gresho-Chan vortex (Gresho & Chan 1990; Springel 2010): a steady vortex in pressure balance in
// a periodic thin slab [-0.5, 0.5)^2 x [0, depth), rho = 1, gamma = 5/3. With R1 = 0.2 and the
// peak speed v0 at r = R1: v_phi = v0 r / R1 inside R1, v0 (2 - r / R1) out to 2 R1, at rest
// beyond.
struct GreshoChanParams {
    int side = 40; // particles across the box
    double ng0 = 100;
    double gamma = 5.0 / 3.0;
    double density = 1.0;
    double speed = 1.0;    // v0
    double radius = 0.2;   // R1
    double pressure = 5.0; // P0: the pressure at the centre
    double dt0 = 1e-4;
    double t_end = 1.0;
};

// The analytic azimuthal speed of the vortex at radius r.
inline double gresho_vphi(const GreshoChanParams& gp, double r) {
    const double s = r / gp.radius;
    if (s < 1) return gp.speed * s;
    if (s < 2) return gp.speed * (2 - s);
    return 0.0;
}

// The pressure in radial balance, dP/dr = rho v_phi^2 / r, from P0 at the centre.
inline double gresho_pressure(const GreshoChanParams& gp, double r) {
    const double s = std::min(r / gp.radius, 2.0), k = gp.density * gp.speed * gp.speed;
    if (s < 1) return gp.pressure + 0.5 * k * s * s;
    return gp.pressure + k * (0.5 * s * s - 4 * s + 4 + 4 * std::log(s));
}

template <class T>
InitialConditions<T> make_gresho_chan(const GreshoChanParams& gp, const CaseContext& ctx) {
    if (gp.side < 16) throw input_error("gresho-chan: -n must be at least 16", true);
    if (2 * gp.radius >= 0.5)
        throw input_error("gresho-chan: radius must be below 0.25 (the vortex inside the box)",
                          true);
    InitialConditions<T> ic;
    ic.name = "gresho-chan";
    ic.dt0 = gp.dt0;
    ic.t_end = gp.t_end;
    ic.eos = {EosKind::ideal_gas, gp.gamma, 0.0};
    const UnitCubePoints points = ctx.slab_points();
    ic.box.lo = {T(-0.5), T(-0.5), T(0)};
    ic.box.hi = {T(0.5), T(0.5), T(points.depth())};
    ic.box.periodic = {true, true, true};
    std::uint64_t first = 0, last = 0;
    points.share(ctx.rank, ctx.nranks, first, last);
    const double mass = gp.density * points.depth() / double(points.size());
    const double h0 = initial_smoothing_length(points.spacing(), gp.ng0);
    auto& ps = ic.particles;
    ps.resize(last - first);
    for (std::uint64_t idx = first; idx < last; ++idx) {
        double x, y, z;
        points.position(idx, x, y, z);
        x -= 0.5;
        y -= 0.5;
        const double r = std::sqrt(x * x + y * y);
        const double f = r > 0 ? gresho_vphi(gp, r) / r : 0.0;
        const double u = gresho_pressure(gp, r) / ((gp.gamma - 1) * gp.density);
        set_particle(ps, idx - first, idx, {x, y, z}, {-f * y, f * x, 0.0}, gp.dt0, h0, mass, u);
    }
    return ic;
}

inline const CaseInfo& gresho_chan_case() {
    static const CaseInfo info = case_info<GreshoChanParams>(
        "gresho-chan", "Gresho-Chan vortex, a steady vortex in pressure balance (thin slab)", true,
        {{"speed", &GreshoChanParams::speed, "peak azimuthal speed v0"},
         {"radius", &GreshoChanParams::radius, "radius R1 of the peak speed"},
         {"pressure", &GreshoChanParams::pressure, "pressure P0 at the centre"},
         {"gamma", &GreshoChanParams::gamma, "adiabatic index"},
         {"dt0", &GreshoChanParams::dt0, "first time step"},
         {"t_end", &GreshoChanParams::t_end, "end time"}},
        [](const GreshoChanParams& p, const CaseContext& c) {
            return make_gresho_chan<double>(p, c);
        });
    return info;
}

} // namespace exasph
