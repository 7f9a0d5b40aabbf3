#pragma once
// momentum_energy_kern's pair loop written with intrinsics (sph/simd_isa.hpp's lanes), as the
// density and IAD loops, for the two forms the schemes run by default with a constant alpha:
// `plain` (standard SPH, no stress, limiter or conductivity: the std scheme) and `limited`
// (volume elements, the slope-limited viscosity and the conductivity: the ve and pe schemes).
// The portable loop's terms in the same order, a step of 8 (AVX2) or 16 (AVX-512) pairs (the
// two kernel polynomials on the step's floats, the rest on two halves of doubles), the
// remainder as one masked step, the image only where the group may need it. GCC's version of
// the plain loop took ~100 instructions per pair, a third of them spills and the one-by-one
// loads of its emulated gathers; the limited one (simdlen 8) was 46 % of the ve step
// (docs/performance-log.md).
#include "exasph/sph/simd_isa.hpp"

#ifdef EXASPH_SIMD_LANES
#include <cstdint>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/limited_terms_simd.hpp"
#include "exasph/tree/neighbour_span.hpp"

namespace exasph::simd {

// The sums of momentum_energy_kern (its MomentumEnergyResult without div v).
struct MomentumEnergySums {
    double ax, ay, az, du, vsig_max;
};

// kLimited: the limited form (PairTerms::limited with volume elements and a constant alpha),
// else the plain one.
template <class V, bool kLimited>
class MomentumEnergyPairs {
    using D = typename V::D;
    using M = typename V::M;
    using F = typename V::F;
    using FM = typename V::FM;

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
            xa_[d] = V::splat(x_[d][a]);
            va_[d] = V::splat(v_[d][a]);
        }
        for (int e = 0; e < 6; ++e) cma_[e] = V::splat(double(cm_[e][a]));
        const double inv_ha = 1.0 / h_[a], inv_ha2 = inv_ha * inv_ha;
        inv_ha_ = V::splat(inv_ha);
        inv_ha2_ = V::splat(inv_ha2);
        inv_ha3_ = V::splat(inv_ha2 * inv_ha);
        // Volume elements: X_a / m_a on both members' pressure coefficients (1 without them)
        if constexpr (kLimited) lim_ = LimitedTerms<V>(a, p, diss);
        const double xa_ma = kLimited ? lim_.xm[a] / m_[a] : 1.0;
        pa_ = double(pgrad_[a]) * xa_ma;
        xa_ma_ = V::splat(xa_ma);
        ca_ = V::splat(double(c_[a]));
        pav_ = V::splat(pa_);
        inv_rho_a_ = V::splat(1.0 / double(rho_[a]));
        pi_factor_ = V::splat(-0.5 * diss.alpha);
    }

    MomentumEnergySums sum(ContiguousSpan nb) const {
        return nb.wraps ? sum<true>(nb) : sum<false>(nb);
    }

  private:
    const double *x_[3], *v_[3], *h_, *m_;
    const float *c_, *pgrad_, *rho_, *cm_[6];
    PolyLanes<V> w_;
    Image<V> image_;
    std::uint32_t a_;
    double pa_;
    D xa_[3], va_[3], cma_[6], inv_ha_, inv_ha2_, inv_ha3_, xa_ma_, ca_, pav_, inv_rho_a_,
        pi_factor_;
    LimitedTerms<V> lim_;

    struct Lanes {
        D ax = V::splat(0.0), ay = V::splat(0.0), az = V::splat(0.0);
        D du_p = V::splat(0.0), du_av = V::splat(0.0), du_cond = V::splat(0.0);
        D vsig_max = V::splat(0.0);
    };

    template <bool kWrap>
    MomentumEnergySums sum(ContiguousSpan nb) const {
        Lanes acc;
        // The body stays a call per step (its sums in memory): inlined into the loop it spilled
        // more than that saved on AVX2 (plain 0.0837 -> 0.0853, limited 0.1375 -> 0.1417 s per
        // step at Sedov 125k), unlike the density and IAD bodies.
        for_each_step<V>(nb.index, nb.count, a_,
                         [&](const std::uint32_t* i, FM valid) { add<kWrap>(i, valid, acc); });
        double du = pa_ * horizontal_sum(acc.du_p) + 0.25 * horizontal_sum(acc.du_av);
        if constexpr (kLimited) du += horizontal_sum(acc.du_cond);
        return {horizontal_sum(acc.ax), horizontal_sum(acc.ay), horizontal_sum(acc.az), du,
                horizontal_max(acc.vsig_max)};
    }

    // One half's pair geometry: d = x_b - x_a, |d|^2 and 1/h_b.
    struct Geometry {
        D d[3], r2, inv_hb;
    };

    // One step; `valid` masks the lanes that hold a pair. An empty lane is the pair (a, a):
    // d = 0 makes every term 0 but the signal velocity, which the mask removes.
    template <bool kWrap>
    EXASPH_INLINE void add(const std::uint32_t* i, FM valid, Lanes& acc) const {
        Geometry g[2];
        typename V::H sa[2], sb[2];
        for (int h = 0; h < 2; ++h) {
            const std::uint32_t* ih = i + h * V::kHalf;
            for (int c = 0; c < 3; ++c) {
                g[h].d[c] = V::gather(x_[c], ih) - xa_[c];
                if constexpr (kWrap) g[h].d[c] = image_(g[h].d[c], c);
            }
            const D* d = g[h].d;
            g[h].r2 = fma(d[2], d[2], fma(d[1], d[1], d[0] * d[0]));
            g[h].inv_hb = V::splat(1.0) / V::gather(h_, ih);
            // v^2 for h_a and for h_b, rounded to float as KernelView::w_at does
            sa[h] = V::to_float(g[h].r2 * inv_ha2_);
            sb[h] = V::to_float(g[h].r2 * (g[h].inv_hb * g[h].inv_hb));
        }
        const F four = V::splat_f(4.0f);
        const F va = V::join(sa[0], sa[1]), vb = V::join(sb[0], sb[1]);
        const F kwa = select(va < four, w_(PolyPowers<V>(va)));
        const F kwb = select(vb < four, w_(PolyPowers<V>(vb)));
        for (int h = 0; h < 2; ++h)
            pair_terms(i + h * V::kHalf, g[h], V::half(kwa, h), V::half(kwb, h), V::half(valid, h),
                       acc);
    }

    // C (x) d for a half's lanes: C_a's broadcast (m) or C_b's gathered.
    EXASPH_INLINE static void iad_times(const D (&m)[6], const D (&d)[3], D (&out)[3]) {
        out[0] = fma(m[2], d[2], fma(m[1], d[1], m[0] * d[0]));
        out[1] = fma(m[4], d[2], fma(m[3], d[1], m[1] * d[0]));
        out[2] = fma(m[5], d[2], fma(m[4], d[1], m[2] * d[0]));
    }

    // physics.md §6's terms of one half's pairs (momentum_energy_portable's plain or limited form).
    EXASPH_INLINE void pair_terms(const std::uint32_t* i, const Geometry& g, D kwa, D kwb, M ok,
                                  Lanes& acc) const {
        const D zero = V::splat(0.0);
        const D r = sqrt(g.r2);
        const D inv_r = select(r > zero, V::splat(1.0) / r);
        const D wa = kwa * inv_ha3_;
        const D wb = ((kwb * g.inv_hb) * g.inv_hb) * g.inv_hb;
        D cmb[6], ca[3], cb[3], aa[3], ab[3], vab[3];
        for (int e = 0; e < 6; ++e) cmb[e] = V::gather(cm_[e], i);
        iad_times(cma_, g.d, ca);
        iad_times(cmb, g.d, cb);
        for (int c = 0; c < 3; ++c) {
            aa[c] = ca[c] * wa; // A_ab(h_a)
            ab[c] = cb[c] * wb; // A_ab(h_b)
            vab[c] = va_[c] - V::gather(v_[c], i);
        }
        const D vr = zero - dot3(vab, g.d); // v_ab . r_ab
        const D w_ab = vr * inv_r;
        const D c_ab = ca_ + V::gather(c_, i);
        const D vsig = c_ab - V::splat(3.0) * w_ab;
        acc.vsig_max = max(select(ok, vsig), acc.vsig_max);
        const M approaching = vr < zero;
        D pi; // Pi_ab
        if constexpr (kLimited)
            pi = lim_.pi(i, g.d, r, inv_r, inv_ha_, g.inv_hb, vr, w_ab, approaching, c_ab,
                         pi_factor_);
        else
            pi = select(approaching, (pi_factor_ * vsig) * w_ab);
        D pb = V::gather(pgrad_, i);
        if constexpr (kLimited) pb = pb * xa_ma_; // X_a / m_a (1 in standard SPH)
        const D rho_b = V::gather(rho_, i);
        const D inv_rho_b = V::splat(1.0) / rho_b;
        const D mb = V::gather(m_, i);
        const D xb = kLimited ? V::gather(lim_.xm, i) : mb; // X_b (m_b in standard SPH)
        D gr[3];                                            // A(h_a)/rho_a + A(h_b)/rho_b
        for (int c = 0; c < 3; ++c) gr[c] = fma(ab[c], inv_rho_b, aa[c] * inv_rho_a_);
        const D half_pi = V::splat(0.5) * pi;
        D* a[3] = {&acc.ax, &acc.ay, &acc.az};
        for (int c = 0; c < 3; ++c) {
            const D pressure = fma(pb, ab[c], pav_ * aa[c]);
            *a[c] = *a[c] - fma(xb, pressure, (mb * half_pi) * gr[c]);
        }
        acc.du_p = fma(xb, dot3(vab, aa), acc.du_p);
        acc.du_av = fma(mb * pi, dot3(vab, gr), acc.du_av);
        if constexpr (kLimited)
            if (lim_.conduction_on)
                acc.du_cond = acc.du_cond - lim_.conduction(i, g.d, inv_r, aa, ab, mb, rho_b);
    }
};

} // namespace exasph::simd
#endif
