#pragma once
#include <array>
#include <cstdint>

#include "exasph/util/annotate.hpp"

namespace exasph {

// 63-bit keys: 21 bits per axis, x most significant within each 3-bit digit.
inline constexpr int kKeyBitsPerAxis = 21;
inline constexpr std::uint32_t kKeyAxisMax = (1u << kKeyBitsPerAxis) - 1;

// Spreads the low 21 bits of v so that bit i moves to bit 3i.
EXASPH_HD EXASPH_INLINE constexpr std::uint64_t spread_bits3(std::uint64_t v) {
    v &= 0x1fffffULL;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}

// Inverse of spread_bits3: gathers bits 0, 3, 6, ... into the low 21 bits.
EXASPH_HD constexpr std::uint32_t compact_bits3(std::uint64_t v) {
    v &= 0x1249249249249249ULL;
    v = (v ^ (v >> 2)) & 0x10c30c30c30c30c3ULL;
    v = (v ^ (v >> 4)) & 0x100f00f00f00f00fULL;
    v = (v ^ (v >> 8)) & 0x1f0000ff0000ffULL;
    v = (v ^ (v >> 16)) & 0x1f00000000ffffULL;
    v = (v ^ (v >> 32)) & 0x1fffffULL;
    return static_cast<std::uint32_t>(v);
}

EXASPH_HD EXASPH_INLINE constexpr std::uint64_t morton_encode(std::uint32_t ix, std::uint32_t iy,
                                                              std::uint32_t iz) {
    return spread_bits3(ix) << 2 | spread_bits3(iy) << 1 | spread_bits3(iz);
}

EXASPH_HD constexpr std::array<std::uint32_t, 3> morton_decode(std::uint64_t key) {
    return {compact_bits3(key >> 2), compact_bits3(key >> 1), compact_bits3(key)};
}

} // namespace exasph
