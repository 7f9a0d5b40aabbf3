#pragma once
#include <cstdint>

#include "exasph/cases/case_context.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"

namespace exasph {

// Gas at rest in the periodic unit box [0, 1)^3 (the turbulence and Jeans cases): rho = 1 (equal
// masses 1/N on the case's points, glass or lattice), an ideal gas of index gamma with sound speed
// c (c^2 = gamma (gamma - 1) u). `shape(pos, u)` may move a particle (inside the box) and change
// its u before it is set; pass [](double*, double&) {} for none.
template <class T, class Shape>
InitialConditions<T> make_periodic_gas(double ng0, double gamma, double sound_speed, double dt0,
                                       const CaseContext& ctx, Shape shape) {
    InitialConditions<T> ic;
    ic.dt0 = dt0;
    ic.eos = {EosKind::ideal_gas, gamma, 0.0};
    ic.box.lo = {T(0), T(0), T(0)};
    ic.box.hi = {T(1), T(1), T(1)};
    ic.box.periodic = {true, true, true};
    const UnitCubePoints points = ctx.points();
    std::uint64_t first = 0, last = 0;
    points.share(ctx.rank, ctx.nranks, first, last);
    const double mass = 1.0 / double(points.size());
    const double h0 = initial_smoothing_length(points.spacing(), ng0);
    const double u0 = sound_speed * sound_speed / (gamma * (gamma - 1));
    auto& ps = ic.particles;
    ps.resize(last - first);
    for (std::uint64_t idx = first; idx < last; ++idx) {
        double pos[3], u = u0;
        points.position(idx, pos[0], pos[1], pos[2]);
        shape(pos, u);
        set_particle(ps, idx - first, idx, {pos[0], pos[1], pos[2]}, {0.0, 0.0, 0.0}, dt0, h0, mass,
                     u);
    }
    return ic;
}

} // namespace exasph
