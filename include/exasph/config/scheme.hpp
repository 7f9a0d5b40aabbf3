#pragma once
#include <array>
#include <functional>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <variant>

#include "exasph/config/parameters.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// A named formulation: the values a scheme gives to the physics parameters of the table. The
// validation suite (docs/validation.md) decides them; Config{} holds the std values.
struct SchemeValue {
    std::string_view key; // a parameter of kParameters (a flag or a number)
    double value;         // flags: 0 off, 1 on
};
inline constexpr std::size_t kSchemeValues = 13;
inline constexpr std::array<SchemeValue, kSchemeValues> kStdScheme{{{"alpha", 1},
                                                                    {"av_switch", 0},
                                                                    {"conductivity", 0},
                                                                    {"av_limiter", 0},
                                                                    {"volume_elements", 0},
                                                                    {"energy_weights", 0},
                                                                    {"tensile_stress", 0},
                                                                    {"torque_free", 0},
                                                                    {"double_precision", 0},
                                                                    {"tensile_exponent", 4},
                                                                    {"tensile_stress_positive", 0},
                                                                    {"ng0", 100},
                                                                    {"ngmax", 150}}};
// Whether a scheme sets the parameter `key` (its default is then the run's scheme's, not
// Config{}'s).
inline constexpr bool set_by_scheme(std::string_view key) {
    for (const SchemeValue& v : kStdScheme)
        if (v.key == key) return true;
    return false;
}

// ve: generalised volume elements (sharp contact discontinuities and density jumps),
// artificial viscosity from slope-limited reconstructed velocities (no dissipation in smooth
// flows: shear, rotation, convergent inflow), and conductivity 1 (Price 2008's value: the
// start-up entropy of shocks spread out; 2 lowers Sedov's peak to 2.85, 0 leaves Noh's shell
// at 47.7). Measured case by case in docs/validation.md.
inline constexpr std::array<SchemeValue, kSchemeValues> kVeScheme{{{"alpha", 1},
                                                                   {"av_switch", 0},
                                                                   {"conductivity", 1},
                                                                   {"av_limiter", 1},
                                                                   {"volume_elements", 1},
                                                                   {"energy_weights", 0},
                                                                   {"tensile_stress", 0},
                                                                   {"torque_free", 0},
                                                                   {"double_precision", 0},
                                                                   {"tensile_exponent", 4},
                                                                   {"tensile_stress_positive", 0},
                                                                   {"ng0", 100},
                                                                   {"ngmax", 150}}};
// wc: std for weakly compressible liquids with free surfaces and negative pressures (the square
// patch, docs/validation.md), with the paper's ~250 neighbours. The artificial stress (Monaghan
// 2000) stops the tensile clumping that std shows there (-n 20, t = 0.25: closest pair 0.33 of
// the spacing with std); at 250 neighbours W(r)/W(dp) varies less inside dp, so the exponent is
// 6, not Monaghan's 4, and eps 0.3 (-n 30 at t = 0.5: closest pair 0.48 with eps 0.2, 0.52 with
// 0.3; eps 0.4 grew v_z to 2e-5). A tenth of it under compression (eps 0.03 for P > 0): the
// patch's closest pairs are under positive pressure, and with the stress for P < 0 only the
// closest pair fell to 0.45 of the spacing at -n 24 on 2 ranks (0.54 with it); 0.3 for P > 0
// grew v_z to 1.4e-3 at -n 30. --torque-free, with
// the stress's own matrix: L_z conserved to 1e-6 (0.3-1.4 % drift without). Double precision:
// single-precision rho, P and C turned round-off differences between the identical layers into 1e-7
// seeds of v_z, which the patch's layer instability grew to |v_z|/max|v_xy| = 1.2e-2 by t = 0.5 (-n
// 20). With ng0 100 that instability grows v_z from 1e-14 to 1e-3 between t = 0.25 and 0.5 (-n 20);
// with 250 it stays below 1e-5 (-n 20, -n 30). ngmax 375, 1.5 ng0 as in the other schemes: ngmax
// only reports, and with 300 the lattice's particles, 308 neighbours at step 1 of -n 30, made the
// default run print a warning about nothing.
inline constexpr std::array<SchemeValue, kSchemeValues> kWcScheme{
    {{"alpha", 1},
     {"av_switch", 0},
     {"conductivity", 0},
     {"av_limiter", 0},
     {"volume_elements", 0},
     {"energy_weights", 0},
     {"tensile_stress", 0.3},
     {"torque_free", 1},
     {"double_precision", 1},
     {"tensile_exponent", 6},
     {"tensile_stress_positive", 0.03},
     {"ng0", 250},
     {"ngmax", 375}}};

