#pragma once
#include <cstdint>

#include "exasph/sfc/curve_kind.hpp"
#include "exasph/sfc/hilbert.hpp"
#include "exasph/sfc/morton.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// Integer cell coordinate of x along one axis of the box, clamped to [0, 2^21 - 1].
// Selects instead of branching, so that loops over particles vectorise (NaN gives 0).
template <class T>
EXASPH_HD EXASPH_INLINE std::uint32_t key_coordinate(T x, const Box<T>& box, int axis) {
    T s = (x - box.lo[axis]) / (box.hi[axis] - box.lo[axis]) * T(kKeyAxisMax + 1);
    s = s > T(0) ? s : T(0);
    s = s < T(kKeyAxisMax) ? s : T(kKeyAxisMax);
    return static_cast<std::uint32_t>(s);
}

template <class T>
EXASPH_HD std::uint64_t sfc_key(T x, T y, T z, const Box<T>& box, CurveKind kind) {
    std::uint32_t ix = key_coordinate(x, box, 0);
    std::uint32_t iy = key_coordinate(y, box, 1);
    std::uint32_t iz = key_coordinate(z, box, 2);
    return kind == CurveKind::hilbert ? hilbert_encode(ix, iy, iz) : morton_encode(ix, iy, iz);
}

} // namespace exasph
