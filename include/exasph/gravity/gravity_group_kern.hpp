#pragma once
#include <cstdint>
#include <vector>

#include "exasph/gravity/gravity_kern.hpp"

namespace exasph {

// One interaction list shared by a group of particles (a leaf of the gravity tree): the nodes
// that no particle of the group opens (packed as structure of arrays, so that the loop over them
// vectorises) and the source ranges of the leaves some particle of the group opens. Scratch
// owned by one thread; reused from group to group without reallocation.
struct GravityInteractionList {
    std::vector<std::uint32_t> nodes;
    std::vector<std::uint32_t> ranges; // [begin, end) pairs of source indices
    std::vector<std::int32_t> stack;
    std::vector<double> mass, cx, cy, cz, q[6], s[10];
    bool missing = false;
};

// Walks the tree once for the group node `group`: a node is used as a multipole when no
// particle inside the group's box (h up to its hmax) must open it (box_may_open, a superset of
// the per-particle must_open, so the group list is at least as accurate).
template <class T>
void collect_interactions(const GravityTreeView<T>& tv, const GravityNode<T>& group,
                          GravityInteractionList& list) {
    list.nodes.clear();
    list.ranges.clear();
    list.missing = false;
    auto& stack = list.stack;
    stack.assign(1, 0);
    while (!stack.empty()) {
        const std::int32_t k = stack.back();
        stack.pop_back();
        const GravityNode<T>& nd = tv.nodes[k];
        if (nd.mp.mass <= 0) continue;
        if (!box_may_open(nd, group.lo, group.hi, group.hmax)) {
            list.nodes.push_back(std::uint32_t(k));
        } else if (nd.first_child >= 0) {
            for (std::int32_t c = std::int32_t(nd.num_children) - 1; c >= 0; --c)
                stack.push_back(nd.first_child + c);
        } else if (nd.end > nd.begin) {
            list.ranges.push_back(nd.begin);
            list.ranges.push_back(nd.end);
        } else {
            list.missing = true;
        }
    }
    const std::size_t n = list.nodes.size();
    for (auto* v : {&list.mass, &list.cx, &list.cy, &list.cz}) v->resize(n);
    for (auto& v : list.q) v.resize(n);
    for (auto& v : list.s) v.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Multipole& mp = tv.nodes[list.nodes[i]].mp;
        list.mass[i] = mp.mass;
        list.cx[i] = mp.com[0];
        list.cy[i] = mp.com[1];
        list.cz[i] = mp.com[2];
        for (int c = 0; c < 6; ++c) list.q[c][i] = mp.q[c];
        for (int c = 0; c < 10; ++c) list.s[c][i] = mp.s[c];
    }
}

// Field (G = 1) at a particle of the group (position x, smoothing length h, source index `self`
// skipped) from the group's interaction list.
template <class T>
GravityField evaluate_interactions(const GravityInteractionList& list, const GravityTreeView<T>& tv,
                                   const SofteningView<T>& soft, double x, double y, double z,
                                   double h, std::uint32_t self) {
    double ax = 0, ay = 0, az = 0, phi = 0;
    const std::size_t n = list.mass.size();
    const double *m = list.mass.data(), *cx = list.cx.data(), *cy = list.cy.data(),
                 *cz = list.cz.data();
    // Column pointers set once, outside the loop: the accessors then index them directly, which
    // lets the compiler vectorise the loop (building the pointer arrays per iteration kept it
    // scalar).
    const double* q[6];
    const double* s[10];
    for (int c = 0; c < 6; ++c) q[c] = list.q[c].data();
    for (int c = 0; c < 10; ++c) s[c] = list.s[c].data();
#pragma omp simd reduction(+ : ax, ay, az, phi)
    for (std::size_t k = 0; k < n; ++k) {
        const GravityField g = multipole_field(
            m[k], [&](int c) { return q[c][k]; }, [&](int c) { return s[c][k]; }, x - cx[k],
            y - cy[k], z - cz[k]);
        ax += g.ax;
        ay += g.ay;
        az += g.az;
        phi += g.phi;
    }
    for (std::size_t r = 0; r < list.ranges.size(); r += 2) {
        const std::uint32_t b = list.ranges[r], e = list.ranges[r + 1];
#pragma omp simd reduction(+ : ax, ay, az, phi)
        for (std::uint32_t j = b; j < e; ++j) {
            const double keep = j == self ? 0.0 : 1.0; // the particle itself
            const GravityField g =
                pair_field(x - tv.x[j], y - tv.y[j], z - tv.z[j], keep * double(tv.m[j]),
                           0.5 * (h + double(tv.h[j])), soft);
            ax += g.ax;
            ay += g.ay;
            az += g.az;
            phi += g.phi;
        }
    }
    return {ax, ay, az, phi};
}

} // namespace exasph
