#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/gravity/gravity_node.hpp"
#include "exasph/kernel/softening.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// Read-only view of a gravity tree and its sources (the particles the leaves point into).
template <class T>
struct GravityTreeView {
    const GravityNode<T>* nodes;
    const T *x, *y, *z, *m, *h;
};

struct GravityResult {
    GravityField field;                      // with G = 1
    bool missing = false;                    // the walk needed a node whose particles are not here
    std::uint32_t multipoles = 0, pairs = 0; // interactions evaluated
};

// Softened pair field (physics.md §8) at displacement d = x_a - x_b from a source of mass m, with
// the pair's smoothing length h_ab = (h_a + h_b)/2.
template <class T>
EXASPH_HD EXASPH_INLINE GravityField pair_field(double dx, double dy, double dz, double m,
                                                double hab, const SofteningView<T>& soft) {
    const double inv_h = 1.0 / hab;
    const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
    T force, psi;
    soft.eval(T(r * inv_h), force, psi);
    const double s = -m * double(force) * inv_h * inv_h * inv_h;
    return {s * dx, s * dy, s * dz, -m * double(psi) * inv_h};
}

// Adds the pair field of source j at a particle at x with smoothing length h.
template <class T>
EXASPH_HD void add_pair_field(const GravityTreeView<T>& tv, const SofteningView<T>& soft,
                              std::uint32_t j, double x, double y, double z, double h,
                              GravityField& f) {
    add_field(f, pair_field(x - tv.x[j], y - tv.y[j], z - tv.z[j], double(tv.m[j]),
                            0.5 * (h + double(tv.h[j])), soft));
}

// Barnes-Hut walk for one particle (position x, smoothing length h, source index `self`, which
// is skipped): nodes beyond their opening radius and outside softening reach act through their
// multipole, leaves that must be opened act particle by particle. Children are visited in order,
// so the sum does not depend on how the tree was distributed.
template <class T>
EXASPH_HD GravityResult gravity_kern(double x, double y, double z, double h, std::uint32_t self,
                                     const GravityTreeView<T>& tv, const SofteningView<T>& soft) {
    constexpr int kStack = 256; // depth <= 21 levels, <= 7 siblings waiting per level
    std::int32_t stack[kStack];
    int top = 0;
    stack[top++] = 0;
    GravityResult res;
    while (top > 0) {
        const GravityNode<T>& nd = tv.nodes[stack[--top]];
        if (nd.mp.mass <= 0) continue;
        if (!must_open(nd, x, y, z, h)) {
            add_multipole_field(nd.mp, x - nd.mp.com[0], y - nd.mp.com[1], z - nd.mp.com[2],
                                res.field);
            ++res.multipoles;
            continue;
        }
        if (nd.first_child >= 0) {
            for (std::int32_t c = std::int32_t(nd.num_children) - 1; c >= 0; --c)
                stack[top++] = nd.first_child + c;
            continue;
        }
        if (nd.end == nd.begin) {
            res.missing = true;
            continue;
        }
        for (std::uint32_t j = nd.begin; j < nd.end; ++j)
            if (j != self) add_pair_field(tv, soft, j, x, y, z, h, res.field);
        res.pairs += nd.end - nd.begin;
    }
    return res;
}

} // namespace exasph
