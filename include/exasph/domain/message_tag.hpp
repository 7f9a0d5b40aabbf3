#pragma once

namespace exasph {

// The kinds of point-to-point message of a step, one MPI tag each, so that messages of different
// kinds between the same two ranks never match each other's receives (the collectives need no
// tag).
enum class MessageTag : int {
    migrate = 7101,     // particles to their new owner (domain/particle_exchange.hpp)
    halo_count = 7102,  // how many halo particles each partner sends (domain/halo_exchange.hpp)
    halo = 7103,        // the halos' fields
    halo_return = 7104, // maxima of the halo copies back to their owners
    gravity = 7201,     // the multipoles of the leaves another rank's walk opens
};

constexpr int mpi_tag(MessageTag t) {
    return static_cast<int>(t);
}

} // namespace exasph
