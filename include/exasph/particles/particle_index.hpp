#pragma once
#include <cstdint>

namespace exasph {

// The position of a particle in this rank's arrays (owned [0, n_owned), halos after them): what
// kernels are called with and what lists hold. 32 bits: a rank holds fewer than 2^32 particles,
// and the lists' memory is half that of 64-bit indices.
using ParticleIndex = std::uint32_t;

} // namespace exasph
