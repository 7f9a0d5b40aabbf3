#pragma once
// momentum_energy_kern's pair loop written for AVX2, as the density and IAD loops
// (sph/density_avx2.hpp), for the two forms the schemes run by default with a constant alpha:
// `plain` (standard SPH, no stress, limiter or conductivity: the std scheme) and `limited`
// (volume elements, the slope-limited viscosity and the conductivity: the ve and pe schemes).
// The portable loop's terms in the same order, eight pairs per step (the two kernel polynomials
// on eight floats, the rest on two halves of four doubles), the remainder as one masked step,
// the image only where the group may need it. GCC's version of the plain loop took ~100
// instructions per pair, a third of them spills and the one-by-one loads of its emulated
// gathers; the limited one (simdlen 8) was 46 % of the ve step (docs/performance.md).
#include "exasph/sph/avx2_lanes.hpp"

#ifdef EXASPH_AVX2_PAIRS
#include <cstdint>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/limited_terms_avx2.hpp"
#include "exasph/tree/neighbour_span.hpp"

namespace exasph::avx2 {

EXASPH_INLINE double horizontal_max(__m256d v) {
    const __m128d m = _mm_max_pd(_mm256_castpd256_pd128(v), _mm256_extractf128_pd(v, 1));
    return _mm_cvtsd_f64(_mm_max_sd(m, _mm_unpackhi_pd(m, m)));
}

// The sums of momentum_energy_kern (its MomentumEnergyResult without div v).
struct MomentumEnergySums {
    double ax, ay, az, du, vsig_max;
};

// kLimited: the limited form (PairTerms::limited with volume elements and a constant alpha),
// else the plain one.
template <bool kLimited>
class MomentumEnergyPairs {
  public:
    MomentumEnergyPairs(std::uint32_t a, const ParticleView<double, float>& p,
                        const Box<double>& box, const KernelView<double>& k,
                        const Dissipation<double>& diss)
        : x_{p[Field::x], p[Field::y], p[Field::z]}, v_{p[Field::vx], p[Field::vy], p[Field::vz]},
          h_(p[Field::h]), m_(p[Field::m]), c_(p.narrow(Field::c)), pgrad_(p.narrow(Field::pgrad)),
          rho_(p.narrow(Field::rho)), cm_{p.narrow(Field::c11), p.narrow(Field::c12),
                                          p.narrow(Field::c13), p.narrow(Field::c22),
                                          p.narrow(Field::c23), p.narrow(Field::c33)},
          w_(k.w_sq_f), image_(PeriodicImage<double>(box)), a_(a) {
        for (int d = 0; d < 3; ++d) {
            xa_[d] = _mm256_set1_pd(x_[d][a]);
            va_[d] = _mm256_set1_pd(v_[d][a]);
        }
        for (int e = 0; e < 6; ++e) cma_[e] = _mm256_set1_pd(double(cm_[e][a]));
        const double inv_ha = 1.0 / h_[a], inv_ha2 = inv_ha * inv_ha;
        inv_ha_ = _mm256_set1_pd(inv_ha);
        inv_ha2_ = _mm256_set1_pd(inv_ha2);
        inv_ha3_ = _mm256_set1_pd(inv_ha2 * inv_ha);
        // Volume elements: X_a / m_a on both members' pressure coefficients (1 without them)
        if constexpr (kLimited) lim_ = LimitedTerms(a, p, diss);
        const double xa_ma = kLimited ? lim_.xm[a] / m_[a] : 1.0;
        pa_ = double(pgrad_[a]) * xa_ma;
        xa_ma_ = _mm256_set1_pd(xa_ma);
        ca_ = _mm256_set1_pd(double(c_[a]));
        pav_ = _mm256_set1_pd(pa_);
        inv_rho_a_ = _mm256_set1_pd(1.0 / double(rho_[a]));
        pi_factor_ = _mm256_set1_pd(-0.5 * diss.alpha);
    }

    MomentumEnergySums sum(ContiguousSpan nb) const {
        return nb.wraps ? sum<true>(nb) : sum<false>(nb);
    }

  private:
    const double *x_[3], *v_[3], *h_, *m_;
    const float *c_, *pgrad_, *rho_, *cm_[6];
    PolyLanes w_;
    Image4 image_;
    std::uint32_t a_;
    double pa_;
    __m256d xa_[3], va_[3], cma_[6], inv_ha_, inv_ha2_, inv_ha3_, xa_ma_, ca_, pav_, inv_rho_a_,
        pi_factor_;
    LimitedTerms lim_;

