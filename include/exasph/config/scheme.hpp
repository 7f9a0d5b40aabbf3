#pragma once
#include <array>
#include <functional>
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
inline constexpr std::array<SchemeValue, 5> kStdScheme{{{"alpha", 1},
                                                        {"av_switch", 0},
                                                        {"conductivity", 0},
                                                        {"av_limiter", 0},
                                                        {"volume_elements", 0}}};
// ve: generalised volume elements (sharp contact discontinuities and density jumps),
// artificial viscosity from slope-limited reconstructed velocities (no dissipation in smooth
// flows: shear, rotation, convergent inflow), and conductivity 1 (Price 2008's value: the
// start-up entropy of shocks spread out; 2 lowers Sedov's peak to 2.85, 0 leaves Noh's shell
// at 47.7). Measured case by case in docs/validation.md.
inline constexpr std::array<SchemeValue, 5> kVeScheme{{{"alpha", 1},
                                                       {"av_switch", 0},
                                                       {"conductivity", 1},
                                                       {"av_limiter", 1},
                                                       {"volume_elements", 1}}};

inline const auto& scheme_values(Scheme s) {
    return s == Scheme::ve ? kVeScheme : kStdScheme;
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
                else
                    throw std::logic_error("scheme parameter " + std::string(sv.key) +
                                           " is neither a flag nor a number");
            },
            p->member);
    }
}

} // namespace exasph
