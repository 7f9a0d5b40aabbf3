#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"
#include "exasph/cases/unit_cube_points.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Sedov-Taylor blast wave (physics.md §9.2): periodic box [-0.5, 0.5)^3, rho = 1, gamma = 5/3, cold
// gas (u0) with total energy E deposited as internal energy in a Gaussian exp(-r^2 / width^2).
struct SedovParams {
    int side = 50;
    double ng0 = 100;
    double gamma = 5.0 / 3.0;
    double energy = 1.0;
    double width = 0.1;
    double u0 = 1e-8;
    double density = 1.0;
    double dt0 = 1e-4;
    double t_end = 0.09;
};

// Each rank makes its share; the normalisation of the Gaussian is summed over all ranks
// (start-up collective) so that the particles carry exactly E.
template <class T>
InitialConditions<T> make_sedov(const SedovParams& sp, const CaseContext& ctx) {
    if (sp.side < 8)
        throw input_error("sedov: -n must be at least 8 (2h below half the box)", true);
    InitialConditions<T> ic;
    ic.name = "sedov";
    ic.dt0 = sp.dt0;
    ic.t_end = sp.t_end;
    ic.eos = {EosKind::ideal_gas, sp.gamma, 0.0};
    ic.exact = ExactDensity::sedov(sp.gamma, sp.energy, sp.density);
    ic.box.lo = {T(-0.5), T(-0.5), T(-0.5)};
    ic.box.hi = {T(0.5), T(0.5), T(0.5)};
    ic.box.periodic = {true, true, true};
    const UnitCubePoints points = ctx.points();
    std::uint64_t first = 0, last = 0;
    points.share(ctx.rank, ctx.nranks, first, last);
    const double mass = sp.density / double(points.size());
    const double h0 = initial_smoothing_length(points.spacing(), sp.ng0);
    auto& ps = ic.particles;
    ps.resize(last - first);
    double weight_sum = 0;
    for (std::uint64_t idx = first; idx < last; ++idx) {
        const std::uint64_t s = idx - first;
        double x, y, z;
        points.position(idx, x, y, z);
        x -= 0.5;
        y -= 0.5;
        z -= 0.5;
        set_particle(ps, s, idx, {x, y, z}, {0.0, 0.0, 0.0}, sp.dt0, h0, mass, 0.0);
        const double w = std::exp(-(x * x + y * y + z * z) / (sp.width * sp.width));
        ps[Field::u][s] = T(w); // weight for now
        weight_sum += mass * w;
    }
    weight_sum = ctx.sum_over_ranks(weight_sum);
    for (std::size_t s = 0; s < ps.size(); ++s)
        ps[Field::u][s] = T(sp.u0 + sp.energy * double(ps[Field::u][s]) / weight_sum);
    return ic;
}

inline const CaseInfo& sedov_case() {
    static const CaseInfo info = case_info<SedovParams>(
        "sedov", "Sedov-Taylor blast wave (docs/physics.md §9.2), periodic box, exact solution",
        true,
        {{"gamma", &SedovParams::gamma, "adiabatic index"},
         {"energy", &SedovParams::energy, "blast energy"},
         {"width", &SedovParams::width, "width of the Gaussian energy deposit"},
         {"u0", &SedovParams::u0, "internal energy of the cold gas"},
         {"dt0", &SedovParams::dt0, "first time step"},
         {"t_end", &SedovParams::t_end, "end time"}},
        [](const SedovParams& p, const CaseContext& c) { return make_sedov<double>(p, c); });
    return info;
}

} // namespace exasph
