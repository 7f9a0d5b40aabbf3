#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "exasph/gravity/multipole.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// What every rank knows about a global leaf (and every node knows about itself): multipole, tight
// box and largest h of its particles (empty: mass 0).
template <class T>
struct LeafSummary {
    Multipole mp;
    T lo[3] = {0, 0, 0};
    T hi[3] = {0, 0, 0};
    T hmax = 0;
};

// One node of the gravity tree: its multipole, the tight box and largest h of its particles, and
// the squared distance from the centre of mass inside which it must be opened.
// Kinds: first_child >= 0: inner node; else end > begin: leaf with sources [begin, end); else a
// node whose particles are not on this rank (a remote top-tree leaf that no walk here opens).
template <class T>
struct GravityNode : LeafSummary<T> {
    double open2 = 0;
    std::int32_t first_child = -1;
    std::uint32_t num_children = 0;
    std::uint32_t begin = 0, end = 0;
};

// Opening radius (physics.md §8, Barnes-Hut with the offset correction of Barnes 1994): a node of
// side l (longest side of its tight box) whose centre of mass lies delta from the box centre is
// used as a multipole only beyond l / theta + delta, so lopsided nodes are opened earlier.
template <class T>
void set_opening_radius(GravityNode<T>& nd, double theta) {
    double l = 0, delta2 = 0;
    for (int d = 0; d < 3; ++d) {
        l = std::max(l, double(nd.hi[d]) - double(nd.lo[d]));
        const double c = 0.5 * (double(nd.hi[d]) + double(nd.lo[d])) - nd.mp.com[d];
        delta2 += c * c;
    }
    const double r = l / theta + std::sqrt(delta2);
    nd.open2 = r * r;
}

// Squared distance from a point to a box (0 inside).
template <class T>
EXASPH_HD double point_box_distance2(double x, double y, double z, const T* lo, const T* hi) {
    const double p[3] = {x, y, z};
    double d2 = 0;
    for (int d = 0; d < 3; ++d) {
        double e = 0;
        if (p[d] < lo[d])
            e = double(lo[d]) - p[d];
        else if (p[d] > hi[d])
            e = p[d] - double(hi[d]);
        d2 += e * e;
    }
    return d2;
}

// Squared distance between two boxes (0 when they overlap).
template <class T>
double box_box_distance2(const T* alo, const T* ahi, const T* blo, const T* bhi) {
    double d2 = 0;
    for (int d = 0; d < 3; ++d) {
        double e =
            std::max({double(alo[d]) - double(bhi[d]), double(blo[d]) - double(ahi[d]), 0.0});
        d2 += e * e;
    }
    return d2;
}

// Whether a particle at x with smoothing length h must open the node: inside the opening radius,
// or within reach of the softened interaction (r < 2 h_ab, h_ab = (h_a + h_b)/2 <= (h + hmax)/2).
template <class T>
EXASPH_HD bool must_open(const GravityNode<T>& nd, double x, double y, double z, double h) {
    const double dx = x - nd.mp.com[0], dy = y - nd.mp.com[1], dz = z - nd.mp.com[2];
    if (dx * dx + dy * dy + dz * dz <= nd.open2) return true;
    const double reach = h + double(nd.hmax);
    return point_box_distance2(x, y, z, nd.lo, nd.hi) < reach * reach;
}

// Whether some particle inside the box [lo, hi] with smoothing lengths up to hmax may open the
// node: the conservative (box) form of must_open, with a margin for round-off.
template <class T>
bool box_may_open(const GravityNode<T>& nd, const T* lo, const T* hi, T hmax) {
    constexpr double kMargin = 1.0 + 1e-6;
    const double c2 = point_box_distance2(nd.mp.com[0], nd.mp.com[1], nd.mp.com[2], lo, hi);
    if (c2 <= nd.open2 * kMargin) return true;
    const double reach = (double(hmax) + double(nd.hmax)) * kMargin;
    return box_box_distance2(nd.lo, nd.hi, lo, hi) < reach * reach;
}

} // namespace exasph
