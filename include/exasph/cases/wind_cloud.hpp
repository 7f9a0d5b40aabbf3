#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"
#include "exasph/cases/unit_cube_points.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Wind-cloud ("blob") test (Agertz et al. 2007; the reference code's box): a cloud of radius R
// and density contrast chi at rest in pressure balance with a supersonic wind (rho = 1,
// u = 1.5, v_x = 2.7) in the periodic box [0, 1) x [0, 0.25)^2. Equal masses: the wind is
// four tiles of the n^3 points across the 0.25 cube, the cloud the same n^3 points shrunk by
// chi^(1/3) around its centre, cut to the sphere.
struct WindCloudParams {
    int side = 20; // wind particles across the box's 0.25
    double ng0 = 100;
    double gamma = 5.0 / 3.0;
    double radius = 0.025;
    double contrast = 10.0; // chi = rho_cloud / rho_wind
    double u_wind = 1.5;
    double v_wind = 2.7;
    double dt0 = 1e-5;
    double t_end = 0; // 0: 4 tau_KH of the radius (0.3748 for 0.025)
};

inline constexpr double kWindCloudWidth = 0.25; // the box's y and z extent; x is 4 times it

inline double wind_cloud_centre(int axis) {
    return axis == 0 ? 0.125 : 0.5 * kWindCloudWidth;
}

// Agertz et al. (2007): tau_KH = 1.6 tau_cr, the cloud-crushing time tau_cr = 2 R chi^(1/2) / v.
inline double wind_cloud_tau_kh(const WindCloudParams& wp) {
    return 1.6 * 2 * wp.radius * std::sqrt(wp.contrast) / wp.v_wind;
}

// Ids [0, 4N) are the wind's tiles (points inside the cloud left out), [4N, 5N) the cloud's
// shrunk points (those outside the sphere left out); each rank makes its share of each.
template <class T>
InitialConditions<T> make_wind_cloud(const WindCloudParams& wp, const CaseContext& ctx) {
    const double shrink = 1 / std::cbrt(wp.contrast);
    if (wp.side < 8) throw input_error("wind-cloud: -n must be at least 8", true);
    if (wp.radius >= 0.5 * kWindCloudWidth * shrink)
        throw input_error("wind-cloud: radius must be below 0.125 / contrast^(1/3)", true);
    InitialConditions<T> ic;
    ic.name = "wind-cloud";
    ic.dt0 = wp.dt0;
    ic.t_end = wp.t_end > 0 ? wp.t_end : 4 * wind_cloud_tau_kh(wp);
    ic.eos = {EosKind::ideal_gas, wp.gamma, 0.0};
    ic.box.lo = {T(0), T(0), T(0)};
    ic.box.hi = {T(4 * kWindCloudWidth), T(kWindCloudWidth), T(kWindCloudWidth)};
    ic.box.periodic = {true, true, true};
    const UnitCubePoints points = ctx.points();
    const std::uint64_t n = points.size();
    std::uint64_t first = 0, last = 0;
    points.share(ctx.rank, ctx.nranks, first, last);
    const double mass = 1.0 * kWindCloudWidth * kWindCloudWidth * kWindCloudWidth / double(n);
    const double h_wind = initial_smoothing_length(kWindCloudWidth * points.spacing(), wp.ng0);
    auto& ps = ic.particles;
    ps.resize(0);
    auto add = [&](std::uint64_t id, double x, double y, double z, bool cloud) {
        const std::size_t s = ps.size();
        ps.resize(s + 1);
        const double v = cloud ? 0.0 : wp.v_wind, u = cloud ? wp.u_wind / wp.contrast : wp.u_wind;
        set_particle(ps, s, id, {x, y, z}, {v, 0.0, 0.0}, wp.dt0, cloud ? h_wind * shrink : h_wind,
                     mass, u);
    };
    auto from_centre = [](double x, double y, double z) {
        const double dx = x - wind_cloud_centre(0), dy = y - wind_cloud_centre(1),
                     dz = z - wind_cloud_centre(2);
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    };
    for (std::uint64_t idx = first; idx < last; ++idx) {
        double px, py, pz;
        points.position(idx, px, py, pz);
        for (std::uint64_t tile = 0; tile < 4; ++tile) {
            const double x = kWindCloudWidth * (double(tile) + px), y = kWindCloudWidth * py,
                         z = kWindCloudWidth * pz;
            if (from_centre(x, y, z) >= wp.radius) add(tile * n + idx, x, y, z, false);
        }
        const double s = kWindCloudWidth * shrink;
        const double x = wind_cloud_centre(0) + s * (px - 0.5),
                     y = wind_cloud_centre(1) + s * (py - 0.5),
                     z = wind_cloud_centre(2) + s * (pz - 0.5);
        if (from_centre(x, y, z) < wp.radius) add(4 * n + idx, x, y, z, true);
    }
    return ic;
}

inline const CaseInfo& wind_cloud_case() {
    // A cloud shredded by shear at its surface: the sh scheme by default (config/scheme.hpp).
    static const CaseInfo info = with_scheme(
        Scheme::sh,
        case_info<WindCloudParams>(
            "wind-cloud",
            "Wind-cloud (blob) test: a dense cloud (contrast 10) in a supersonic wind, "
            "periodic box 1 x 0.25 x 0.25",
            true,
            {{"radius", &WindCloudParams::radius, "cloud radius"},
             {"contrast", &WindCloudParams::contrast, "cloud over wind density"},
             {"u_wind", &WindCloudParams::u_wind, "internal energy of the wind"},
             {"v_wind", &WindCloudParams::v_wind, "wind speed along x"},
             {"gamma", &WindCloudParams::gamma, "adiabatic index"},
             {"dt0", &WindCloudParams::dt0, "first time step"},
             {"t_end", &WindCloudParams::t_end, "end time; 0 is 4 tau_KH of the radius"}},
            [](const WindCloudParams& p, const CaseContext& c) {
                return make_wind_cloud<double>(p, c);
            }));
    return info;
}

} // namespace exasph
