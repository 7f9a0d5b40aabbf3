#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/periodic_gas.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Jeans instability (physics.md §9.10): uniform gas in the periodic unit box, rho = 1, sound
// speed c, adiabatic (gamma = 5/3), at rest, with a plane-wave density perturbation
// delta rho / rho = eps cos(k x), k = 2 pi m (mode m along x), made by displacing the particles
// by xi = -(eps / k) sin(k x) and raising u adiabatically, u ∝ rho^(gamma - 1). Self-gravity with
// the mean density removed (the periodic Ewald sum's background): with k_J = sqrt(4 pi G rho) / c
// set by the parameter ratio = k / k_J, linear theory gives
//   k < k_J: delta(t) = eps cosh(g t),   g = sqrt(4 pi G rho - c^2 k^2)   (growth),
//   k > k_J: delta(t) = eps cos(w t),    w = sqrt(c^2 k^2 - 4 pi G rho)   (oscillation).
// The default end time: three e-foldings (growth) or one period (oscillation).
struct JeansParams {
    int side = 24;
    double ng0 = 100;
    double ratio = 0.5;      // k / k_J
    double mode = 1;         // m: wavelength 1 / m along x
    double amplitude = 0.01; // eps
    double sound_speed = 1.0;
    double gamma = 5.0 / 3.0;
    double G = -1; // --G; < 0: from ratio
};

// The linear theory of a JeansParams: 4 pi G rho, G (given, else from ratio = k / k_J), and the
// growth rate (k < k_J) or angular frequency (k > k_J).
struct JeansTheory {
    double k, four_pi_g_rho, G;
    bool grows;
    double rate;

    explicit JeansTheory(const JeansParams& p) {
        k = 2 * M_PI * p.mode;
        const double ck = p.sound_speed * k;
        G = p.G > 0 ? p.G : ck * ck / (p.ratio * p.ratio) / (4 * M_PI);
        four_pi_g_rho = 4 * M_PI * G;
        grows = four_pi_g_rho > ck * ck;
        rate = std::sqrt(std::abs(four_pi_g_rho - ck * ck));
    }
    // delta(t) / eps.
    double amplitude(double t) const { return grows ? std::cosh(rate * t) : std::cos(rate * t); }
};

template <class T>
InitialConditions<T> make_jeans(const JeansParams& p, const CaseContext& ctx) {
    if (p.side < 8) throw input_error("jeans: -n must be at least 8", true);
    if (!(p.gamma > 1)) throw input_error("jeans: gamma must be above 1", true);
    const JeansTheory th(p);
    if (!(th.rate > 0))
        throw input_error("jeans: k = k_J is the marginal mode (ratio 1); choose another", true);
    if (p.G == 0) throw input_error("jeans: the case needs self-gravity (G > 0)", true);
    if (!(p.amplitude < 0.5)) throw input_error("jeans: amplitude must be below 0.5", true);
    if (std::abs(p.mode - std::round(p.mode)) > 1e-12)
        throw input_error("jeans: mode must be a whole number (the box is periodic)", true);
    const double dt0 = 1e-3 / (p.sound_speed * p.side);
    InitialConditions<T> ic =
        make_periodic_gas<T>(p.ng0, p.gamma, p.sound_speed, dt0, ctx, [&](double* pos, double& u) {
            const double phase = th.k * pos[0];
            pos[0] -= p.amplitude / th.k * std::sin(phase);
            pos[0] -= std::floor(pos[0]);
            u *= 1 + (p.gamma - 1) * p.amplitude * std::cos(phase);
        });
    ic.name = "jeans";
    ic.G = th.G;
    ic.t_end = th.grows ? 3 / th.rate : 2 * M_PI / th.rate;
    return ic;
}

inline const CaseInfo& jeans_case() {
    static const CaseInfo info = case_info<JeansParams>(
        "jeans",
        "Jeans instability: a plane-wave perturbation that grows (ratio < 1) or oscillates "
        "(ratio > 1) under self-gravity (periodic box)",
        true,
        {{"ratio", &JeansParams::ratio, "k / k_J (sets G unless --G is given)"},
         {"mode", &JeansParams::mode, "wave number along x in units of 2 pi"},
         {"amplitude", &JeansParams::amplitude, "initial density contrast"},
         {"sound_speed", &JeansParams::sound_speed, "sound speed"},
         {"gamma", &JeansParams::gamma, "adiabatic index"}},
        [](const JeansParams& p, const CaseContext& c) { return make_jeans<double>(p, c); });
    return info;
}

} // namespace exasph
