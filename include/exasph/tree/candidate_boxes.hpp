#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "exasph/tree/leaf_scan.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/simd_sets.hpp"

// The candidate leaves of a leaf group as box arrays, and which of them a particle reaches:
// the first test of the neighbour search's encoding (tree/neighbour_encode.hpp).
namespace exasph {

// The candidate leaves' boxes as arrays (centre, inflated half-width, hmax), so that one
// vectorised loop tests a particle against all of them (node_distance2, same arithmetic), and
// their particle ranges (read per particle without chasing the node pointers: that loop took
// 16 % of the search on Zen 2). `wraps[l]`: whether some particle of leaf l may lie more than
// half a period from some particle of the group along a periodic axis (from the tight boxes;
// fl(x_b - x_a) <= fl(hi_l - lo_g) as rounding is monotonic), i.e. whether the minimum image
// can change a distance; where it cannot, the leaf scan skips it (the same bits, less work: the
// image was half the scan's arithmetic).
template <class T>
struct CandidateBoxes {
    std::vector<T> c[3], e[3], hmax;
    std::vector<std::uint32_t> begin, size;
    std::vector<unsigned char> reached, wraps;
    std::vector<std::uint64_t> reached_words; // bit l: candidate l reached
    bool any_wraps = false;                   // some wraps[l]
    // The box arrays hold whole halves of kLanes: the padding's boxes lie at infinity.
#ifdef EXASPH_SIMD_LANES
    static constexpr std::size_t kLanes = simd::Native::kHalf;
#else
    static constexpr std::size_t kLanes = 4;
#endif
    void assign(const std::vector<const OctreeNode<T>*>& leaves, const OctreeNode<T>& group,
                const PeriodicImage<T>& im) {
        const std::size_t n = leaves.size(), padded = (n + kLanes - 1) / kLanes * kLanes;
        for (int d = 0; d < 3; ++d) {
            c[d].assign(padded, std::numeric_limits<T>::infinity());
            e[d].assign(padded, T(0));
        }
        hmax.assign(padded, T(0));
        begin.resize(n);
        size.resize(n);
        reached.resize(n);
        reached_words.resize((n + 63) / 64);
        wraps.resize(n);
        for (std::size_t l = 0; l < n; ++l) {
            for (int d = 0; d < 3; ++d) {
                c[d][l] = T(0.5) * (leaves[l]->lo[d] + leaves[l]->hi[d]);
                e[d][l] = T(0.5) * (leaves[l]->hi[d] - leaves[l]->lo[d]) * T(kPruneInflate);
            }
            hmax[l] = leaves[l]->hmax;
            begin[l] = leaves[l]->begin;
            size[l] = leaves[l]->end - leaves[l]->begin;
            bool w = false;
            for (int d = 0; d < 3; ++d) {
                const T far =
                    std::max(leaves[l]->hi[d] - group.lo[d], group.hi[d] - leaves[l]->lo[d]);
                w |= im.len[d] > T(0) && !(far <= im.half[d]);
            }
            wraps[l] = w;
        }
        any_wraps = std::find(wraps.begin(), wraps.end(), (unsigned char)1) != wraps.end();
    }
};

// Which candidate leaf boxes come within reach of the particle at pos with smoothing length hi
// (branch-free, vectorised): flags in boxes.reached.
template <class T>
EXASPH_INLINE const unsigned char* mark_reached_leaves(CandidateBoxes<T>& boxes,
                                                       std::size_t nleaves, const T (&pos)[3], T hi,
                                                       bool symmetric, const PeriodicImage<T>& im) {
    const T lx = im.len[0], ly = im.len[1], lz = im.len[2];
    const T hx = im.half[0], hy = im.half[1], hz = im.half[2];
    const T *cx = boxes.c[0].data(), *cy = boxes.c[1].data(), *cz = boxes.c[2].data();
    const T *ex = boxes.e[0].data(), *ey = boxes.e[1].data(), *ez = boxes.e[2].data();
    const T* lh = boxes.hmax.data();
    unsigned char* reached = boxes.reached.data();
#pragma omp simd
    for (std::size_t l = 0; l < nleaves; ++l) {
        T gx = std::abs(min_image(cx[l] - pos[0], lx, hx)) - ex[l];
        T gy = std::abs(min_image(cy[l] - pos[1], ly, hy)) - ey[l];
        T gz = std::abs(min_image(cz[l] - pos[2], lz, hz)) - ez[l];
        gx = gx > T(0) ? gx : T(0);
        gy = gy > T(0) ? gy : T(0);
        gz = gz > T(0) ? gz : T(0);
        T reach = T(2) * (symmetric ? std::max(hi, lh[l]) : hi);
        reached[l] = gx * gx + gy * gy + gz * gz < reach * reach;
    }
    return reached;
}

#ifdef EXASPH_SIMD_LANES
// mark_reached_leaves on lane set V, a half's candidates per compare, as bits (GCC left the
// portable loop scalar: doubles in, bytes out). The same arithmetic: the minimum image (only
// where some leaf of the group may need it, kWrap: CandidateBoxes::any_wraps; elsewhere it
// changes no centre's offset, by the argument of CandidateBoxes::wraps, so the bits are the
// same), the gap to the inflated box per axis clamped at 0, then
// |gap|^2 < (2 max(h_a, hmax_l))^2.
template <class V, bool kWrap>
void reached_leaf_bits_lanes(const CandidateBoxes<double>& boxes, std::size_t nleaves,
                             const double (&pos)[3], double hi, bool symmetric,
                             const PeriodicImage<double>& im, std::uint64_t* words) {
    using D = typename V::D;
    const D p[3] = {V::splat(pos[0]), V::splat(pos[1]), V::splat(pos[2])};
    const simd::Image<V> image(im);
    const D vhi = V::splat(hi), zero = V::splat(0.0), two = V::splat(2.0);
    for (std::size_t w = 0; w < (nleaves + 63) / 64; ++w) {
        std::uint64_t word = 0;
        const std::size_t end = std::min(nleaves, 64 * w + 64);
        for (std::size_t l = 64 * w; l < end; l += V::kHalf) {
            D r2 = zero;
            for (int d = 0; d < 3; ++d) {
                D x = V::load(boxes.c[d].data() + l) - p[d];
                if constexpr (kWrap) x = image(x, d);
                const D g = abs(x) - V::load(boxes.e[d].data() + l);
                const D gap = select(g > zero, g);
                r2 = fma(gap, gap, r2);
            }
            const D h = symmetric ? max(vhi, V::load(boxes.hmax.data() + l)) : vhi;
            const D reach = two * h;
            word |= std::uint64_t(simd::bits(r2 < reach * reach)) << (l - 64 * w);
        }
        // The padding's lanes: never reached, even for a NaN position (whose gaps clamp to 0)
        const std::size_t valid = end - 64 * w;
        words[w] = valid < 64 ? word & ((std::uint64_t(1) << valid) - 1) : word;
    }
}
#endif

// mark_reached_leaves as bits: word w's bit k for candidate 64 w + k (the padding's never set).
template <class T>
EXASPH_INLINE const std::uint64_t* reached_leaf_bits(CandidateBoxes<T>& boxes, std::size_t nleaves,
                                                     const T (&pos)[3], T hi, bool symmetric,
                                                     const PeriodicImage<T>& im) {
    std::uint64_t* words = boxes.reached_words.data();
#ifdef EXASPH_SIMD_LANES
    if constexpr (std::is_same_v<T, double>) {
        using V = simd::Native;
        if (boxes.any_wraps)
            reached_leaf_bits_lanes<V, true>(boxes, nleaves, pos, hi, symmetric, im, words);
        else
            reached_leaf_bits_lanes<V, false>(boxes, nleaves, pos, hi, symmetric, im, words);
        return words;
    }
#endif
    const unsigned char* reached = mark_reached_leaves(boxes, nleaves, pos, hi, symmetric, im);
    for (std::size_t l = 0; l < nleaves; l += 64) {
        std::uint64_t word = 0;
        for (std::size_t k = 0; k < std::min<std::size_t>(64, nleaves - l); ++k)
            word |= std::uint64_t(reached[l + k]) << k;
        words[l / 64] = word;
    }
    return words;
}

} // namespace exasph
