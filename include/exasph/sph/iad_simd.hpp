#pragma once
// iad_sums' pair loop written with intrinsics (double positions, the float kernel polynomial, a
// contiguous list; sph/simd_isa.hpp's lanes), as the density pass's (sph/density_simd.hpp): the
// portable loop's arithmetic lane for lane, a step of 8 (AVX2) or 16 (AVX-512) pairs, the
// remainder as one masked step, the minimum image only for groups that may need it.
#include "exasph/sph/simd_isa.hpp"

#ifdef EXASPH_SIMD_LANES
#include <cstdint>
#include <type_traits>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_matrix.hpp"
#include "exasph/tree/neighbour_span.hpp"

namespace exasph::simd {

// V_b = X_b / k_b (not --torque-free's X_b / k_a); kGrad: D_a as well. K: the type of k (float
// rho for standard SPH, or the double k of volume elements).
template <class V, bool kGrad, class K>
class IadPairs {
    using D = typename V::D;
    using F = typename V::F;
    using FM = typename V::FM;

  public:
    IadPairs(std::uint32_t a, const ParticleView<double, float>& p, const Box<double>& box,
             const KernelView<double>& k, const K* kx)
        : x_{p[Field::x], p[Field::y], p[Field::z]}, v_{p[Field::vx], p[Field::vy], p[Field::vz]},
          xm_(p[Field::xm] ? p[Field::xm] : p[Field::m]), kx_(kx), w_(k.w_sq_f),
          image_(PeriodicImage<double>(box)), a_(a) {
        for (int d = 0; d < 3; ++d) {
            xa_[d] = V::splat(x_[d][a]);
            va_[d] = V::splat(v_[d][a]);
        }
        const double inv_h = 1.0 / p[Field::h][a];
        inv_h2_ = V::splat(inv_h * inv_h);
    }

    IadSums<double> sum(ContiguousSpan nb) const {
        return nb.wraps ? sum<true>(nb) : sum<false>(nb);
    }

  private:
    const double *x_[3], *v_[3], *xm_;
    const K* kx_;
    PolyLanes<V> w_;
    Image<V> image_;
    std::uint32_t a_;
    D xa_[3], va_[3], inv_h2_;

    // The sums over a half's lanes (tau's six moments, D's nine), locals of sum().
    struct Lanes {
        D t[6], d[kGrad ? 9 : 1];
        Lanes() {
            for (auto& v : t) v = V::splat(0.0);
            for (auto& v : d) v = V::splat(0.0);
        }
    };

    template <bool kWrap>
    IadSums<double> sum(ContiguousSpan nb) const {
        Lanes acc;
        for_each_step<V>(nb.index, nb.count, a_,
                         [&](const std::uint32_t* i, FM valid)
                             EXASPH_INLINE_LAMBDA { add<kWrap>(i, valid, acc); });
        IadSums<double> s{};
        for (int c = 0; c < 6; ++c) s.t[c] = horizontal_sum(acc.t[c]);
        if constexpr (kGrad)
            for (int c = 0; c < 9; ++c) s.d[c] = horizontal_sum(acc.d[c]);
        return s;
    }

    // One step; `valid` masks the lanes that hold a pair.
    template <bool kWrap>
    EXASPH_INLINE void add(const std::uint32_t* i, FM valid, Lanes& acc) const {
        D d[2][3];
        typename V::H s[2];
        // Unrolled: GCC kept both loops over the halves as loops, the halves' differences and
        // kernel values in memory (IAD with the velocity gradient 10 % slower).
#pragma GCC unroll 2
        for (int h = 0; h < 2; ++h) {
            for (int c = 0; c < 3; ++c) {
                d[h][c] = V::gather(x_[c], i + h * V::kHalf) - xa_[c];
                if constexpr (kWrap) d[h][c] = image_(d[h][c], c);
            }
            const D r2 = fma(d[h][2], d[h][2], fma(d[h][1], d[h][1], d[h][0] * d[h][0]));
            s[h] = V::to_float(r2 * inv_h2_); // v^2, rounded as w_at does
        }
        const F v2 = V::join(s[0], s[1]);
        const F w = select((v2 < V::splat_f(4.0f)) & valid, w_(PolyPowers<V>(v2))); // finite
#pragma GCC unroll 2
        for (int h = 0; h < 2; ++h) {
            const std::uint32_t* ih = i + h * V::kHalf;
            const D vw = (V::gather(xm_, ih) / V::gather(kx_, ih)) * V::half(w, h);
            add_moments(d[h], vw, acc);
            if constexpr (kGrad) add_gradient(ih, d[h], vw, acc);
        }
    }

    // add_second_moment on a half's lanes.
    EXASPH_INLINE static void add_moments(const D (&d)[3], D vw, Lanes& acc) {
        const int row[6] = {0, 0, 0, 1, 1, 2}, col[6] = {0, 1, 2, 1, 2, 2};
        for (int c = 0; c < 6; ++c) acc.t[c] = fma(d[row[c]] * d[col[c]], vw, acc.t[c]);
    }

    // D's nine sums (v_b - v_a) vw (x) d on a half's lanes.
    EXASPH_INLINE void add_gradient(const std::uint32_t* i, const D (&d)[3], D vw,
                                    Lanes& acc) const {
        for (int r = 0; r < 3; ++r) {
            const D wr = (V::gather(v_[r], i) - va_[r]) * vw;
            for (int c = 0; c < 3; ++c) acc.d[3 * r + c] = fma(wr, d[c], acc.d[3 * r + c]);
        }
    }
};

} // namespace exasph::simd
#endif
