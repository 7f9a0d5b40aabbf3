#pragma once
// density_kern's pair loop written for AVX2 (double positions, float kernel polynomials, a
// contiguous list): the same arithmetic as the portable loop, lane for lane, eight pairs per
// step. GCC's vectorisation of that loop (simdlen 8 of doubles) kept two ymm registers per value
// and spilled a quarter of its instructions, and left up to seven pairs per particle to a
// scalar remainder; here the remainder is one masked step (docs/performance.md).
#include "exasph/sph/avx2_lanes.hpp"

#ifdef EXASPH_AVX2_PAIRS
#include <cstdint>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/tree/neighbour_span.hpp"

namespace exasph::avx2 {

// k_a and the grad-h sum of density_kern over a's neighbours, without a's own term.
struct DensitySums {
    double k = 0, dh = 0;
    std::uint32_t nc = 0;
};

class DensityPairs {
  public:
    DensityPairs(std::uint32_t a, const ParticleView<double, float>& p, const Box<double>& box,
                 const KernelView<double>& k)
        : x_(p[Field::x]), y_(p[Field::y]), z_(p[Field::z]),
          xm_(p[Field::xm] ? p[Field::xm] : p[Field::m]), w_(k.w_sq_f), gradh_(k.gradh_sq_f),
          image_(PeriodicImage<double>(box)), a_(a) {
        xa_[0] = _mm256_set1_pd(x_[a]), xa_[1] = _mm256_set1_pd(y_[a]);
        xa_[2] = _mm256_set1_pd(z_[a]);
        const double h = p[Field::h][a];
        inv_h2_ = _mm256_set1_pd(1.0 / (h * h));
    }

    DensitySums sum(ContiguousSpan nb) const { return nb.wraps ? sum<true>(nb) : sum<false>(nb); }

  private:
    const double *x_, *y_, *z_, *xm_;
    PolyLanes w_, gradh_;
    Image4 image_;
    std::uint32_t a_;
    __m256d xa_[3], inv_h2_;

    // The sums of lanes 0-3 and 4-7 (locals of sum(), so that they stay in registers).
    struct Lanes {
        __m256d k[2] = {_mm256_setzero_pd(), _mm256_setzero_pd()};
        __m256d dh[2] = {_mm256_setzero_pd(), _mm256_setzero_pd()};
        __m256i nc = _mm256_setzero_si256(); // minus the count (a true mask is -1)
    };

    // kWrap: with the minimum image (the span's `wraps`; without it, the image would change
    // no distance).
    template <bool kWrap>
    DensitySums sum(ContiguousSpan nb) const {
        Lanes acc;
        for_each_eight(nb.index, nb.count, a_,
                       [&](const std::uint32_t* i, __m256i valid)
                           EXASPH_INLINE_LAMBDA { add8<kWrap>(i, valid, acc); });
        DensitySums s;
        s.k = horizontal_sum(_mm256_add_pd(acc.k[0], acc.k[1]));
        s.dh = horizontal_sum(_mm256_add_pd(acc.dh[0], acc.dh[1]));
        s.nc = std::uint32_t(-horizontal_sum(acc.nc));
        return s;
    }

    // v^2 = |x_b - x_a|^2 / h_a^2 of four pairs, rounded to float as density_kern does.
    template <bool kWrap>
    EXASPH_INLINE __m256d difference(const double* x, const std::uint32_t* i, int axis) const {
        const __m256d d = _mm256_sub_pd(gather4(x, i), xa_[axis]);
        return kWrap ? image_(d, axis) : d;
    }
    template <bool kWrap>
    EXASPH_INLINE __m128 v2(const std::uint32_t* i) const {
        const __m256d dx = difference<kWrap>(x_, i, 0);
        const __m256d dy = difference<kWrap>(y_, i, 1);
        const __m256d dz = difference<kWrap>(z_, i, 2);
        const __m256d r2 = _mm256_fmadd_pd(dz, dz, _mm256_fmadd_pd(dy, dy, _mm256_mul_pd(dx, dx)));
        return _mm256_cvtpd_ps(_mm256_mul_pd(r2, inv_h2_));
    }

    // Eight pairs; `valid` masks the lanes that hold one.
    template <bool kWrap>
    EXASPH_INLINE void add8(const std::uint32_t* i, __m256i valid_lanes, Lanes& acc) const {
        const __m256 valid = _mm256_castsi256_ps(valid_lanes);
        const __m256 s = join(v2<kWrap>(i), v2<kWrap>(i + 4));
        const __m256 inside =
            _mm256_and_ps(_mm256_cmp_ps(s, _mm256_set1_ps(4.0f), _CMP_LT_OQ), valid);
        acc.nc = _mm256_add_epi32(acc.nc, _mm256_castps_si256(inside));
        const PolyPowers pw(s);
        // w and the grad-h term are finite for every s (t is clamped): the mask zeroes them.
        const __m256 w = _mm256_and_ps(w_(pw), inside);
        const __m256 g = _mm256_and_ps(gradh_(pw), inside);
        const __m256d xb0 = gather4(xm_, i), xb1 = gather4(xm_, i + 4);
        acc.k[0] = _mm256_fmadd_pd(xb0, low_pd(w), acc.k[0]);
        acc.k[1] = _mm256_fmadd_pd(xb1, high_pd(w), acc.k[1]);
        acc.dh[0] = _mm256_fmadd_pd(xb0, low_pd(g), acc.dh[0]);
        acc.dh[1] = _mm256_fmadd_pd(xb1, high_pd(g), acc.dh[1]);
    }
};

} // namespace exasph::avx2
#endif
