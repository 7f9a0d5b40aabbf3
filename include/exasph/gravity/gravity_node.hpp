#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "exasph/gravity/multipole.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/box.hpp"

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

// Whether a particle at x with smoothing length h must open the node: inside the opening radius,
// or within reach of the softened interaction (r < 2 h_ab, h_ab = (h_a + h_b)/2 <= (h + hmax)/2).
template <class T>
EXASPH_HD bool must_open(const GravityNode<T>& nd, double x, double y, double z, double h) {
    const double dx = x - nd.mp.com[0], dy = y - nd.mp.com[1], dz = z - nd.mp.com[2];
    if (dx * dx + dy * dy + dz * dz <= nd.open2) return true;
    const double reach = h + double(nd.hmax);
    return point_box_distance2(x, y, z, nd.lo, nd.hi) < reach * reach;
}

// The minimum image the gravity walks use, in double precision: len 0 and half infinite on an
// open axis (no wrap there).
using GravityImage = PeriodicImage<double>;

template <class T>
GravityImage gravity_image(const Box<T>& box) {
    Box<double> b;
    for (int d = 0; d < 3; ++d)
        b.lo[d] = double(box.lo[d]), b.hi[d] = double(box.hi[d]), b.periodic[d] = box.periodic[d];
    return GravityImage(b);
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

// Whether some particle inside the box [lo, hi] with smoothing lengths up to hmax may open the
// node: the conservative (box) form of must_open, with a margin for round-off.
// kPeriodic: distances by the minimum image `img`. A multipole then stands for its particles at
// the image of its centre of mass, even those beyond the half period (Newton's law plus the Ewald
// correction is the same periodic field at every image); the correction's expansion about the com
// is valid while the node is far from the com's next image too, so the node is also opened when
// that image, L - |d_com| away along an axis, lies inside twice the opening radius: the
// correction is expanded to the quadrupole only, one order below the multipoles, and the factor 2
// brings its error to theirs (measured in test_ewald: rms 4.4e-4 with factor 1, 1.3e-4 with 2,
// at 1.3x the cost of a pass).
inline constexpr double kReplicaFactor2 = 4.0; // the factor 2, squared
template <bool kPeriodic, class T>
bool box_may_open(const GravityNode<T>& nd, const T* lo, const T* hi, T hmax,
                  const GravityImage& img) {
    constexpr double kMargin = 1.0 + 1e-6;
    const double reach = (double(hmax) + double(nd.hmax)) * kMargin;
    if constexpr (!kPeriodic) {
        (void)img;
        const double c2 = point_box_distance2(nd.mp.com[0], nd.mp.com[1], nd.mp.com[2], lo, hi);
        if (c2 <= nd.open2 * kMargin) return true;
        return box_box_distance2(nd.lo, nd.hi, lo, hi) < reach * reach;
    } else {
        double c2 = 0, b2 = 0, replica = std::numeric_limits<double>::infinity();
        for (int d = 0; d < 3; ++d) {
            const double gc = 0.5 * (double(lo[d]) + double(hi[d]));
            const double gh = 0.5 * (double(hi[d]) - double(lo[d])) * kMargin;
            const double dcom = std::fabs(img(nd.mp.com[d] - gc, d));
            const double ec = std::max(dcom - gh, 0.0);
            c2 += ec * ec;
            replica = std::min(replica, 2 * img.half[d] - dcom - gh);
            const double nc = 0.5 * (double(nd.lo[d]) + double(nd.hi[d]));
            const double nh = 0.5 * (double(nd.hi[d]) - double(nd.lo[d])) * kMargin;
            const double eb = std::max(std::fabs(img(nc - gc, d)) - gh - nh, 0.0);
            b2 += eb * eb;
        }
        if (replica <= 0 || replica * replica <= kReplicaFactor2 * nd.open2 * kMargin) return true;
        return c2 <= nd.open2 * kMargin || b2 < reach * reach;
    }
}

} // namespace exasph
