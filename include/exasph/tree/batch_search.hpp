#pragma once
#include <cstdint>

#include "exasph/tree/neighbour_search.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/box.hpp"

// The neighbour search of the GPU path (docs/architecture.md, "Backends"): one independent tree
// walk per particle, first over the owned tree and then over the halo tree, with the same pair
// test as the CPU lists (tree/neighbour_encode.hpp: the minimum image of PeriodicImage, then
// r2 < 4 max(h_a, h_b)^2), so that both find the same neighbours in the same order (ascending
// particle index). Pure host/device functions: a CUDA thread or an OpenMP iteration runs one
// particle; nothing is allocated, nothing shared.
namespace exasph {

// The lists of the GPU path are interleaved per batch of kBatch consecutive particles: neighbour
// n of the batch's lane l is at batch_offset + n * kBatch + l, so that 32 threads of a warp read
// their n-th neighbours from one cache line (NeighbourSpan's stride).
inline constexpr std::uint32_t kBatch = 32;

// A tree as the device sees it: its node array (node 0 the root, as Octree<T> builds it).
template <class T>
struct TreeView {
    const OctreeNode<T>* nodes = nullptr;
    std::uint32_t count = 0;
};

// Depth-first stack of a walk: at most 7 pending siblings per level of a 21-level key (plus the
// root and one level of slack).
inline constexpr int kWalkStack = 8 * 22;

// The pair test of the CPU lists (scan_leaf in tree/neighbour_encode.hpp), same arithmetic.
template <class T>
EXASPH_HD EXASPH_INLINE bool is_pair(const SearchView<T>& p, const PeriodicImage<T>& im,
                                     const T (&pos)[3], T hi, bool symmetric, std::uint32_t j) {
    const T dx = im(p.x[j] - pos[0], 0);
    const T dy = im(p.y[j] - pos[1], 1);
    const T dz = im(p.z[j] - pos[2], 2);
    const T r2 = dx * dx + dy * dy + dz * dz;
    const T hh = symmetric ? (hi > p.h[j] ? hi : p.h[j]) : hi;
    return r2 < T(4) * hh * hh;
}

// Walks `tree` for particle i; each neighbour j goes to out[(found + k) * stride] while found + k
// < cap. Returns the number found in this tree.
template <class T>
EXASPH_HD std::uint32_t walk_tree(const TreeView<T>& tree, const SearchView<T>& p,
                                  const Box<T>& box, const PeriodicImage<T>& im, bool symmetric,
                                  std::uint32_t i, std::uint32_t found, std::uint32_t* out,
                                  std::uint32_t stride, std::uint32_t cap) {
    if (tree.count == 0) return 0;
    const T pos[3] = {p.x[i], p.y[i], p.z[i]};
    const T hi = p.h[i];
    std::uint32_t stack[kWalkStack];
    int top = 0;
    stack[top++] = 0;
    std::uint32_t count = 0;
    while (top > 0) {
        const OctreeNode<T>& nd = tree.nodes[stack[--top]];
        const T reach = T(2) * (symmetric && nd.hmax > hi ? nd.hmax : hi);
        if (box.box_distance2(nd.lo, nd.hi, pos, pos, T(kPruneInflate)) >= reach * reach) continue;
        if (nd.first_child >= 0) {
            for (std::uint32_t c = nd.num_children; c-- > 0;)
                stack[top++] = static_cast<std::uint32_t>(nd.first_child) + c;
            continue;
        }
        for (std::uint32_t j = nd.begin; j < nd.end; ++j) {
            if (j == i || !is_pair(p, im, pos, hi, symmetric, j)) continue;
            if (found + count < cap) out[(found + count) * stride] = j;
            ++count;
        }
    }
    return count;
}

// Neighbours of particle i in the owned tree and then the halo tree, written as above up to
// `cap` (cap 0 with out null: only counts). Returns the true count.
template <class T>
EXASPH_HD std::uint32_t search_particle(const TreeView<T>& owned, const TreeView<T>& halos,
                                        const SearchView<T>& p, const Box<T>& box, bool symmetric,
                                        std::uint32_t i, std::uint32_t* out, std::uint32_t stride,
                                        std::uint32_t cap) {
    const PeriodicImage<T> im(box);
    const std::uint32_t n = walk_tree(owned, p, box, im, symmetric, i, 0, out, stride, cap);
    return n + walk_tree(halos, p, box, im, symmetric, i, n, out, stride, cap);
}

} // namespace exasph
