#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "exasph/sfc/morton.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// 3D Hilbert keys by J. Skilling's transpose method ("Programming the Hilbert curve", AIP Conf.
// Proc. 707, 2004): the coordinates are transformed in place into the "transposed" Hilbert index,
// whose bits interleaved like a Morton key give the 63-bit Hilbert key. Like Morton keys, every
// prefix of 3l bits names one cube of level l, so the octree can be built from either.
EXASPH_HD EXASPH_INLINE constexpr std::uint64_t hilbert_encode(std::uint32_t ix, std::uint32_t iy,
                                                               std::uint32_t iz) {
    std::uint32_t a[3] = {ix, iy, iz};
    constexpr std::uint32_t top = 1u << (kKeyBitsPerAxis - 1);
    // Undo the rotations/reflections from the top bit down. Branch-free (the bit tests are
    // data-dependent and mispredict half the time): where bit q of a[i] is set, a[0] ^= p;
    // otherwise the low bits of a[0] and a[i] are exchanged (nothing for i = 0).
    for (std::uint32_t q = top; q > 1; q >>= 1) {
        std::uint32_t p = q - 1;
        for (int i = 0; i < 3; ++i) {
            std::uint32_t set = 0u - std::uint32_t((a[i] & q) != 0);
            std::uint32_t t = (a[0] ^ a[i]) & p & ~set;
            a[0] ^= (p & set) | t;
            a[i] ^= t;
        }
    }
    // Gray encoding.
    a[1] ^= a[0];
    a[2] ^= a[1];
    std::uint32_t t = 0;
    for (std::uint32_t q = top; q > 1; q >>= 1)
        t ^= (q - 1) & (0u - std::uint32_t((a[2] & q) != 0));
    for (auto& c : a) c ^= t;
    return morton_encode(a[0], a[1], a[2]);
}

// hilbert_encode of n <= kHilbertBlock points at once, a[axis][k] the coordinates of point k
// (overwritten): the same steps with the loop over points innermost, so that it vectorises.
inline constexpr std::size_t kHilbertBlock = 64;
inline void hilbert_encode_block(std::uint32_t (&a)[3][kHilbertBlock], std::size_t n,
                                 std::uint64_t* keys) {
    constexpr std::uint32_t top = 1u << (kKeyBitsPerAxis - 1);
    for (std::uint32_t q = top; q > 1; q >>= 1) {
        const std::uint32_t p = q - 1;
        for (int i = 0; i < 3; ++i) {
#pragma omp simd
            for (std::size_t k = 0; k < n; ++k) {
                std::uint32_t set = 0u - std::uint32_t((a[i][k] & q) != 0);
                std::uint32_t t = (a[0][k] ^ a[i][k]) & p & ~set;
                a[0][k] ^= (p & set) | t;
                a[i][k] ^= t;
            }
        }
    }
    std::uint32_t t[kHilbertBlock];
#pragma omp simd
    for (std::size_t k = 0; k < n; ++k) {
        a[1][k] ^= a[0][k];
        a[2][k] ^= a[1][k];
        t[k] = 0;
    }
    for (std::uint32_t q = top; q > 1; q >>= 1)
#pragma omp simd
        for (std::size_t k = 0; k < n; ++k)
            t[k] ^= (q - 1) & (0u - std::uint32_t((a[2][k] & q) != 0));
#pragma omp simd
    for (std::size_t k = 0; k < n; ++k)
        keys[k] = morton_encode(a[0][k] ^ t[k], a[1][k] ^ t[k], a[2][k] ^ t[k]);
}

EXASPH_HD constexpr std::array<std::uint32_t, 3> hilbert_decode(std::uint64_t key) {
    auto d = morton_decode(key);
    std::uint32_t a[3] = {d[0], d[1], d[2]};
    // Gray decoding.
    std::uint32_t t = a[2] >> 1;
    a[2] ^= a[1];
    a[1] ^= a[0];
    a[0] ^= t;
    // Redo the rotations/reflections from the bottom bit up.
    for (std::uint32_t q = 2; q != (1u << kKeyBitsPerAxis); q <<= 1) {
        std::uint32_t p = q - 1;
        for (int i = 2; i >= 0; --i) {
            if (a[i] & q) {
                a[0] ^= p;
            } else {
                std::uint32_t s = (a[0] ^ a[i]) & p;
                a[0] ^= s;
                a[i] ^= s;
            }
        }
    }
    return {a[0], a[1], a[2]};
}

} // namespace exasph
