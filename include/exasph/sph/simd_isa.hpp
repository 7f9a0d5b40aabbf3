#pragma once
// What the intrinsic pair loops build on the lane sets (util/simd_sets.hpp): KernelPoly on a
// step's floats and the branch-free exponential.
#include "exasph/util/simd_sets.hpp"

#ifdef EXASPH_SIMD_LANES
#include "exasph/kernel/kernel_poly.hpp"
#include "exasph/util/branch_free_exp.hpp"

namespace exasph::simd {

// The powers of t = min(s, 4)/2 - 1 that KernelPoly's Estrin scheme uses, shared by the
// polynomials evaluated at one s.
template <class V>
struct PolyPowers {
    using F = typename V::F;
    F t, t2, t4, t8;
    EXASPH_INLINE explicit PolyPowers(F s) {
        // min returns 4 for a NaN s, as the scalar does
        t = fma(min(s, V::splat_f(4.0f)), V::splat_f(0.5f), V::splat_f(-1.0f));
        t2 = t * t, t4 = t2 * t2, t8 = t4 * t4;
    }
};

// KernelPoly<float>'s coefficients, each broadcast once per particle (a broadcast per
// coefficient and step was a fifth of the density loop's instructions), evaluated before its
// factor (s < 4) in the scalar's order of fused multiply-adds, so every lane rounds as it does.
template <class V>
struct PolyLanes {
    using F = typename V::F;
    static constexpr int kTerms = KernelPoly<float>::kTerms;
    F c[kTerms];
    explicit PolyLanes(const KernelPoly<float>& k) {
        for (int i = 0; i < kTerms; ++i) c[i] = V::splat_f(k.c[i]);
    }
    EXASPH_INLINE F operator()(const PolyPowers<V>& w) const {
        static_assert(kTerms == 16, "written out for 16 terms, as KernelPoly<float>");
        auto pair = [&](int i) { return fma(c[i + 1], w.t, c[i]); };
        const F q0 = fma(pair(2), w.t2, pair(0)), q1 = fma(pair(6), w.t2, pair(4));
        const F q2 = fma(pair(10), w.t2, pair(8)), q3 = fma(pair(14), w.t2, pair(12));
        return fma(fma(q3, w.t4, q2), w.t8, fma(q1, w.t4, q0));
    }
};

// exp_nonpositive (util/branch_free_exp.hpp) on one half's lanes, step for step.
template <class V>
EXASPH_INLINE typename V::D exp_nonpositive(typename V::D x) {
    using D = typename V::D;
    const D floor = V::splat(-700.0);
    x = blend(x < floor, x, floor); // a NaN stays a NaN
    const D k = round_nearest(x * V::splat(kLog2e));
    const D r = (x - k * V::splat(kLn2Hi)) - k * V::splat(kLn2Lo);
    D series = V::splat(kExpSeries[0]);
    for (int j = 1; j < kExpSeriesTerms; ++j) series = fma(series, r, V::splat(kExpSeries[j]));
    return series * shift_to_exponent((k + V::splat(1023.0)) + V::splat(0x1p52));
}

} // namespace exasph::simd
#endif
