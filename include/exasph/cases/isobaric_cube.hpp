#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"
#include "exasph/cases/unit_cube_points.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Isobaric cube (Saitoh & Makino 2013; Hopkins 2015): a cube of dense gas, |x|, |y|, |z| < 0.25,
// at rest in pressure balance with light gas in the periodic box [-0.5, 0.5)^3. Equal masses:
// with density contrast 8 the inner cube holds as many points per axis as the whole box (the
// same points at half the spacing). Exactly in equilibrium: any motion is the scheme's error
// at the contact discontinuity. The points are two nested lattices, not glasses (as in Saitoh &
// Makino 2013's and Hopkins 2015's square tests): the union of a glass and its shrunk copy is
// not relaxed at the interface, and its noise moved the particles by ~2 inner spacings (rms) by
// t = 2 with every scheme, eroding the corners that the test measures (docs/validation.md).
struct IsobaricCubeParams {
    int side = 20; // particles across the box outside the cube (and across the cube inside)
    double ng0 = 100;
    double gamma = 5.0 / 3.0;
    double pressure = 2.5;
    double density_out = 1.0; // the inner density is 8 times this
    double dt0 = 1e-4;
    double t_end = 2.0;
};

inline constexpr double kIsobaricCubeHalf = 0.25; // half the side of the dense cube

inline bool inside_isobaric_cube(double x, double y, double z) {
    return std::abs(x) < kIsobaricCubeHalf && std::abs(y) < kIsobaricCubeHalf &&
           std::abs(z) < kIsobaricCubeHalf;
}

// Ids [0, N) are the points of the box (those inside the cube are left out), ids [N, 2N) the
// same points shrunk into the cube; each rank makes its share of both.
template <class T>
InitialConditions<T> make_isobaric_cube(const IsobaricCubeParams& cp, const CaseContext& ctx) {
    if (cp.side < 8 || cp.side % 2)
        throw input_error("isobaric-cube: -n must be even and at least 8", true);
    InitialConditions<T> ic;
    ic.name = "isobaric-cube";
    ic.dt0 = cp.dt0;
    ic.t_end = cp.t_end;
    ic.eos = {EosKind::ideal_gas, cp.gamma, 0.0};
    ic.box.lo = {T(-0.5), T(-0.5), T(-0.5)};
    ic.box.hi = {T(0.5), T(0.5), T(0.5)};
    ic.box.periodic = {true, true, true};
    const UnitCubePoints points = UnitCubePoints::lattice(std::uint64_t(cp.side));
    const std::uint64_t n = points.size();
    std::uint64_t first = 0, last = 0;
    points.share(ctx.rank, ctx.nranks, first, last);
    const double mass = cp.density_out / double(n);
    const double h_out = initial_smoothing_length(points.spacing(), cp.ng0);
    auto& ps = ic.particles;
    ps.resize(0);
    for (const bool inner : {false, true}) {
        const double scale = inner ? 2 * kIsobaricCubeHalf : 1.0;
        const double rho = inner ? 8 * cp.density_out : cp.density_out;
        for (std::uint64_t idx = first; idx < last; ++idx) {
            double x, y, z;
            points.position(idx, x, y, z);
            x = scale * (x - 0.5), y = scale * (y - 0.5), z = scale * (z - 0.5);
            if (!inner && inside_isobaric_cube(x, y, z)) continue;
            const std::size_t s = ps.size();
            ps.resize(s + 1);
            set_particle(ps, s, inner ? n + idx : idx, {x, y, z}, {0.0, 0.0, 0.0}, cp.dt0,
                         h_out * scale, mass, cp.pressure / ((cp.gamma - 1) * rho));
        }
    }
    return ic;
}

inline const CaseInfo& isobaric_cube_case() {
    // A contact discontinuity at rest: the pe scheme (energy weights, no conductivity) by
    // default (config/scheme.hpp).
    static const CaseInfo info = with_scheme(
        Scheme::pe,
        case_info<IsobaricCubeParams>(
            "isobaric-cube",
            "Isobaric cube: a dense cube (contrast 8) at rest in pressure balance, periodic box",
            false,
            {{"pressure", &IsobaricCubeParams::pressure, "the uniform pressure"},
             {"gamma", &IsobaricCubeParams::gamma, "adiabatic index"},
             {"dt0", &IsobaricCubeParams::dt0, "first time step"},
             {"t_end", &IsobaricCubeParams::t_end, "end time"}},
            [](const IsobaricCubeParams& p, const CaseContext& c) {
                return make_isobaric_cube<double>(p, c);
            }));
    return info;
}

} // namespace exasph
