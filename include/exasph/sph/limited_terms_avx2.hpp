#pragma once
// What the limited form of the momentum-energy pair loop (sph/momentum_energy_avx2.hpp) adds
// to the plain one, on four pairs: volume elements' X, the slope-limited viscosity
// (limited_viscosity, sph/pair_dissipation.hpp) and the artificial conductivity, in the
// portable loop's order of operations.
#include "exasph/sph/avx2_lanes.hpp"

#ifdef EXASPH_AVX2_PAIRS
#include <cstdint>

#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/pair_dissipation.hpp"
#include "exasph/util/branch_free_exp.hpp"

namespace exasph::avx2 {

// d.S.d for four pairs (strain_along) with S's six components.
EXASPH_INLINE __m256d strain_along4(const __m256d (&e)[6], const __m256d (&d)[3]) {
    const __m256d two = _mm256_set1_pd(2.0);
    const __m256d row0 = _mm256_add_pd(
        _mm256_mul_pd(e[0], d[0]),
        _mm256_mul_pd(two, _mm256_add_pd(_mm256_mul_pd(e[1], d[1]), _mm256_mul_pd(e[2], d[2]))));
    const __m256d row1 =
        _mm256_add_pd(_mm256_mul_pd(e[3], d[1]), _mm256_mul_pd(_mm256_mul_pd(two, e[4]), d[2]));
    return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(d[0], row0), _mm256_mul_pd(d[1], row1)),
                         _mm256_mul_pd(_mm256_mul_pd(d[2], e[5]), d[2]));
}

// Particle a's part (fields, its strain rate, u, P and rho broadcast) and the pair terms.
struct LimitedTerms {
    const double *xm = nullptr, *u = nullptr;
    const float *pr = nullptr, *strain[6] = {};
    __m256d ea[6], eta_crit, alpha_u, u_a, p_a, rho_a;
    bool conduction_on = false; // alpha_u > 0 (the pe scheme has none)

    LimitedTerms() = default;
    LimitedTerms(std::uint32_t a, const ParticleView<double, float>& p,
                 const Dissipation<double>& diss)
        : xm(p[Field::xm]), u(p[Field::u]), pr(p.narrow(Field::p)),
          conduction_on(diss.alpha_u > 0) {
        for (int e = 0; e < 6; ++e) {
            strain[e] = p.narrow(strain_rate_field(e));
            ea[e] = _mm256_set1_pd(double(strain[e][a]));
        }
        eta_crit = _mm256_set1_pd(diss.eta_crit);
        alpha_u = _mm256_set1_pd(diss.alpha_u);
        u_a = _mm256_set1_pd(u[a]);
        p_a = _mm256_set1_pd(double(pr[a]));
        rho_a = _mm256_set1_pd(double(p.narrow(Field::rho)[a]));
    }

    // Pi_ab of limited_viscosity: the van Leer limiter of both slopes along d, faded below
    // eta_crit (e^-e^2 only where some lane is that close, about one step in six).
    // pi_factor = -alpha / 2, c_ab = c_a + c_b.
    EXASPH_INLINE __m256d pi(const std::uint32_t* i, const __m256d (&d)[3], __m256d r,
                             __m256d inv_r, __m256d inv_ha, __m256d inv_hb, __m256d vr,
                             __m256d w_ab, __m256d approaching, __m256d c_ab,
                             __m256d pi_factor) const {
        __m256d eb[6];
        for (int e = 0; e < 6; ++e) eb[e] = gather4_float(strain[e], i);
        const __m256d qa = strain_along4(ea, d), qb = strain_along4(eb, d);
        const __m256d zero = _mm256_setzero_pd();
        const __m256d qs = _mm256_add_pd(qa, qb);
        const __m256d agree = _mm256_cmp_pd(_mm256_mul_pd(qa, qb), zero, _CMP_GT_OQ);
        __m256d phi = _mm256_and_pd(
            agree, _mm256_div_pd(_mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(4.0), qa), qb),
                                 _mm256_mul_pd(qs, qs)));
        const __m256d eta = _mm256_min_pd(_mm256_mul_pd(r, inv_ha), _mm256_mul_pd(r, inv_hb));
        const __m256d close = _mm256_cmp_pd(eta, eta_crit, _CMP_LT_OQ);
        if (_mm256_movemask_pd(close)) {
            const __m256d e = _mm256_div_pd(_mm256_sub_pd(eta, eta_crit), _mm256_set1_pd(0.2));
            const __m256d fade = exp_nonpositive4(_mm256_sub_pd(zero, _mm256_mul_pd(e, e)));
            phi = _mm256_mul_pd(phi, _mm256_blendv_pd(_mm256_set1_pd(1.0), fade, close));
        }
        const __m256d recon =
            _mm256_sub_pd(vr, _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(0.5), phi), qs));
        const __m256d wt =
            _mm256_max_pd(_mm256_mul_pd(recon, inv_r),
                          _mm256_mul_pd(_mm256_set1_pd(kReconstructedApproachCap), w_ab));
        const __m256d on = _mm256_and_pd(approaching, _mm256_cmp_pd(wt, zero, _CMP_LT_OQ));
        const __m256d pi = _mm256_mul_pd(
            _mm256_mul_pd(pi_factor, _mm256_sub_pd(c_ab, _mm256_mul_pd(_mm256_set1_pd(3.0), wt))),
            wt);
        return _mm256_and_pd(on, pi);
    }

    // The conductivity's term of four pairs (momentum_energy_portable's du_cond), to subtract
    // from du: A(h_a), A(h_b) are the pairs' IAD gradients, rho_b their densities.
    EXASPH_INLINE __m256d conduction(const std::uint32_t* i, const __m256d (&d)[3], __m256d inv_r,
                                     const __m256d (&aa)[3], const __m256d (&ab)[3], __m256d mb,
                                     __m256d rho_b) const {
        const __m256d inv_rho_bar = _mm256_div_pd(_mm256_set1_pd(2.0), _mm256_add_pd(rho_a, rho_b));
        const __m256d dp = _mm256_sub_pd(p_a, gather4_float(pr, i));
        const __m256d abs_dp = _mm256_andnot_pd(_mm256_set1_pd(-0.0), dp);
        const __m256d vu = _mm256_sqrt_pd(_mm256_mul_pd(abs_dp, inv_rho_bar));
        __m256d s[3];
        for (int c = 0; c < 3; ++c) s[c] = _mm256_add_pd(aa[c], ab[c]);
        const __m256d fbar = _mm256_mul_pd(_mm256_mul_pd(_mm256_set1_pd(0.5), dot3(s, d)), inv_r);
        const __m256d du = _mm256_sub_pd(u_a, gather4(u, i));
        __m256d t = _mm256_mul_pd(_mm256_mul_pd(mb, alpha_u), vu);
        t = _mm256_mul_pd(_mm256_mul_pd(t, du), fbar);
        return _mm256_mul_pd(t, inv_rho_bar);
    }
};

} // namespace exasph::avx2
#endif
