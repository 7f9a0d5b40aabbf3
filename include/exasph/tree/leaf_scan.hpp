#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <type_traits>

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

#include "exasph/tree/neighbour_codec.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/util/annotate.hpp"

// The leaf scan of the neighbour search (tree/neighbour_encode.hpp): one candidate leaf's
// particles tested against a particle's reach, the hits appended to its record as bits. An
// AVX-512 and an AVX2 version, and the portable loop the compiler vectorises; all compute the
// same distances (the minimum image where it may matter, then r2 < 4 max(h_a, h_b)^2).
namespace exasph {

// The minimum image (PeriodicImage, util/box.hpp) with the period and half-period hoisted
// into scalars by the caller, so that the distance loops vectorise.
template <class T>
EXASPH_INLINE T wrap(T d, T len, T half) {
    d = d > half ? d - len : d;
    return d < -half ? d + len : d;
}

#if defined(__AVX512F__) && defined(__AVX512VL__)
// The leaf scan of encode_neighbours with AVX-512: sixteen candidates per step (two compares of
// eight), the hit mask appended to the record as it is. The same arithmetic as the portable loop
// (the minimum image, then r2 < 4 max(h_a, h_b)^2). Sixteen a step: a leaf (~15-30 particles on
// Sedov lattices) takes one or two steps instead of two to four, fewer exits to mispredict.
template <bool kWrap>
std::uint32_t scan_leaf_avx512(std::uint32_t begin, std::uint32_t end, const SearchView<double>& p,
                               const double pos[3], double hi, bool symmetric,
                               const PeriodicImage<double>& im, std::uint32_t self,
                               codec::BitWriter& out) {
    const __m512d px = _mm512_set1_pd(pos[0]), py = _mm512_set1_pd(pos[1]),
                  pz = _mm512_set1_pd(pos[2]), vhi = _mm512_set1_pd(hi);
    const __m512d len[3] = {_mm512_set1_pd(im.len[0]), _mm512_set1_pd(im.len[1]),
                            _mm512_set1_pd(im.len[2])};
    const __m512d half[3] = {_mm512_set1_pd(im.half[0]), _mm512_set1_pd(im.half[1]),
                             _mm512_set1_pd(im.half[2])};
    auto wrap8 = [&](__m512d d, int axis) {
        __mmask8 above = _mm512_cmp_pd_mask(d, half[axis], _CMP_GT_OQ);
        d = _mm512_mask_sub_pd(d, above, d, len[axis]);
        __mmask8 below =
            _mm512_cmp_pd_mask(d, _mm512_sub_pd(_mm512_setzero_pd(), half[axis]), _CMP_LT_OQ);
        return _mm512_mask_add_pd(d, below, d, len[axis]);
    };
    // The hit bits of the candidates b.. whose lanes `valid` holds (eight at most).
    auto hits8 = [&](std::uint32_t b, __mmask8 valid) {
        __m512d dx = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.x + b), px);
        __m512d dy = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.y + b), py);
        __m512d dz = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.z + b), pz);
        if constexpr (kWrap) dx = wrap8(dx, 0), dy = wrap8(dy, 1), dz = wrap8(dz, 2);
        __m512d r2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                   _mm512_mul_pd(dz, dz));
        // the zero-masking max with every lane: the plain one trips GCC 12's false "maybe
        // uninitialized" (bug 105593) on its undefined pass-through vector
        __m512d hh = symmetric ? _mm512_maskz_max_pd(__mmask8(0xff), vhi,
                                                     _mm512_maskz_loadu_pd(valid, p.h + b))
                               : vhi;
        __m512d reach2 = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(4.0), hh), hh);
        return std::uint32_t(_mm512_mask_cmp_pd_mask(valid, r2, reach2, _CMP_LT_OQ));
    };
    std::uint32_t count = 0;
    for (std::uint32_t b = begin; b < end; b += 16) {
        const std::uint32_t n = std::min<std::uint32_t>(16, end - b);
        const std::uint32_t valid = (1u << n) - 1u;
        std::uint32_t hit = hits8(b, __mmask8(valid)) | hits8(b + 8, __mmask8(valid >> 8)) << 8;
        if (self - b < n) hit &= ~(1u << (self - b)); // (unsigned: false for self < b)
        out.put(hit, n);
        count += std::uint32_t(std::popcount(hit));
    }
    return count;
}
#elif defined(__AVX2__)
// The leaf scan with AVX2 (hosts without AVX-512): the same arithmetic as scan_leaf_avx512, four
// candidates per compare and eight per bit field, the hit bits taken with movemask (the portable
// loop's flags, packed one by one, cost as much as the distances).
template <bool kWrap>
std::uint32_t scan_leaf_avx2(std::uint32_t begin, std::uint32_t end, const SearchView<double>& p,
                             const double pos[3], double hi, bool symmetric,
                             const PeriodicImage<double>& im, std::uint32_t self,
                             codec::BitWriter& out) {
    const __m256d centre[3] = {_mm256_set1_pd(pos[0]), _mm256_set1_pd(pos[1]),
                               _mm256_set1_pd(pos[2])};
    const __m256d vhi = _mm256_set1_pd(hi);
    __m256d len[3], half[3], neg_half[3];
    for (int d = 0; d < 3; ++d) {
        len[d] = _mm256_set1_pd(im.len[d]);
        half[d] = _mm256_set1_pd(im.half[d]);
        neg_half[d] = _mm256_sub_pd(_mm256_setzero_pd(), half[d]);
    }
    const double* coord[3] = {p.x, p.y, p.z};
    const __m256i lane = _mm256_setr_epi64x(0, 1, 2, 3);
    // Hit flags of the four candidates from b on (lanes at or past `end` are not loaded).
    auto hits4 = [&](std::uint32_t b) {
        const __m256i valid = _mm256_cmpgt_epi64(_mm256_set1_epi64x(std::int64_t(end - b)), lane);
        __m256d r2 = _mm256_setzero_pd();
        for (int d = 0; d < 3; ++d) {
            __m256d x = _mm256_sub_pd(_mm256_maskload_pd(coord[d] + b, valid), centre[d]);
            if constexpr (kWrap) {
                x = _mm256_blendv_pd(x, _mm256_sub_pd(x, len[d]),
                                     _mm256_cmp_pd(x, half[d], _CMP_GT_OQ));
                x = _mm256_blendv_pd(x, _mm256_add_pd(x, len[d]),
                                     _mm256_cmp_pd(x, neg_half[d], _CMP_LT_OQ));
            }
            r2 = d == 0 ? _mm256_mul_pd(x, x) : _mm256_add_pd(r2, _mm256_mul_pd(x, x));
        }
        const __m256d hh = symmetric ? _mm256_max_pd(vhi, _mm256_maskload_pd(p.h + b, valid)) : vhi;
        const __m256d reach2 = _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(4.0), hh), hh);
        const __m256d hit =
            _mm256_and_pd(_mm256_cmp_pd(r2, reach2, _CMP_LT_OQ), _mm256_castsi256_pd(valid));
        return std::uint32_t(_mm256_movemask_pd(hit));
    };
    std::uint32_t count = 0;
    for (std::uint32_t b = begin; b < end; b += 8) {
        const std::uint32_t n = std::min<std::uint32_t>(8, end - b);
        std::uint32_t hit = hits4(b) | (n > 4 ? hits4(b + 4) << 4 : 0u);
        if (self >= b && self < b + n) hit &= ~(1u << (self - b));
        out.put(hit, n);
        count += std::uint32_t(std::popcount(hit));
    }
    return count;
}
#endif