// pe: ve for contact discontinuities in pressure balance (the isobaric cube). Weights X = m u
// make P = (gamma - 1) sum_b m_b u_b W_ab, with no pressure blip at a contact at rest, where
// (m/rho)^0.7 leaves one that rounds the cube off. No conductivity: Price's signal
// sqrt(|P_a - P_b| / rho) feeds on the particles' pressure scatter and carried heat into the
// cube (its mean u 0.47 -> 0.85 by t = 2, the cube expanding to rho 5.4 of 8). 200 neighbours:
// with 100 the dense particles at the surface (h = 0.7 of the light side's spacing) sample the
// light side with one layer of particles, and the layers' mean pressure there dipped 18 %
// (5 % with 200). The isobaric cube -n 20 on lattices, at t = 2: corner fill 1.15, layer
// pressure within 5.2 % (pe); 0.93, 20 % with 100 neighbours; 0.47 with conductivity 1; 0.26
// with ve; 0.00 with ve without conductivity (docs/validation.md). Not for shocks into cold
// gas, where u jumps by orders of magnitude within a kernel.
// A scheme that is `base` with some values changed (each key must be in base).
template <std::size_t N>
constexpr std::array<SchemeValue, kSchemeValues>
scheme_with(std::array<SchemeValue, kSchemeValues> base, const SchemeValue (&changes)[N]) {
    for (const SchemeValue& c : changes) {
        std::size_t found = 0;
        for (SchemeValue& v : base)
            if (v.key == c.key) v.value = c.value, ++found;
        if (found != 1) throw std::logic_error("scheme_with: unknown key");
    }
    return base;
}
inline constexpr auto kPeScheme = scheme_with(
    kVeScheme, {{"conductivity", 0}, {"energy_weights", 1}, {"ng0", 200}, {"ngmax", 300}});

// sh: ve for shear flows (Kelvin-Helmholtz, wind-cloud). alpha = 1 on every approaching close
// pair gives the shear layer a viscosity whose damping rate nu k^2 matches the mode's growth
// rate (KH -n 32: no growth with ve); the Morris & Monaghan switch lets alpha decay to
// --alpha-min away from compression. No conductivity: Price's signal sqrt(|P_a - P_b| / rho)
// feeds on the contact's pressure scatter and diffused the dense band over ~0.3 by t = 2 (KH
// -n 32 with the switch: no billows); without it the contact stays sharp. Not ve's default:
// ve with the switch failed Gresho-Chan (L1 0.080 against ve's 0.046; the vortex's velocity
// noise needs alpha = 1), and ve's conductivity is Noh's wall-heating cure. docs/validation.md.
inline constexpr auto kShScheme = scheme_with(kVeScheme, {{"av_switch", 1}, {"conductivity", 0}});

inline const auto& scheme_values(Scheme s) {
    switch (s) {
    case Scheme::ve:
        return kVeScheme;
    case Scheme::wc:
        return kWcScheme;
    case Scheme::pe:
        return kPeScheme;
    case Scheme::sh:
        return kShScheme;
    default:
        return kStdScheme;
    }
}

// Sets cfg.scheme = s and every parameter of the scheme that `given` (the parameters the user
// set explicitly) does not hold to the scheme's value.
inline void apply_scheme(Config& cfg, Scheme s,
                         const std::function<bool(const Param&)>& given = {}) {
    cfg.scheme = s;
    for (const SchemeValue& sv : scheme_values(s)) {
        const Param* p = find_parameter(sv.key);
        if (!p) throw std::logic_error("scheme parameter " + std::string(sv.key) + "?");
        if (given && given(*p)) continue;
        std::visit(
            [&](const auto& m) {
                if constexpr (std::is_same_v<std::decay_t<decltype(m)>, bool Config::*>)
                    cfg.*m = sv.value != 0;
                else if constexpr (std::is_same_v<std::decay_t<decltype(m)>, double Config::*>)
                    cfg.*m = sv.value;
                else if constexpr (std::is_same_v<std::decay_t<decltype(m)>, int Config::*>)
                    cfg.*m = int(sv.value);
                else
                    throw std::logic_error("scheme parameter " + std::string(sv.key) +
                                           " is not a flag or a number");
            },
            p->member);
    }
}

} // namespace exasph
