#pragma once
#include <cmath>

#include "exasph/cases/case_info.hpp"
#include "exasph/cases/turbulence.hpp"

namespace exasph {

// Turbulent collapse (physics.md §9.5): the turbulence case's box (periodic unit cube, rho = 1,
// sound speed 1, gamma = 1.001, stirred on the largest scales) with self-gravity through the
// Ewald sum, G = 4 pi so that the Jeans length c_s sqrt(pi / (G rho)) is half the box (eight
// Jeans masses; free fall time sqrt(3 pi / (32 G rho)) = 0.15). The stirring at Mach 1 seeds the
// overdensities that gravity then pulls together: at -n 16 the densest particle passes 10 times
// the mean at t = 0.46 and 100 at t = 0.5, the default end time; beyond it the collapse runs away
// (at t = 0.52 the time step is 1e-4, a thousand times the first).
struct TurbulentCollapseParams {
    int side = 16;
    double ng0 = 100;
    double G = 4 * M_PI;
    double mach = 1.0;
    double gamma = 1.001;
    double sound_speed = 1.0;
    double t_end = 0.5;
};

template <class T>
InitialConditions<T> make_turbulent_collapse(const TurbulentCollapseParams& p,
                                             const CaseContext& ctx) {
    TurbulenceParams tp;
    tp.side = p.side;
    tp.ng0 = p.ng0;
    tp.gamma = p.gamma;
    tp.sound_speed = p.sound_speed;
    tp.mach = p.mach;
    tp.t_end = p.t_end;
    InitialConditions<T> ic = make_turbulence<T>(tp, ctx);
    ic.name = "turbulent-collapse";
    ic.G = p.G;
    return ic;
}

inline const CaseInfo& turbulent_collapse_case() {
    static const CaseInfo info = case_info<TurbulentCollapseParams>(
        "turbulent-collapse",
        "Stirred periodic box collapsing under its own gravity (Jeans length half the box)", true,
        {{"mach", &TurbulentCollapseParams::mach, "target rms Mach number of the stirring"},
         {"sound_speed", &TurbulentCollapseParams::sound_speed, "initial sound speed"},
         {"gamma", &TurbulentCollapseParams::gamma, "adiabatic index"},
         {"t_end", &TurbulentCollapseParams::t_end, "end time"}},
        [](const TurbulentCollapseParams& p, const CaseContext& c) {
            return make_turbulent_collapse<double>(p, c);
        });
    return info;
}

} // namespace exasph
