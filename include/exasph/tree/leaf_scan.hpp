#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <type_traits>

#include "exasph/tree/neighbour_codec.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/simd_sets.hpp"

// The leaf scan of the neighbour search (tree/neighbour_encode.hpp): one candidate leaf's
// particles tested against a particle's reach, the hits appended to its record as bits. Written
// once on the lane sets (util/simd_sets.hpp) where the build has them, and as the portable loop
// the compiler vectorises; both compute the same distances (the minimum image where it may
// matter, then r2 < 4 max(h_a, h_b)^2).
namespace exasph {

#ifdef EXASPH_SIMD_LANES
// The leaf scan on lane set V: a step of V::kStep candidates (two halves of doubles), the hit
// mask appended to the record as it is. Sixteen a step with AVX-512: a leaf (~15-30 particles
// on Sedov lattices) takes one or two steps, few exits to mispredict.
template <class V, bool kWrap>
std::uint32_t scan_leaf_lanes(std::uint32_t begin, std::uint32_t end, const SearchView<double>& p,
                              const double pos[3], double hi, bool symmetric,
                              const PeriodicImage<double>& im, std::uint32_t self,
                              codec::BitWriter& out) {
    using D = typename V::D;
    using M = typename V::M;
    const D centre[3] = {V::splat(pos[0]), V::splat(pos[1]), V::splat(pos[2])};
    const D vhi = V::splat(hi), four = V::splat(4.0);
    const simd::Image<V> image(im);
    const double* coord[3] = {p.x, p.y, p.z};
    // The hit bits of the candidates b.. whose lanes `valid` holds (lanes outside: not read).
    auto hits = [&](std::uint32_t b, M valid) {
        D r2 = V::splat(0.0);
        for (int d = 0; d < 3; ++d) {
            D x = V::load(coord[d] + b, valid) - centre[d];
            if constexpr (kWrap) x = image(x, d);
            r2 = d == 0 ? x * x : r2 + x * x;
        }
        const D hh = symmetric ? max(vhi, V::load(p.h + b, valid)) : vhi;
        return simd::bits((r2 < four * hh * hh) & valid);
    };
    std::uint32_t count = 0;
    for (std::uint32_t b = begin; b < end; b += V::kStep) {
        const std::uint32_t n = std::min<std::uint32_t>(V::kStep, end - b);
        const auto lanes = V::first(n);
        std::uint32_t hit = hits(b, V::half(lanes, 0));
        if (n > std::uint32_t(V::kHalf)) hit |= hits(b + V::kHalf, V::half(lanes, 1)) << V::kHalf;
        if (self - b < n) hit &= ~(1u << (self - b)); // (unsigned: false for self < b)
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
#ifdef EXASPH_SIMD_LANES
    if constexpr (std::is_same_v<T, double>)
        return scan_leaf_lanes<simd::Native, kWrap>(begin, end, p, pos, hi, symmetric, im, self,
                                                    out);
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
                dx = min_image(dx, lx, hx), dy = min_image(dy, ly, hy), dz = min_image(dz, lz, hz);
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