    struct Lanes {
        __m256d ax = _mm256_setzero_pd(), ay = _mm256_setzero_pd(), az = _mm256_setzero_pd();
        __m256d du_p = _mm256_setzero_pd(), du_av = _mm256_setzero_pd();
        __m256d du_cond = _mm256_setzero_pd();
        __m256d vsig_max = _mm256_setzero_pd();
    };

    template <bool kWrap>
    MomentumEnergySums sum(ContiguousSpan nb) const {
        Lanes acc;
        // The body stays a call per eight pairs (its sums in memory): inlined into the loop it
        // spilled more than that saved (plain 0.0837 -> 0.0853, limited 0.1375 -> 0.1417 s per
        // step at Sedov 125k), unlike the density and IAD bodies.
        for_each_eight(nb.index, nb.count, a_,
                       [&](const std::uint32_t* i, __m256i valid) { add8<kWrap>(i, valid, acc); });
        double du = pa_ * horizontal_sum(acc.du_p) + 0.25 * horizontal_sum(acc.du_av);
        if constexpr (kLimited) du += horizontal_sum(acc.du_cond);
        return {horizontal_sum(acc.ax), horizontal_sum(acc.ay), horizontal_sum(acc.az), du,
                horizontal_max(acc.vsig_max)};
    }

    // One half's pair geometry: d = x_b - x_a, |d|^2 and 1/h_b.
    struct Geometry {
        __m256d d[3], r2, inv_hb;
    };

