#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/initial_h.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Kelvin-Helmholtz instability (McNally, Lyra & Passy 2012; the reference code's setup): in the
// periodic thin slab [0, 1)^2 x [0, depth), a dense band rho = 2 in 0.25 < y < 0.75 moving at
// v_x = +0.5 through light gas rho = 1 at -0.5, P = 2.5 everywhere, gamma = 5/3; the velocity
// changes across layers of width 0.025 (McNally's exponential profile) and a seed
// v_y = 0.01 sin(4 pi x) excites the mode. Equal masses: two lattices, the dense one 2^(1/3)
// finer (-n 32: 32 and 40 points per unit length; the masses differ by 2.4 %, the densities
// are exact).
struct KelvinHelmholtzParams {
    int side = 32; // particles per unit length in the light gas
    double ng0 = 100;
    double gamma = 5.0 / 3.0;
    double pressure = 2.5;
    double speed = 0.5; // |v_x| of each stream
    double layer = 0.025;
    double seed = 0.01; // amplitude of v_y
    double dt0 = 1e-4;
    double t_end = 3.0;
};

// v_x at height y (McNally et al. 2012, eq. 1, with equal and opposite streams).
inline double kh_vx(const KelvinHelmholtzParams& kp, double y) {
    const double u = kp.speed, l = kp.layer;
    if (y < 0.25) return -u + u * std::exp((y - 0.25) / l);
    if (y < 0.5) return u - u * std::exp((0.25 - y) / l);
    if (y < 0.75) return u - u * std::exp((y - 0.75) / l);
    return -u + u * std::exp((0.75 - y) / l);
}

// One of the two lattices: nx x ny x nz cell-centred points filling [0, 1) x [y0, y0 + height)
// x [0, depth) (the light one is split in two half-bands below and above the dense band).
struct KhLattice {
    std::uint64_t nx, ny, nz;
    double y0, height, depth;
    std::uint64_t size() const { return nx * ny * nz; }
    void position(std::uint64_t id, double& x, double& y, double& z) const {
        const std::uint64_t i = id / (ny * nz), j = (id / nz) % ny, k = id % nz;
        x = (double(i) + 0.5) / double(nx);
        y = y0 + (double(j) + 0.5) * height / double(ny);
        z = (double(k) + 0.5) * depth / double(nz);
        if (y >= 1) y -= 1;
    }
};

template <class T>
InitialConditions<T> make_kelvin_helmholtz(const KelvinHelmholtzParams& kp,
                                           const CaseContext& ctx) {
    if (kp.side < 16 || kp.side % 4)
        throw input_error("kelvin-helmholtz: -n must be a multiple of 4, at least 16", true);
    const auto n = std::uint64_t(kp.side);
    const auto nd = std::uint64_t(std::lround(kp.side * std::cbrt(2.0)));
    const std::uint64_t layers = 8;
    const double depth = double(layers) / double(n);
    // The light gas is one lattice from y = 0.75 across the periodic boundary to y = 0.25.
    const KhLattice light{n, n / 2, layers, 0.75, 0.5, depth};
    const KhLattice dense{nd,   nd / 2, std::uint64_t(std::lround(layers * std::cbrt(2.0))),
                          0.25, 0.5,    depth};
    InitialConditions<T> ic;
    ic.name = "kelvin-helmholtz";
    ic.dt0 = kp.dt0;
    ic.t_end = kp.t_end;
    ic.eos = {EosKind::ideal_gas, kp.gamma, 0.0};
    ic.box.lo = {T(0), T(0), T(0)};
    ic.box.hi = {T(1), T(1), T(depth)};
    ic.box.periodic = {true, true, true};
    const std::uint64_t total = light.size() + dense.size();
    const std::uint64_t first = total * std::uint64_t(ctx.rank) / std::uint64_t(ctx.nranks);
    const std::uint64_t last = total * std::uint64_t(ctx.rank + 1) / std::uint64_t(ctx.nranks);
    auto& ps = ic.particles;
    ps.resize(last - first);
    for (std::uint64_t id = first; id < last; ++id) {
        const bool is_dense = id >= light.size();
        const KhLattice& lat = is_dense ? dense : light;
        const double rho = is_dense ? 2.0 : 1.0;
        double x, y, z;
        lat.position(is_dense ? id - light.size() : id, x, y, z);
        const double mass = rho * 0.5 * depth / double(lat.size());
        const double h = initial_smoothing_length(1.0 / double(lat.nx), kp.ng0);
        set_particle(ps, id - first, id, {x, y, z},
                     {kh_vx(kp, y), kp.seed * std::sin(4 * M_PI * x), 0.0}, kp.dt0, h, mass,
                     kp.pressure / ((kp.gamma - 1) * rho));
    }
    return ic;
}

inline const CaseInfo& kelvin_helmholtz_case() {
    // A shear layer: the sh scheme (the AV switch, no conductivity) by default
    // (config/scheme.hpp).
    static const CaseInfo info = with_scheme(
        Scheme::sh,
        case_info<KelvinHelmholtzParams>(
            "kelvin-helmholtz",
            "Kelvin-Helmholtz instability, a dense band (contrast 2) shearing past light gas "
            "(thin slab, lattices)",
            false,
            {{"speed", &KelvinHelmholtzParams::speed, "speed of each stream"},
             {"seed", &KelvinHelmholtzParams::seed, "amplitude of the seed v_y"},
             {"layer", &KelvinHelmholtzParams::layer, "width of the shear layers"},
             {"pressure", &KelvinHelmholtzParams::pressure, "the uniform pressure"},
             {"gamma", &KelvinHelmholtzParams::gamma, "adiabatic index"},
             {"dt0", &KelvinHelmholtzParams::dt0, "first time step"},
             {"t_end", &KelvinHelmholtzParams::t_end, "end time"}},
            [](const KelvinHelmholtzParams& p, const CaseContext& c) {
                return make_kelvin_helmholtz<double>(p, c);
            }));
    return info;
}

} // namespace exasph
