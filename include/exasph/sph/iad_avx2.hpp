#pragma once
// iad_sums' pair loop written for AVX2 (double positions, the float kernel polynomial, a
// contiguous list), as the density pass's (sph/density_avx2.hpp): the portable loop's
// arithmetic lane for lane, eight pairs per step, the remainder as one masked step, the minimum
// image only for groups that may need it.
#include "exasph/sph/avx2_lanes.hpp"

#ifdef EXASPH_AVX2_PAIRS
#include <cstdint>
#include <type_traits>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_matrix.hpp"
#include "exasph/tree/neighbour_span.hpp"

namespace exasph::avx2 {

// Four values of k (float rho for standard SPH, or the double k of volume elements) as doubles.
EXASPH_INLINE __m256d gather4_wide(const double* f, const std::uint32_t* i) {
    return gather4(f, i);
}
EXASPH_INLINE __m256d gather4_wide(const float* f, const std::uint32_t* i) {
    return _mm256_cvtps_pd(_mm_setr_ps(f[i[0]], f[i[1]], f[i[2]], f[i[3]]));
}

// V_b = X_b / k_b (not --torque-free's X_b / k_a); kGrad: D_a as well.
template <bool kGrad, class K>
class IadPairs {
  public:
    IadPairs(std::uint32_t a, const ParticleView<double, float>& p, const Box<double>& box,
             const KernelView<double>& k, const K* kx)
        : x_{p[Field::x], p[Field::y], p[Field::z]}, v_{p[Field::vx], p[Field::vy], p[Field::vz]},
          xm_(p[Field::xm] ? p[Field::xm] : p[Field::m]), kx_(kx), w_(k.w_sq_f),
          image_(PeriodicImage<double>(box)), a_(a) {
        for (int d = 0; d < 3; ++d) {
            xa_[d] = _mm256_set1_pd(x_[d][a]);
            va_[d] = _mm256_set1_pd(v_[d][a]);
        }
        const double inv_h = 1.0 / p[Field::h][a];
        inv_h2_ = _mm256_set1_pd(inv_h * inv_h);
    }

    IadSums<double> sum(ContiguousSpan nb) const {
        return nb.wraps ? sum<true>(nb) : sum<false>(nb);
    }

  private:
    const double *x_[3], *v_[3], *xm_;
    const K* kx_;
    PolyLanes w_;
    Image4 image_;
    std::uint32_t a_;
    __m256d xa_[3], va_[3], inv_h2_;

    // The sums over lanes 0-7 (tau's six moments, D's nine), locals of sum().
    struct Lanes {
        __m256d t[6], d[kGrad ? 9 : 1];
        Lanes() {
            for (auto& v : t) v = _mm256_setzero_pd();
            for (auto& v : d) v = _mm256_setzero_pd();
        }
    };

    template <bool kWrap>
    IadSums<double> sum(ContiguousSpan nb) const {
        Lanes acc;
        for_each_eight(nb.index, nb.count, a_,
                       [&](const std::uint32_t* i, __m256i valid)
                           EXASPH_INLINE_LAMBDA { add8<kWrap>(i, valid, acc); });
        IadSums<double> s{};
        for (int c = 0; c < 6; ++c) s.t[c] = horizontal_sum(acc.t[c]);
        if constexpr (kGrad)
            for (int c = 0; c < 9; ++c) s.d[c] = horizontal_sum(acc.d[c]);
        return s;
    }

    template <bool kWrap>
    EXASPH_INLINE __m256d difference(const std::uint32_t* i, int axis) const {
        const __m256d d = _mm256_sub_pd(gather4(x_[axis], i), xa_[axis]);
        return kWrap ? image_(d, axis) : d;
    }

    // Eight pairs; `valid` masks the lanes that hold one.
    template <bool kWrap>
    EXASPH_INLINE void add8(const std::uint32_t* i, __m256i valid_lanes, Lanes& acc) const {
        const __m256 valid = _mm256_castsi256_ps(valid_lanes);
        __m256d d[2][3];
        __m128 s[2];
        // Unrolled: GCC kept both loops over the halves as loops, the halves' differences and
        // kernel values in memory (IAD with the velocity gradient 10 % slower).
#pragma GCC unroll 2
        for (int h = 0; h < 2; ++h) {
            for (int c = 0; c < 3; ++c) d[h][c] = difference<kWrap>(i + 4 * h, c);
            const __m256d r2 =
                _mm256_fmadd_pd(d[h][2], d[h][2],
                                _mm256_fmadd_pd(d[h][1], d[h][1], _mm256_mul_pd(d[h][0], d[h][0])));
            s[h] = _mm256_cvtpd_ps(_mm256_mul_pd(r2, inv_h2_)); // v^2, rounded as w_at does
        }
        const __m256 v2 = join(s[0], s[1]);
        const __m256 inside =
            _mm256_and_ps(_mm256_cmp_ps(v2, _mm256_set1_ps(4.0f), _CMP_LT_OQ), valid);
        const __m256 w = _mm256_and_ps(w_(PolyPowers(v2)), inside); // finite: the mask zeroes it
#pragma GCC unroll 2
        for (int h = 0; h < 2; ++h) {
            const std::uint32_t* ih = i + 4 * h;
            const __m256d vol = _mm256_div_pd(gather4(xm_, ih), gather4_wide(kx_, ih));
            const __m256d vw = _mm256_mul_pd(vol, h == 0 ? low_pd(w) : high_pd(w));
            add_moments(d[h], vw, acc);
            if constexpr (kGrad) add_gradient(ih, d[h], vw, acc);
        }
    }

    // add_second_moment on four lanes.
    EXASPH_INLINE static void add_moments(const __m256d (&d)[3], __m256d vw, Lanes& acc) {
        const int row[6] = {0, 0, 0, 1, 1, 2}, col[6] = {0, 1, 2, 1, 2, 2};
        for (int c = 0; c < 6; ++c)
            acc.t[c] = _mm256_fmadd_pd(_mm256_mul_pd(d[row[c]], d[col[c]]), vw, acc.t[c]);
    }

    // D's nine sums (v_b - v_a) vw (x) d on four lanes.
    EXASPH_INLINE void add_gradient(const std::uint32_t* i, const __m256d (&d)[3], __m256d vw,
                                    Lanes& acc) const {
        for (int r = 0; r < 3; ++r) {
            const __m256d wr = _mm256_mul_pd(_mm256_sub_pd(gather4(v_[r], i), va_[r]), vw);
            for (int c = 0; c < 3; ++c)
                acc.d[3 * r + c] = _mm256_fmadd_pd(wr, d[c], acc.d[3 * r + c]);
        }
    }
};

} // namespace exasph::avx2
#endif