// One reached leaf's hit bits for particle `self`: a branch-free distance pass that the
// compiler vectorises, then the flags packed into bits. Returns the neighbour count. kWrap:
// apply the minimum image (CandidateBoxes::wraps).
template <bool kWrap, class T>
EXASPH_INLINE std::uint32_t
scan_leaf(std::uint32_t begin, std::uint32_t end, const SearchView<T>& p, const T (&pos)[3], T hi,
          bool symmetric, const PeriodicImage<T>& im, std::uint32_t self, codec::BitWriter& out) {
#if defined(__AVX512F__) && defined(__AVX512VL__)
    if constexpr (std::is_same_v<T, double>)
        return scan_leaf_avx512<kWrap>(begin, end, p, pos, hi, symmetric, im, self, out);
#elif defined(__AVX2__)
    if constexpr (std::is_same_v<T, double>)
        return scan_leaf_avx2<kWrap>(begin, end, p, pos, hi, symmetric, im, self, out);
#endif
    const T lx = im.len[0], ly = im.len[1], lz = im.len[2];
    const T hx = im.half[0], hy = im.half[1], hz = im.half[2];
    constexpr std::uint32_t kChunk = 32;
    unsigned char hit[kChunk];
    std::uint32_t count = 0;
    for (std::uint32_t b = begin; b < end; b += kChunk) {
        const std::uint32_t n = std::min(kChunk, end - b);
        const T *xb = p.x + b, *yb = p.y + b, *zb = p.z + b, *hb = p.h + b;
#pragma omp simd
        for (std::uint32_t k = 0; k < n; ++k) {
            T dx = xb[k] - pos[0], dy = yb[k] - pos[1], dz = zb[k] - pos[2];
            if constexpr (kWrap)
                dx = wrap(dx, lx, hx), dy = wrap(dy, ly, hy), dz = wrap(dz, lz, hz);
            T r2 = dx * dx + dy * dy + dz * dz;
            T hh = symmetric ? std::max(hi, hb[k]) : hi;
            hit[k] = (r2 < T(4) * hh * hh) & (b + k != self);
        }
        std::uint32_t word = 0;
        for (std::uint32_t k = 0; k < n; ++k) word |= std::uint32_t(hit[k]) << k;
        out.put(word, n);
        count += std::uint32_t(std::popcount(word));
    }
    return count;
}

} // namespace exasph
