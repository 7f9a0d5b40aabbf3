#pragma once
#include <cstdint>
#include <vector>

#include "exasph/gravity/ewald_table.hpp"
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
    std::vector<double> mass, cx, cy, cz, d2, q[6], s[10];
    bool missing = false;
};

// Walks the tree once for the group node `group`: a node is used as a multipole when no
// particle inside the group's box (h up to its hmax) must open it (box_may_open, a superset of
// the per-particle must_open, so the group list is at least as accurate).
template <bool kPeriodic, class T>
void collect_interactions(const GravityTreeView<T>& tv, const GravityNode<T>& group,
                          const GravityImage& img, GravityInteractionList& list) {
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
        if (!box_may_open<kPeriodic>(nd, group.lo, group.hi, group.hmax, img)) {
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
    for (auto* v : {&list.mass, &list.cx, &list.cy, &list.cz, &list.d2}) v->resize(n);
    for (auto& v : list.q) v.resize(n);
    for (auto& v : list.s) v.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Multipole& mp = tv.nodes[list.nodes[i]].mp;
        list.mass[i] = mp.mass;
        list.cx[i] = mp.com[0];
        list.cy[i] = mp.com[1];
        list.cz[i] = mp.com[2];
        list.d2[i] = mp.d2;
        for (int c = 0; c < 6; ++c) list.q[c][i] = mp.q[c];
        for (int c = 0; c < 10; ++c) list.s[c][i] = mp.s[c];
    }
}

// A coordinate difference as the walks use it: the minimum image (kPeriodic), else as it is.
template <bool kPeriodic>
EXASPH_HD EXASPH_INLINE double gravity_difference(double d, double len, double half) {
    if constexpr (kPeriodic)
        return min_image(d, len, half);
    else
        return d;
}

// The list's multipoles' field (G = 1) at x; kPeriodic: plus their Ewald correction, to their
// quadrupole. Everything the loop reads besides its columns is copied into locals first: a value
// reached through a reference is reloaded every iteration and keeps the loop scalar.
template <bool kPeriodic>
GravityField multipoles_field(const GravityInteractionList& list, double x, double y, double z,
                              const GravityImage& img, const EwaldTable::View& ewald) {
    const double lx = img.len[0], ly = img.len[1], lz = img.len[2];
    const double hx = img.half[0], hy = img.half[1], hz = img.half[2];
    const EwaldTable::View ew = ewald;
    double ax = 0, ay = 0, az = 0, phi = 0; // summed here (through a lambda they stay scalar)
    const std::size_t n = list.mass.size();
    const double *m = list.mass.data(), *cx = list.cx.data(), *cy = list.cy.data(),
                 *cz = list.cz.data(), *d2 = list.d2.data();
    const double* q[6]; // column pointers set once, indexed directly by the accessors
    const double* s[10];
    for (int c = 0; c < 6; ++c) q[c] = list.q[c].data();
    for (int c = 0; c < 10; ++c) s[c] = list.s[c].data();
#pragma omp simd reduction(+ : ax, ay, az, phi)
    for (std::size_t k = 0; k < n; ++k) {
        const double dx = gravity_difference<kPeriodic>(x - cx[k], lx, hx),
                     dy = gravity_difference<kPeriodic>(y - cy[k], ly, hy),
                     dz = gravity_difference<kPeriodic>(z - cz[k], lz, hz);
        GravityField g = multipole_field(
            m[k], [&](int c) { return q[c][k]; }, [&](int c) { return s[c][k]; }, dx, dy, dz);
        if constexpr (kPeriodic)
            add_field(g, ew.at(
                             dx, dy, dz, m[k], [&](int c) { return q[c][k]; }, d2[k]));
        ax += g.ax;
        ay += g.ay;
        az += g.az;
        phi += g.phi;
    }
    return {ax, ay, az, phi};
}

// The field (G = 1) of the sources [b, e) at x (smoothing length h; source `self` skipped: a
// factor, not a branch, so the loads stay unconditional). Open boxes read the sources through
// the view, which keeps the loop scalar (a vectorised one, all gathers, measured slower); the
// periodic loop, with its Ewald lookups, gains from vectorising and hoists the pointers.
template <bool kPeriodic, class T>
GravityField pairs_field(const GravityTreeView<T>& tv, const SofteningView<T>& soft,
                         std::uint32_t b, std::uint32_t e, double x, double y, double z, double h,
                         std::uint32_t self, const GravityImage& img,
                         const EwaldTable::View& ewald) {
    double ax = 0, ay = 0, az = 0, phi = 0;
    if constexpr (kPeriodic) {
        const double lx = img.len[0], ly = img.len[1], lz = img.len[2];
        const double hx = img.half[0], hy = img.half[1], hz = img.half[2];
        const EwaldTable::View ew = ewald;
        const T *px = tv.x, *py = tv.y, *pz = tv.z, *pm = tv.m, *ph = tv.h;
        const SofteningView<T> sv = soft;
#pragma omp simd reduction(+ : ax, ay, az, phi)
        for (std::uint32_t j = b; j < e; ++j) {
            const double mj = (j == self ? 0.0 : 1.0) * double(pm[j]);
            const double dx = min_image(x - px[j], lx, hx), dy = min_image(y - py[j], ly, hy),
                         dz = min_image(z - pz[j], lz, hz);
            GravityField g = pair_field(dx, dy, dz, mj, 0.5 * (h + double(ph[j])), sv);
            add_field(g, ew.at(dx, dy, dz, mj));
            ax += g.ax;
            ay += g.ay;
            az += g.az;
            phi += g.phi;
        }
    } else {
        (void)img, (void)ewald;
#pragma omp simd reduction(+ : ax, ay, az, phi)
        for (std::uint32_t j = b; j < e; ++j) {
            const double mj = (j == self ? 0.0 : 1.0) * double(tv.m[j]);
            const GravityField g = pair_field(x - tv.x[j], y - tv.y[j], z - tv.z[j], mj,
                                              0.5 * (h + double(tv.h[j])), soft);
            ax += g.ax;
            ay += g.ay;
            az += g.az;
            phi += g.phi;
        }
    }
    return {ax, ay, az, phi};
}

// Field (G = 1) at a particle of the group (position x, smoothing length h, source index `self`
// skipped) from the group's interaction list. kPeriodic: displacements by the minimum image
// `img` plus the Ewald correction of the other images (`ewald`, physics.md §8); open boxes:
// differences as they are, `img` and `ewald` unused. Kept out of the caller's loop (inlined
// there, its loops lose their vectorisation).
template <bool kPeriodic, class T>
EXASPH_NOINLINE GravityField evaluate_interactions(const GravityInteractionList& list,
                                                   const GravityTreeView<T>& tv,
                                                   const SofteningView<T>& soft, double x, double y,
                                                   double z, double h, std::uint32_t self,
                                                   const GravityImage& img,
                                                   const EwaldTable::View& ewald) {
    GravityField f = multipoles_field<kPeriodic>(list, x, y, z, img, ewald);
    for (std::size_t r = 0; r < list.ranges.size(); r += 2)
        add_field(f, pairs_field<kPeriodic>(tv, soft, list.ranges[r], list.ranges[r + 1], x, y, z,
                                            h, self, img, ewald));
    return f;
}

} // namespace exasph
