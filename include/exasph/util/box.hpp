#pragma once
#include <array>
#include <limits>

#include "exasph/util/annotate.hpp"

namespace exasph {

// The minimum image of a coordinate difference d along an axis of period len (half = len / 2;
// an open axis: len = 0, half = infinity, and d is returned as it is). Valid for |d| < len, which
// holds for two positions inside the box. The one scalar form: Box::min_image, PeriodicImage
// and the loops that hoist len and half call it; the lanes' form is simd::Image
// (util/simd_sets.hpp), with the same comparisons and single rounding.
template <class T>
EXASPH_HD EXASPH_INLINE T min_image(T d, T len, T half) {
    d = d > half ? d - len : d;
    return d < -half ? d + len : d; // after a shift down d > -half: one shift at most
}

// Axis-aligned simulation box. On a periodic axis [lo, hi) is the period; on an open axis it is
// just the current bounds of the particles (used to scale SFC keys).
// Invariant: on periodic axes all owned particles lie in [lo, hi).
template <class T>
struct Box {
    std::array<T, 3> lo{0, 0, 0};
    std::array<T, 3> hi{1, 1, 1};
    std::array<bool, 3> periodic{false, false, false};

    EXASPH_HD T length(int axis) const { return hi[axis] - lo[axis]; }
    EXASPH_HD bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }

    // Minimum image of one coordinate difference (exasph::min_image).
    EXASPH_HD T min_image(T d, int axis) const {
        if (!periodic[axis]) return d;
        const T len = hi[axis] - lo[axis];
        return exasph::min_image(d, len, T(0.5) * len);
    }

    // Squared minimum-image distance between the boxes [alo, ahi] and [blo, bhi] (a point when
    // lo == hi). Half-widths are multiplied by `inflate`: slightly above 1 makes the result a
    // lower bound despite round-off (tree pruning). Symmetric in a and b.
    EXASPH_HD T box_distance2(const T alo[3], const T ahi[3], const T blo[3], const T bhi[3],
                              T inflate = T(1)) const {
        T d2 = 0;
        for (int d = 0; d < 3; ++d) {
            T dc = min_image(T(0.5) * (alo[d] + ahi[d]) - T(0.5) * (blo[d] + bhi[d]), d);
            T gap =
                (dc < T(0) ? -dc : dc) - T(0.5) * ((ahi[d] - alo[d]) + (bhi[d] - blo[d])) * inflate;
            if (gap > T(0)) d2 += gap * gap;
        }
        return d2;
    }

    // Wraps a coordinate into [lo, hi) on a periodic axis; returns the shift applied.
    EXASPH_HD T wrap_shift(T x, int axis) const {
        if (!periodic[axis]) return T(0);
        T len = hi[axis] - lo[axis];
        if (x >= hi[axis]) return -len;
        if (x < lo[axis]) return len;
        return T(0);
    }
};

// The minimum image of Box::min_image with loop-invariant operands, for neighbour loops that
// must vectorise; an open axis gets an infinite half-period (never wraps).
template <class T>
struct PeriodicImage {
    T len[3], half[3];
    EXASPH_HD explicit PeriodicImage(const Box<T>& box) {
        for (int d = 0; d < 3; ++d) {
            len[d] = box.periodic[d] ? box.hi[d] - box.lo[d] : T(0);
            half[d] = box.periodic[d] ? T(0.5) * len[d] : std::numeric_limits<T>::infinity();
        }
    }
    EXASPH_HD T operator()(T d, int axis) const { return min_image(d, len[axis], half[axis]); }
};

} // namespace exasph
