#pragma once
#include <cstdint>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/initial_conditions.hpp"
#include "exasph/cases/periodic_gas.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Subsonic driven turbulence: gas at rest in the periodic unit box [0, 1)^3, rho = 1, sound
// speed 1, nearly isothermal (gamma = 1.001, so that the heat of the dissipated turbulence
// barely changes c_s), stirred on the largest scales (sim/stirring.hpp) towards an rms Mach
// number of 0.3 (--stir-mach). The turnover time of the driving scale L/2 is L / (2 M c_s).
struct TurbulenceParams {
    int side = 30;
    double ng0 = 100;
    double gamma = 1.001;
    double sound_speed = 1.0;
    double mach = 0.3; // the stirring's target unless --stir-mach is given
    double dt0 = 1e-3;
    double t_end = 10.0;
};

template <class T>
InitialConditions<T> make_turbulence(const TurbulenceParams& tp, const CaseContext& ctx) {
    if (tp.side < 8) throw input_error("turbulence: -n must be at least 8", true);
    if (!(tp.gamma > 1)) throw input_error("turbulence: gamma must be above 1", true);
    InitialConditions<T> ic = make_periodic_gas<T>(tp.ng0, tp.gamma, tp.sound_speed, tp.dt0, ctx,
                                                   [](double*, double&) {});
    ic.name = "turbulence";
    ic.t_end = tp.t_end;
    ic.stir_mach = tp.mach;
    return ic;
}

inline const CaseInfo& turbulence_case() {
    static const CaseInfo info = case_info<TurbulenceParams>(
        "turbulence", "Subsonic driven turbulence, stirred towards Mach 0.3 (periodic box)", true,
        {{"mach", &TurbulenceParams::mach, "target rms Mach number of the stirring"},
         {"sound_speed", &TurbulenceParams::sound_speed, "initial sound speed"},
         {"gamma", &TurbulenceParams::gamma, "adiabatic index"},
         {"dt0", &TurbulenceParams::dt0, "first time step"},
         {"t_end", &TurbulenceParams::t_end, "end time"}},
        [](const TurbulenceParams& p, const CaseContext& c) {
            return make_turbulence<double>(p, c);
        });
    return info;
}

} // namespace exasph
