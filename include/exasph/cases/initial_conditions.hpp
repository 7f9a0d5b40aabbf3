#pragma once
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
};

} // namespace exasph
