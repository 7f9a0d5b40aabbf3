#pragma once
// density_kern's pair loop written with intrinsics (double positions, float kernel polynomials,
// a contiguous list; sph/simd_isa.hpp's lanes): the same arithmetic as the portable loop, lane
// for lane, a step of 8 (AVX2) or 16 (AVX-512) pairs. GCC's vectorisation of that loop (simdlen
// 8 of doubles) kept two ymm registers per value and spilled a quarter of its instructions, and
// left up to seven pairs per particle to a scalar remainder; here the remainder is one masked
// step (docs/performance-log.md).
#include "exasph/sph/simd_isa.hpp"

#ifdef EXASPH_SIMD_LANES
#include <cstdint>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/tree/neighbour_span.hpp"

namespace exasph::simd {

// k_a and the grad-h sum of density_kern over a's neighbours, without a's own term.
struct DensitySums {
    double k = 0, dh = 0;
    std::uint32_t nc = 0;
};

template <class V>
class DensityPairs {
    using D = typename V::D;
    using F = typename V::F;
    using FM = typename V::FM;

  public:
    DensityPairs(std::uint32_t a, const ParticleView<double, float>& p, const Box<double>& box,
                 const KernelView<double>& k)
        : x_{p[Field::x], p[Field::y], p[Field::z]}, xm_(p[Field::xm] ? p[Field::xm] : p[Field::m]),
          w_(k.w_sq_f), gradh_(k.gradh_sq_f), image_(PeriodicImage<double>(box)), a_(a) {
        for (int d = 0; d < 3; ++d) xa_[d] = V::splat(x_[d][a]);
        const double h = p[Field::h][a];
        inv_h2_ = V::splat(1.0 / (h * h));
    }

    DensitySums sum(ContiguousSpan nb) const { return nb.wraps ? sum<true>(nb) : sum<false>(nb); }

  private:
    const double *x_[3], *xm_;
    PolyLanes<V> w_, gradh_;
    Image<V> image_;
    std::uint32_t a_;
    D xa_[3], inv_h2_;

    // The sums of the two halves (locals of sum(), so that they stay in registers).
    struct Lanes {
        D k[2] = {V::splat(0.0), V::splat(0.0)};
        D dh[2] = {V::splat(0.0), V::splat(0.0)};
        std::uint32_t nc = 0;
    };

    // kWrap: with the minimum image (the span's `wraps`; without it, the image would change
    // no distance).
    template <bool kWrap>
    DensitySums sum(ContiguousSpan nb) const {
        Lanes acc;
        for_each_step<V>(nb.index, nb.count, a_,
                         [&](const std::uint32_t* i, FM valid)
                             EXASPH_INLINE_LAMBDA { add<kWrap>(i, valid, acc); });
        DensitySums s;
        s.k = horizontal_sum(acc.k[0] + acc.k[1]);
        s.dh = horizontal_sum(acc.dh[0] + acc.dh[1]);
        s.nc = acc.nc;
        return s;
    }

    // v^2 = |x_b - x_a|^2 / h_a^2 of one half, rounded to float as density_kern does.
    template <bool kWrap>
    EXASPH_INLINE typename V::H v2(const std::uint32_t* i) const {
        D d[3];
        for (int c = 0; c < 3; ++c) {
            d[c] = V::gather(x_[c], i) - xa_[c];
            if constexpr (kWrap) d[c] = image_(d[c], c);
        }
        return V::to_float(fma(d[2], d[2], fma(d[1], d[1], d[0] * d[0])) * inv_h2_);
    }

    // One step; `valid` masks the lanes that hold a pair.
    template <bool kWrap>
    EXASPH_INLINE void add(const std::uint32_t* i, FM valid, Lanes& acc) const {
        const F s = V::join(v2<kWrap>(i), v2<kWrap>(i + V::kHalf));
        const FM inside = (s < V::splat_f(4.0f)) & valid;
        acc.nc += std::uint32_t(count(inside));
        const PolyPowers<V> pw(s);
        // w and the grad-h term are finite for every s (t is clamped): the mask zeroes them.
        const F w = select(inside, w_(pw)), g = select(inside, gradh_(pw));
        for (int h = 0; h < 2; ++h) {
            const D xb = V::gather(xm_, i + h * V::kHalf);
            acc.k[h] = fma(xb, V::half(w, h), acc.k[h]);
            acc.dh[h] = fma(xb, V::half(g, h), acc.dh[h]);
        }
    }
};

} // namespace exasph::simd
#endif
