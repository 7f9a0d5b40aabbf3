#pragma once
#include <cstdint>
#include <string>

#include "exasph/exact/exact_density.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/sph/eos.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// What a test case hands to the simulation: particles (state fields filled), the box, the EOS,
// the first time step and the case's default end time.
template <class T>
struct InitialConditions {
    std::string name;
    ParticleSet<T> particles;
    Box<T> box;
    EosParams eos;
    double dt0 = 1e-6;                // first time step; also sets x_{-1} = x_0 - v_0 dt0
    double t_end = 0.0;               // default end time of the case
    std::string units = "code units"; // unit system of all fields, written to outputs
    ExactDensity exact;               // the analytic density, when the case has one
    double G = 0.0;                   // gravitational constant; 0: no self-gravity
    double stir_mach = 0.0;           // target Mach number of the stirring; 0: none
};

// Sets the state of slot s: id, position, velocity, x_{-1} = x - v dt0 (the Press scheme's
// previous position, physics.md §7), h, m and u; the other state fields start at zero.
template <class T>
void set_particle(ParticleSet<T>& ps, std::size_t s, std::uint64_t id, const double (&pos)[3],
                  const double (&vel)[3], double dt0, double h, double m, double u) {
    ps.id[s] = id;
    for (int d = 0; d < 3; ++d) {
        ps[component(Field::x, d)][s] = T(pos[d]);
        ps[component(Field::vx, d)][s] = T(vel[d]);
        ps[static_cast<Field>(int(Field::x_m1) + d)][s] = T(pos[d] - vel[d] * dt0);
    }
    ps[Field::h][s] = T(h);
    ps[Field::m][s] = T(m);
    ps[Field::u][s] = T(u);
}

} // namespace exasph
