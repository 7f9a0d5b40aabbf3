#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"
#include "exasph/cases/unit_cube_points.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Noh implosion (physics.md §9.3): a sphere of cold gas (rho = 1, gamma = 5/3) falling onto the
// centre at speed 1, in open space. -n counts particles across the sphere's diameter. The default
// radius is 1, not 0.5: the exact solution at time t needs the gas that starts at radius 4t/3 (0.8
// at t = 0.6) to still be falling in.
struct NohParams {
    int side = 40;
    double ng0 = 100;
    double gamma = 5.0 / 3.0;
    double radius = 1.0;
    double speed = 1.0;
    double u0 = 1e-10;
    double density = 1.0;
    double dt0 = 1e-4;
    double t_end = 0.6;
};

template <class T>
InitialConditions<T> make_noh(const NohParams& np, const CaseContext& ctx) {
    if (np.side < 8) throw input_error("noh: -n must be at least 8", true);
    InitialConditions<T> ic;
    ic.name = "noh";
    ic.dt0 = np.dt0;
    ic.t_end = np.t_end;
    ic.eos = {EosKind::ideal_gas, np.gamma, 0.0};
    ic.exact = ExactDensity::noh(np.gamma, np.density, np.speed);
    const T R = T(np.radius);
    ic.box.lo = {-R, -R, -R};
    ic.box.hi = {R, R, R};
    ic.box.periodic = {false, false, false};
    std::uint64_t first = 0, last = 0;
    const UnitCubePoints points = ctx.points();
    points.share(ctx.rank, ctx.nranks, first, last);
    const double dx = 2 * np.radius * points.spacing();
    const double mass = np.density * dx * dx * dx;
    const double h0 = initial_smoothing_length(dx, np.ng0);
    auto& ps = ic.particles;
    ps.resize(0);
    for (std::uint64_t idx = first; idx < last; ++idx) {
        double x, y, z;
        points.position(idx, x, y, z);
        x = np.radius * (2 * x - 1);
        y = np.radius * (2 * y - 1);
        z = np.radius * (2 * z - 1);
        const double r = std::sqrt(x * x + y * y + z * z);
        if (r >= np.radius) continue;
        const std::size_t s = ps.size();
        ps.resize(s + 1);
        const double f = r > 0 ? -np.speed / r : 0.0;
        set_particle(ps, s, idx, {x, y, z}, {f * x, f * y, f * z}, np.dt0, h0, mass, np.u0);
    }
    return ic;
}

inline const CaseInfo& noh_case() {
    static const CaseInfo info = case_info<NohParams>(
        "noh",
        "Noh implosion (docs/physics.md §9.3), a sphere falling onto its centre, exact solution",
        true,
        {{"gamma", &NohParams::gamma, "adiabatic index"},
         {"radius", &NohParams::radius, "radius of the sphere"},
         {"speed", &NohParams::speed, "infall speed"},
         {"u0", &NohParams::u0, "internal energy of the cold gas"},
         {"dt0", &NohParams::dt0, "first time step"},
         {"t_end", &NohParams::t_end, "end time"}},
        [](const NohParams& p, const CaseContext& c) { return make_noh<double>(p, c); });
    return info;
}

} // namespace exasph
