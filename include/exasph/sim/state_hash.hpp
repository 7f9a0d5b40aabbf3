#pragma once
#include <cstdint>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/util/checksum.hpp"

namespace exasph {

// Hash of one particle's id and state fields (bit patterns, in field-list order).
template <class T>
std::uint64_t particle_state_hash(const ParticleSet<T>& ps, std::size_t i,
                                  const std::vector<Field>& fields) {
    HashChain h(ps.id[i]);
    for (Field f : fields) h.add_float(ps[f][i]);
    return h.value();
}

// particle_state_hash of the particles [first, first + count), count <= kHashBlock: the chain
// advances one field at a time over the whole block, so that the mixing vectorises.
inline constexpr std::size_t kHashBlock = 256;
template <class T>
void state_hash_block(const ParticleSet<T>& ps, const std::vector<Field>& fields, std::size_t first,
                      std::size_t count, std::uint64_t* h) {
    const std::uint64_t* id = ps.id.data() + first;
#pragma omp simd
    for (std::size_t k = 0; k < count; ++k) h[k] = mix64(id[k]);
    for (Field f : fields) {
        const T* v = ps.data(f) + first;
#pragma omp simd
        for (std::size_t k = 0; k < count; ++k) h[k] = mix64(h[k] ^ float_bits(v[k]));
    }
}

} // namespace exasph
