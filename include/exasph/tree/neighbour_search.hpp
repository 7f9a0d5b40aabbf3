#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "exasph/tree/octree.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Which pairs are neighbours (physics.md §2).
//  gather:    r_ab < 2 h_a                (enough for density and IAD)
//  symmetric: r_ab < 2 max(h_a, h_b)      (needed for exact conservation in momentum-energy)
enum class NeighbourCriterion { gather, symmetric };

// Read-only positions and smoothing lengths for the search.
template <class T>
struct SearchView {
    const T* x;
    const T* y;
    const T* z;
    const T* h;
};

// Squared minimum-image distance between particles i and j. Shared by the tree search and the
// brute-force reference so that both decide ties identically.
template <class T>
inline T pair_distance2(const SearchView<T>& p, const Box<T>& box, std::uint32_t i,
                        std::uint32_t j) {
    T dx = box.min_image(p.x[j] - p.x[i], 0);
    T dy = box.min_image(p.y[j] - p.y[i], 1);
    T dz = box.min_image(p.z[j] - p.z[i], 2);
    return dx * dx + dy * dy + dz * dz;
}

template <class T>
inline bool is_neighbour(T r2, T hi, T hj, NeighbourCriterion crit) {
    T hh = crit == NeighbourCriterion::symmetric ? std::max(hi, hj) : hi;
    return r2 < T(4) * hh * hh;
}

// Round-off slack of tree pruning: half-widths grow by this factor, so that a particle on a box
// face is never pruned.
inline constexpr double kPruneInflate = 1.000000001;

// Squared minimum-image distance from a point to a node's box (conservative).
template <class T>
inline T node_distance2(const OctreeNode<T>& nd, const T p[3], const Box<T>& box) {
    return box.box_distance2(nd.lo, nd.hi, p, p, T(kPruneInflate));
}

// Squared minimum-image distance between two nodes' boxes (conservative).
template <class T>
inline T box_distance2(const OctreeNode<T>& a, const OctreeNode<T>& b, const Box<T>& box) {
    return box.box_distance2(a.lo, a.hi, b.lo, b.hi, T(kPruneInflate));
}

// Neighbours of particle i (self excluded), in tree order. Writes at most `cap` indices to `out`
// and returns the true count, which may exceed `cap`.
template <class T>
std::uint32_t find_neighbours(const Octree<T>& tree, const SearchView<T>& p, const Box<T>& box,
                              NeighbourCriterion crit, std::uint32_t i, std::uint32_t* out,
                              std::uint32_t cap) {
    const auto& nodes = tree.nodes();
    if (nodes.empty()) return 0;
    const T pos[3] = {p.x[i], p.y[i], p.z[i]};
    const T hi = p.h[i];
    std::uint32_t count = 0;
    std::uint32_t stack[8 * 64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const auto& nd = nodes[stack[--top]];
        T reach = T(2) * (crit == NeighbourCriterion::symmetric ? std::max(hi, nd.hmax) : hi);
        if (node_distance2(nd, pos, box) >= reach * reach) continue;
        if (nd.first_child >= 0) {
            for (std::uint32_t c = nd.num_children; c-- > 0;)
                stack[top++] = static_cast<std::uint32_t>(nd.first_child) + c;
            continue;
        }
        for (std::uint32_t j = nd.begin; j < nd.end; ++j) {
            if (j == i) continue;
            if (!is_neighbour(pair_distance2(p, box, i, j), hi, p.h[j], crit)) continue;
            if (count < cap) out[count] = j;
            ++count;
        }
    }
    return count;
}

// The search radius must stay below half of every period for the minimum image to be the only
// image within reach.
template <class T>
void check_periodic_reach(const Box<T>& box, T hmax) {
    for (int d = 0; d < 3; ++d) {
        if (box.periodic[d] && T(4) * hmax >= box.length(d))
            throw input_error(
                "smoothing length h = " + std::to_string(hmax) +
                " is too large for the periodic box: 2h must be below half the period " +
                std::to_string(box.length(d)) + " (use more particles)");
    }
}

} // namespace exasph
