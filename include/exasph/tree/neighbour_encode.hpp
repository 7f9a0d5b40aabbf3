#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <type_traits>
#include <vector>

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

#include "exasph/tree/neighbour_codec.hpp"
#include "exasph/tree/neighbour_search.hpp"
#include "exasph/util/annotate.hpp"

// The search-and-encode steps of NeighbourLists (tree/neighbour_lists.hpp): the candidate
// leaves of a group and each particle's part of the group record.
namespace exasph {

// Record header: the candidate leaves as (gap, size) pairs. Leaves come from depth-first
// walks of the owned tree and then of the halo tree (indices after the owned), so they are
// ascending; returns false if not.
template <class T>
bool encode_candidates(const std::vector<const OctreeNode<T>*>& candidates,
                       std::vector<std::uint8_t>& rec) {
    codec::put_varint(rec, std::uint32_t(candidates.size()));
    std::uint32_t end = 0;
    for (const auto* leaf : candidates) {
        if (leaf->begin < end) return false;
        // Most candidates follow the previous one directly: the size carries a "gap follows"
        // flag, so such a leaf takes one byte.
        const std::uint32_t gap = leaf->begin - end;
        codec::put_varint(rec, (leaf->end - leaf->begin) << 1 | (gap != 0 ? 1u : 0u));
        if (gap != 0) codec::put_varint(rec, gap);
        end = leaf->end;
    }
    return true;
}

// Leaves of `tree` that may hold a neighbour of some particle of `group`.
template <class T>
void collect_leaves(const Octree<T>& tree, const OctreeNode<T>& group, const Box<T>& box,
                    NeighbourCriterion crit, std::vector<const OctreeNode<T>*>& out) {
    const auto& nodes = tree.nodes();
    if (nodes.empty()) return;
    std::uint32_t stack[8 * 64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const auto& nd = nodes[stack[--top]];
        T reach = T(2) * (crit == NeighbourCriterion::symmetric ? std::max(group.hmax, nd.hmax)
                                                                : group.hmax);
        if (box_distance2(group, nd, box) >= reach * reach) continue;
        if (nd.first_child < 0) {
            out.push_back(&nd);
            continue;
        }
        for (std::uint32_t c = nd.num_children; c-- > 0;)
            stack[top++] = static_cast<std::uint32_t>(nd.first_child) + c;
    }
}

// The minimum image (PeriodicImage, util/box.hpp) with the period and half-period hoisted
// into scalars by the caller, so that the distance loops vectorise.
template <class T>
EXASPH_INLINE T wrap(T d, T len, T half) {
    d = d > half ? d - len : d;
    return d < -half ? d + len : d;
}

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
    void assign(const std::vector<const OctreeNode<T>*>& leaves, const OctreeNode<T>& group,
                const PeriodicImage<T>& im) {
        const std::size_t n = leaves.size();
        for (int d = 0; d < 3; ++d) c[d].resize(n), e[d].resize(n);
        hmax.resize(n);
        begin.resize(n);
        size.resize(n);
        reached.resize(n);
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
    }
};

#if defined(__AVX512F__) && defined(__AVX512VL__)
// The leaf scan of encode_neighbours with AVX-512: eight candidates per step, the hit mask of the
// compare appended to the record as it is. The same arithmetic as the portable loop (the minimum
// image, then r2 < 4 max(h_a, h_b)^2).
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
    std::uint32_t count = 0;
    for (std::uint32_t b = begin; b < end; b += 8) {
        const std::uint32_t n = std::min<std::uint32_t>(8, end - b);
        const __mmask8 valid = __mmask8((1u << n) - 1);
        __m512d dx = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.x + b), px);
        __m512d dy = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.y + b), py);
        __m512d dz = _mm512_sub_pd(_mm512_maskz_loadu_pd(valid, p.z + b), pz);
        if constexpr (kWrap) dx = wrap8(dx, 0), dy = wrap8(dy, 1), dz = wrap8(dz, 2);
        __m512d r2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                   _mm512_mul_pd(dz, dz));
        __m512d hh = symmetric ? _mm512_max_pd(vhi, _mm512_maskz_loadu_pd(valid, p.h + b)) : vhi;
        __m512d reach2 = _mm512_mul_pd(_mm512_mul_pd(_mm512_set1_pd(4.0), hh), hh);
        __mmask8 hit = _mm512_mask_cmp_pd_mask(valid, r2, reach2, _CMP_LT_OQ);
        if (self >= b && self < b + n) hit &= __mmask8(~(1u << (self - b)));
        out.put(hit, n);
        count += std::uint32_t(__builtin_popcount(hit));
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
        T gx = std::abs(wrap(cx[l] - pos[0], lx, hx)) - ex[l];
        T gy = std::abs(wrap(cy[l] - pos[1], ly, hy)) - ey[l];
        T gz = std::abs(wrap(cz[l] - pos[2], lz, hz)) - ez[l];
        gx = gx > T(0) ? gx : T(0);
        gy = gy > T(0) ? gy : T(0);
        gz = gz > T(0) ? gz : T(0);
        T reach = T(2) * (symmetric ? std::max(hi, lh[l]) : hi);
        reached[l] = gx * gx + gy * gy + gz * gz < reach * reach;
    }
    return reached;
}

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

// Particle i's part of the group record, appended to `rec`: the bitmap of the candidate
// leaves whose boxes come within reach, then one bit per particle of those leaves (in
// candidate order) telling whether it is a neighbour. Returns the neighbour count.
template <class T>
std::uint32_t encode_neighbours(const std::vector<const OctreeNode<T>*>& candidates,
                                CandidateBoxes<T>& boxes, const SearchView<T>& p,
                                const PeriodicImage<T>& im, NeighbourCriterion crit,
                                std::uint32_t i, std::vector<std::uint8_t>& rec) {
    const T pos[3] = {p.x[i], p.y[i], p.z[i]};
    const T hi = p.h[i];
    const bool symmetric = crit == NeighbourCriterion::symmetric;
    const std::size_t nleaves = candidates.size();
    const unsigned char* reached = mark_reached_leaves(boxes, nleaves, pos, hi, symmetric, im);
    const std::uint32_t* leaf_begin = boxes.begin.data();
    const std::uint32_t* leaf_size = boxes.size.data();
    std::uint32_t bits = 0;
#pragma omp simd reduction(+ : bits)
    for (std::size_t l = 0; l < nleaves; ++l) bits += reached[l] ? leaf_size[l] : 0u;
    const std::size_t r0 = rec.size();
    const std::size_t bytes = (nleaves + 7) / 8 + (bits + 7) / 8;
    rec.resize(r0 + bytes + codec::kReadPad);
    codec::BitWriter out(rec.data() + r0);
    for (std::size_t l = 0; l < nleaves; l += 32) {
        const std::size_t n = std::min<std::size_t>(32, nleaves - l);
        std::uint32_t word = 0;
        for (std::size_t k = 0; k < n; ++k) word |= std::uint32_t(reached[l + k]) << k;
        out.put(word, unsigned(n));
    }
    out.align();
    std::uint32_t count = 0;
    for (std::size_t l = 0; l < nleaves; ++l) {
        if (!reached[l]) continue;
        const std::uint32_t b = leaf_begin[l], e = b + leaf_size[l];
        count += boxes.wraps[l] ? scan_leaf<true>(b, e, p, pos, hi, symmetric, im, i, out)
                                : scan_leaf<false>(b, e, p, pos, hi, symmetric, im, i, out);
    }
    out.align();
    rec.resize(r0 + bytes);
    return count;
}

} // namespace exasph
