#pragma once
// What the limited form of the momentum-energy pair loop (sph/momentum_energy_simd.hpp) adds
// to the plain one, on one half's lanes: volume elements' X, the slope-limited viscosity
// (limited_viscosity, sph/pair_dissipation.hpp) and the artificial conductivity, in the
// portable loop's order of operations.
#include "exasph/sph/simd_isa.hpp"

#ifdef EXASPH_SIMD_LANES
#include <cstdint>

#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/pair_dissipation.hpp"

namespace exasph::simd {

// d.S.d (strain_along) with S's six components.
template <class V, class D = typename V::D>
EXASPH_INLINE D strain_along(const D (&e)[6], const D (&d)[3]) {
    const D two = V::splat(2.0);
    const D row0 = e[0] * d[0] + two * (e[1] * d[1] + e[2] * d[2]);
    const D row1 = e[3] * d[1] + (two * e[4]) * d[2];
    return (d[0] * row0 + d[1] * row1) + (d[2] * e[5]) * d[2];
}

// Particle a's part (fields, its strain rate, u, P and rho broadcast) and the pair terms.
template <class V>
struct LimitedTerms {
    using D = typename V::D;
    using M = typename V::M;
    const double *xm = nullptr, *u = nullptr;
    const float *pr = nullptr, *strain[6] = {};
    D ea[6], eta_crit, alpha_u, u_a, p_a, rho_a;
    bool conduction_on = false; // alpha_u > 0 (the pe scheme has none)

    LimitedTerms() = default;
    LimitedTerms(std::uint32_t a, const ParticleView<double, float>& p,
                 const Dissipation<double>& diss)
        : xm(p[Field::xm]), u(p[Field::u]), pr(p.narrow(Field::p)),
          conduction_on(diss.alpha_u > 0) {
        for (int e = 0; e < 6; ++e) {
            strain[e] = p.narrow(strain_rate_field(e));
            ea[e] = V::splat(double(strain[e][a]));
        }
        eta_crit = V::splat(diss.eta_crit);
        alpha_u = V::splat(diss.alpha_u);
        u_a = V::splat(u[a]);
        p_a = V::splat(double(pr[a]));
        rho_a = V::splat(double(p.narrow(Field::rho)[a]));
    }

    // Pi_ab of limited_viscosity: the van Leer limiter of both slopes along d, faded below
    // eta_crit (e^-e^2 only where some lane is that close, about one step in six).
    // pi_factor = -alpha / 2, c_ab = c_a + c_b.
    EXASPH_INLINE D pi(const std::uint32_t* i, const D (&d)[3], D r, D inv_r, D inv_ha, D inv_hb,
                       D vr, D w_ab, M approaching, D c_ab, D pi_factor) const {
        D eb[6];
        for (int e = 0; e < 6; ++e) eb[e] = V::gather(strain[e], i);
        const D qa = strain_along<V>(ea, d), qb = strain_along<V>(eb, d);
        const D zero = V::splat(0.0);
        const D qs = qa + qb;
        D phi = select(qa * qb > zero, (V::splat(4.0) * qa) * qb / (qs * qs));
        const D eta = min(r * inv_ha, r * inv_hb);
        const M close = eta < eta_crit;
        if (any(close)) {
            const D e = (eta - eta_crit) / V::splat(0.2);
            phi = phi * blend(close, V::splat(1.0), exp_nonpositive<V>(zero - e * e));
        }
        const D recon = vr - (V::splat(0.5) * phi) * qs;
        const D wt = max(recon * inv_r, V::splat(kReconstructedApproachCap) * w_ab);
        return select(approaching & (wt < zero), (pi_factor * (c_ab - V::splat(3.0) * wt)) * wt);
    }

    // The conductivity's term (momentum_energy_portable's du_cond), to subtract from du: A(h_a),
    // A(h_b) are the pairs' IAD gradients, rho_b their densities.
    EXASPH_INLINE D conduction(const std::uint32_t* i, const D (&d)[3], D inv_r, const D (&aa)[3],
                               const D (&ab)[3], D mb, D rho_b) const {
        const D inv_rho_bar = V::splat(2.0) / (rho_a + rho_b);
        const D vu = sqrt(abs(p_a - V::gather(pr, i)) * inv_rho_bar);
        const D s[3] = {aa[0] + ab[0], aa[1] + ab[1], aa[2] + ab[2]};
        const D fbar = (V::splat(0.5) * dot3(s, d)) * inv_r;
        const D du = u_a - V::gather(u, i);
        return ((((mb * alpha_u) * vu) * du) * fbar) * inv_rho_bar;
    }
};

} // namespace exasph::simd
#endif
