#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Rotating square patch (physics.md §9.1), CGS units.
struct SquarePatchParams {
    int side = 30;         // particles per axis
    double ng0 = 100;      // target neighbour count, sets h_0
    double length = 100.0; // cm
    double density = 1.0;  // g/cm^3
    double omega = 5.0;    // rad/s
    double sound_speed = 3500.0;
    double dt0 = 1e-6;
    double t_end = 0.02; // default end time (s)
};

// Initial pressure P_0(x', y') = rho L^2 sum_{m,l odd <= 39} -32 w^2 / (m l pi^2)
//   / ((m pi)^2 + (l pi)^2) sin(m pi x') sin(l pi y'), with x', y' in [0, 1].
inline double square_patch_pressure(double xs, double ys, const SquarePatchParams& sp) {
    constexpr int kModes = 20; // m = 1, 3, ..., 39
    double sx[kModes], sy[kModes];
    for (int k = 0; k < kModes; ++k) {
        sx[k] = std::sin((2 * k + 1) * M_PI * xs);
        sy[k] = std::sin((2 * k + 1) * M_PI * ys);
    }
    double sum = 0.0;
    for (int k = 0; k < kModes; ++k) {
        double mm = 2 * k + 1;
        for (int j = 0; j < kModes; ++j) {
            double ll = 2 * j + 1;
            double denom = (mm * M_PI) * (mm * M_PI) + (ll * M_PI) * (ll * M_PI);
            sum += -32.0 * sp.omega * sp.omega / (mm * ll * M_PI * M_PI) / denom * sx[k] * sy[j];
        }
    }
    return sp.density * sp.length * sp.length * sum;
}

// Rank `rank` of `nranks` creates only its share of the lattice (ids [N r / P, N (r+1) / P));
// the first domain sync moves particles to their owners.
template <class T>
InitialConditions<T> make_square_patch(const SquarePatchParams& sp, int rank = 0, int nranks = 1) {
    if (sp.side < 2) throw input_error("square patch: -n must be at least 2");
    InitialConditions<T> ic;
    ic.name = "square-patch";
    ic.dt0 = sp.dt0;
    ic.t_end = sp.t_end;
    ic.units = "cgs (cm, g, s)";
    ic.eos = {EosKind::tait, 5.0 / 3.0, sp.sound_speed};
    const double half = 0.5 * sp.length;
    ic.box.lo = {T(-half), T(-half), T(-half)};
    ic.box.hi = {T(half), T(half), T(half)};
    ic.box.periodic = {false, false, true};

    const std::uint64_t n1 = static_cast<std::uint64_t>(sp.side);
    const std::uint64_t n = n1 * n1 * n1;
    const double dx = sp.length / double(sp.side);
    const double mass = sp.density * sp.length * sp.length * sp.length / double(n);
    const double h0 = 0.5 * dx * std::cbrt(3.0 * sp.ng0 / (4.0 * M_PI));
    const std::uint64_t first = n * std::uint64_t(rank) / std::uint64_t(nranks);
    const std::uint64_t last = n * std::uint64_t(rank + 1) / std::uint64_t(nranks);
    auto& ps = ic.particles;
    ps.resize(last - first);
    ps.enable(Field::rho0); // the Tait EOS's reference state
    ps.enable(Field::p0);
#pragma omp parallel for schedule(static)
    for (std::uint64_t idx = first; idx < last; ++idx) {
        const std::uint64_t s = idx - first; // slot on this rank
        std::uint64_t i = idx / (n1 * n1), j = (idx / n1) % n1, k = idx % n1;
        double x = -half + (double(i) + 0.5) * dx;
        double y = -half + (double(j) + 0.5) * dx;
        double z = -half + (double(k) + 0.5) * dx;
        set_particle(ps, s, idx, {x, y, z}, {sp.omega * y, -sp.omega * x, 0.0}, sp.dt0, h0, mass,
                     0.0);
        ps[Field::rho0][s] = T(sp.density); // replaced by the measured density at step 0
        ps[Field::p0][s] =
            T(square_patch_pressure((x + half) / sp.length, (y + half) / sp.length, sp));
    }
    return ic;
}

inline const CaseInfo& square_patch_case() {
    // The paper's test of tensile instability: the wc scheme (config/scheme.hpp) by default.
    static const CaseInfo info = with_scheme(
        Scheme::wc,
        case_info<SquarePatchParams>(
            "square-patch",
            "Rotating square patch (docs/physics.md §9.1), weakly compressible water, CGS", false,
            {{"omega", &SquarePatchParams::omega, "angular velocity [rad/s]"},
             {"sound_speed", &SquarePatchParams::sound_speed, "Tait sound speed [cm/s]"},
             {"dt0", &SquarePatchParams::dt0, "first time step [s]"},
             {"t_end", &SquarePatchParams::t_end, "end time [s]"}},
            [](const SquarePatchParams& p, const CaseContext& c) {
                return make_square_patch<double>(p, c.rank, c.nranks);
            }));
    return info;
}

} // namespace exasph
