#pragma once
#include <cstddef>

#include "exasph/io/restart_state.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/sph/eos.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// What the output formats (snapshots, checkpoints) read of a run: a view, valid while the run
// does not step. The simulation hands it out (Simulation::output_state()).
template <class T>
struct OutputState {
    const ParticleSet<T>& particles;
    std::size_t n_owned; // owned particles: [0, n_owned)
    const Box<T>& box;
    const EosParams& eos;
    RestartState restart; // time, step, previous dt, global tree
    double dt;            // the last step's dt (0 before the first step)
    double dt0;           // the case's first dt
};

} // namespace exasph
