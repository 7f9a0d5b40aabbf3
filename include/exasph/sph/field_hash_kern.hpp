#pragma once
#include <cstdint>

#include "exasph/particles/particle_index.hpp"
#include "exasph/sph/reduction.hpp"
#include "exasph/util/checksum.hpp"

// The silent-data-corruption seals' hash (sim/step_seals.hpp) as a kernel that a launcher sums
// where the particles live: per particle the chain of sim/state_hash.hpp (mix64 of the id, then
// of each field's bit pattern in list order) folded to 32 bits, summed modulo 2^64 (an integer
// sum: the same in any order, so the same on every launcher).
namespace exasph {

// The fields a hash reads, each an array of 4-byte (float) or 8-byte (double) values.
struct HashedFields {
    static constexpr int kMost = 40;
    const void* data[kMost];
    std::uint8_t bytes[kMost]; // 4 or 8
    int count = 0;
};

// Requires: id and every listed array hold the particles the launcher visits.
struct FieldHashKernel {
    const std::uint64_t* id;
    HashedFields fields;
    using Reduction = SumOf<std::uint64_t>;

    EXASPH_HD std::uint64_t operator()(ParticleIndex i) const {
        std::uint64_t h = mix64(id[i]);
        for (int k = 0; k < fields.count; ++k) h = mix64(h ^ bits(k, i));
        return fold_hash(h);
    }

  private:
    EXASPH_HD std::uint64_t bits(int k, ParticleIndex i) const {
        if (fields.bytes[k] == 4) return float_bits(static_cast<const float*>(fields.data[k])[i]);
        return float_bits(static_cast<const double*>(fields.data[k])[i]);
    }
};

} // namespace exasph