    // Eight pairs; `valid` (32-bit lanes) masks those that hold one. An empty lane is the pair
    // (a, a): d = 0 makes every term 0 but the signal velocity, which the mask removes.
    template <bool kWrap>
    EXASPH_INLINE void add8(const std::uint32_t* i, __m256i valid, Lanes& acc) const {
        Geometry g[2];
        __m128 sa[2], sb[2];
        for (int h = 0; h < 2; ++h) {
            const std::uint32_t* ih = i + 4 * h;
            for (int c = 0; c < 3; ++c) {
                const __m256d d = _mm256_sub_pd(gather4(x_[c], ih), xa_[c]);
                g[h].d[c] = kWrap ? image_(d, c) : d;
            }
            const __m256d* d = g[h].d;
            g[h].r2 =
                _mm256_fmadd_pd(d[2], d[2], _mm256_fmadd_pd(d[1], d[1], _mm256_mul_pd(d[0], d[0])));
            g[h].inv_hb = _mm256_div_pd(_mm256_set1_pd(1.0), gather4(h_, ih));
            // v^2 for h_a and for h_b, rounded to float as KernelView::w_at does
            sa[h] = _mm256_cvtpd_ps(_mm256_mul_pd(g[h].r2, inv_ha2_));
            sb[h] =
                _mm256_cvtpd_ps(_mm256_mul_pd(g[h].r2, _mm256_mul_pd(g[h].inv_hb, g[h].inv_hb)));
        }
        const __m256 four = _mm256_set1_ps(4.0f);
        const __m256 va = join(sa[0], sa[1]), vb = join(sb[0], sb[1]);
        const __m256 kwa = _mm256_and_ps(w_(PolyPowers(va)), _mm256_cmp_ps(va, four, _CMP_LT_OQ));
        const __m256 kwb = _mm256_and_ps(w_(PolyPowers(vb)), _mm256_cmp_ps(vb, four, _CMP_LT_OQ));
        const __m256d ok[2] = {
            _mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm256_castsi256_si128(valid))),
            _mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm256_extracti128_si256(valid, 1)))};
        pair_terms(i, g[0], low_pd(kwa), low_pd(kwb), ok[0], acc);
        pair_terms(i + 4, g[1], high_pd(kwa), high_pd(kwb), ok[1], acc);
    }

    // C (x) d for four lanes: C_a's broadcast (m) or C_b's gathered.
    EXASPH_INLINE static void iad_times(const __m256d (&m)[6], const __m256d (&d)[3],
                                        __m256d (&out)[3]) {
        out[0] =
            _mm256_fmadd_pd(m[2], d[2], _mm256_fmadd_pd(m[1], d[1], _mm256_mul_pd(m[0], d[0])));
        out[1] =
            _mm256_fmadd_pd(m[4], d[2], _mm256_fmadd_pd(m[3], d[1], _mm256_mul_pd(m[1], d[0])));
        out[2] =
            _mm256_fmadd_pd(m[5], d[2], _mm256_fmadd_pd(m[4], d[1], _mm256_mul_pd(m[2], d[0])));
    }

    // SPEC 6's terms of four pairs (momentum_energy_portable's plain or limited form).
    EXASPH_INLINE void pair_terms(const std::uint32_t* i, const Geometry& g, __m256d kwa,
                                  __m256d kwb, __m256d ok, Lanes& acc) const {
        const __m256d r = _mm256_sqrt_pd(g.r2);
        const __m256d inv_r = _mm256_and_pd(_mm256_cmp_pd(r, _mm256_setzero_pd(), _CMP_GT_OQ),
                                            _mm256_div_pd(_mm256_set1_pd(1.0), r));
        const __m256d wa = _mm256_mul_pd(kwa, inv_ha3_);
        const __m256d wb =
            _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(kwb, g.inv_hb), g.inv_hb), g.inv_hb);
        __m256d cmb[6], ca[3], cb[3], aa[3], ab[3], vab[3];
        for (int e = 0; e < 6; ++e) cmb[e] = gather4_float(cm_[e], i);
        iad_times(cma_, g.d, ca);
        iad_times(cmb, g.d, cb);
        for (int c = 0; c < 3; ++c) {
            aa[c] = _mm256_mul_pd(ca[c], wa); // A_ab(h_a)
            ab[c] = _mm256_mul_pd(cb[c], wb); // A_ab(h_b)
            vab[c] = _mm256_sub_pd(va_[c], gather4(v_[c], i));
        }
        const __m256d vr = _mm256_sub_pd(_mm256_setzero_pd(), dot3(vab, g.d)); // v_ab . r_ab
        const __m256d w_ab = _mm256_mul_pd(vr, inv_r);
        const __m256d c_ab = _mm256_add_pd(ca_, gather4_float(c_, i));
        const __m256d vsig = _mm256_sub_pd(c_ab, _mm256_mul_pd(_mm256_set1_pd(3.0), w_ab));
        acc.vsig_max = _mm256_max_pd(_mm256_and_pd(vsig, ok), acc.vsig_max);
        const __m256d approaching = _mm256_cmp_pd(vr, _mm256_setzero_pd(), _CMP_LT_OQ);
        __m256d pi; // Pi_ab
        if constexpr (kLimited)
            pi = lim_.pi(i, g.d, r, inv_r, inv_ha_, g.inv_hb, vr, w_ab, approaching, c_ab,
                         pi_factor_);
        else
            pi = _mm256_and_pd(approaching, _mm256_mul_pd(_mm256_mul_pd(pi_factor_, vsig), w_ab));
        __m256d pb = gather4_float(pgrad_, i);
        if constexpr (kLimited) pb = _mm256_mul_pd(pb, xa_ma_); // X_a / m_a (1 in standard SPH)
        const __m256d rho_b = gather4_float(rho_, i);
        const __m256d inv_rho_b = _mm256_div_pd(_mm256_set1_pd(1.0), rho_b);
        const __m256d mb = gather4(m_, i);
        const __m256d xb = kLimited ? gather4(lim_.xm, i) : mb; // X_b (m_b in standard SPH)
        __m256d gr[3];                                          // A(h_a)/rho_a + A(h_b)/rho_b
        for (int c = 0; c < 3; ++c)
            gr[c] = _mm256_fmadd_pd(ab[c], inv_rho_b, _mm256_mul_pd(aa[c], inv_rho_a_));
        const __m256d half_pi = _mm256_mul_pd(_mm256_set1_pd(0.5), pi);
        __m256d* a[3] = {&acc.ax, &acc.ay, &acc.az};
        for (int c = 0; c < 3; ++c) {
            const __m256d pressure = _mm256_fmadd_pd(pb, ab[c], _mm256_mul_pd(pav_, aa[c]));
            const __m256d viscous = _mm256_mul_pd(_mm256_mul_pd(mb, half_pi), gr[c]);
            *a[c] = _mm256_sub_pd(*a[c], _mm256_fmadd_pd(xb, pressure, viscous));
        }
        acc.du_p = _mm256_fmadd_pd(xb, dot3(vab, aa), acc.du_p);
        acc.du_av = _mm256_fmadd_pd(_mm256_mul_pd(mb, pi), dot3(vab, gr), acc.du_av);
        if constexpr (kLimited)
            if (lim_.conduction_on)
                acc.du_cond =
                    _mm256_sub_pd(acc.du_cond, lim_.conduction(i, g.d, inv_r, aa, ab, mb, rho_b));
    }
};

using MomentumEnergyPlain = MomentumEnergyPairs<false>;
using MomentumEnergyLimited = MomentumEnergyPairs<true>;

} // namespace exasph::avx2
#endif
