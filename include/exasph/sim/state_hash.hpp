#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/util/checksum.hpp"

namespace exasph {

// Hash of one particle's id and fields (bit patterns, in list order; either storage).
template <class T>
std::uint64_t particle_state_hash(const ParticleSet<T>& ps, std::size_t i,
                                  const std::vector<Field>& fields) {
    HashChain h(ps.id[i]);
    for (Field f : fields)
        ps.stored_single(f) ? h.add_float(ps.narrow(f)[i]) : h.add_float(ps[f][i]);
    return h.value();
}

// Mixes one field's values of `count` particles into their hashes.
template <class V>
void mix_field(const V* v, std::size_t count, std::uint64_t* h) {
#pragma omp simd
    for (std::size_t k = 0; k < count; ++k) h[k] = mix64(h[k] ^ float_bits(v[k]));
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
        if (ps.stored_single(f))
            mix_field(ps.narrow(f) + first, count, h);
        else
            mix_field(ps.data(f) + first, count, h);
    }
}

// A particle's hash folded to the 32 bits that the state guard keeps.
inline std::uint32_t fold_hash(std::uint64_t h) {
    return std::uint32_t(h ^ (h >> 32));
}

// Sum (mod 2^64) of the folded particle_state_hash over `fields` of particles [0, n): it does
// not depend on their order, and over the state fields it is the sum of the state guard's seal.
template <class T>
std::uint64_t field_hash_sum(const ParticleSet<T>& ps, const std::vector<Field>& fields,
                             std::size_t n) {
    const auto blocks = std::int64_t((n + kHashBlock - 1) / kHashBlock);
    std::uint64_t sum = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum)
    for (std::int64_t b = 0; b < blocks; ++b) {
        std::uint64_t h[kHashBlock];
        const std::size_t first = std::size_t(b) * kHashBlock;
        const std::size_t count = std::min(kHashBlock, n - first);
        state_hash_block(ps, fields, first, count, h);
        for (std::size_t k = 0; k < count; ++k) sum += fold_hash(h[k]);
    }
    return sum;
}

template <class T>
std::uint64_t state_hash_sum(const ParticleSet<T>& ps, std::size_t n) {
    return field_hash_sum(ps, ps.fields(kState), n);
}

} // namespace exasph
