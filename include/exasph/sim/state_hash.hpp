#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "exasph/particles/particle_set.hpp"
#include "exasph/sph/field_hash_kern.hpp"
#include "exasph/sph/launch.hpp"
#include "exasph/util/checksum.hpp"
#include "exasph/util/error.hpp"

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

// The arrays of `fields` for FieldHashKernel, each in its storage.
template <class T>
HashedFields hashed_fields(const ParticleSet<T>& ps, const std::vector<Field>& fields) {
    if (fields.size() > std::size_t(HashedFields::kMost))
        throw Error("hashing " + std::to_string(fields.size()) + " fields: at most " +
                    std::to_string(HashedFields::kMost));
    HashedFields h;
    for (Field f : fields) {
        const bool single = ps.stored_single(f);
        h.data[h.count] = single ? static_cast<const void*>(ps.narrow(f)) : ps.data(f);
        h.bytes[h.count++] = std::uint8_t(single ? sizeof(float) : sizeof(T));
    }
    return h;
}

// Sum (mod 2^64) of the folded particle_state_hash over `fields` of particles [0, n): it does
// not depend on their order, and over the state fields it is the sum of the state guard's seal.
// The CPU launcher hashes a block of particles one field at a time (vectorised); the GPU path's
// launchers run FieldHashKernel where the fields are (the same sum:
// tests/unit/sim/test_state_hash).
template <class L = DefaultLauncher, class T>
std::uint64_t field_hash_sum(const ParticleSet<T>& ps, const std::vector<Field>& fields,
                             std::size_t n) {
    if constexpr (L::kBackend != Backend::openmp) {
        return L::reduce(n, FieldHashKernel{ps.id.data(), hashed_fields(ps, fields)});
    } else {
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
}

template <class T>
std::uint64_t state_hash_sum(const ParticleSet<T>& ps, std::size_t n) {
    return field_hash_sum(ps, ps.fields(kState), n);
}

} // namespace exasph
