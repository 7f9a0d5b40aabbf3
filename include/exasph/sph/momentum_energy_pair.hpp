#pragma once
// One particle's side of the portable momentum-energy loop (sph/momentum_energy_kern.hpp): what
// the loop reads of particle a once, and the terms of one pair (a, b) as values, so that the loop
// body reads as the sums of physics.md §6. Every helper is inlined into the `omp simd` loop; the
// arithmetic is the loop's own, operation for operation.
#include <cstdint>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/pair_dissipation.hpp"
#include "exasph/sph/tensile_stress.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// The geometry of a pair: d = x_b - x_a = -r_ab, the kernels and the IAD gradients A_ab(h_a),
// A_ab(h_b), the relative velocity v_ab and w_ab = v_ab . r_ab / r.
template <class T>
struct MomentumEnergyPairGeometry {
    T dx, dy, dz, r, inv_r, va, vb;
    T kwa, kwb, wa, wb; // w(v) without and with 1/h^3, at h_a and h_b
    T aax, aay, aaz;    // A_ab(h_a)
    T abx, aby, abz;    // A_ab(h_b)
    T vabx, vaby, vabz; // v_ab
    T vr, w_ab;         // v_ab . r_ab and that over r
};

// The artificial stress's share of a pair: the pressure coefficients with it (qa, qb), and with
// --torque-free its own-matrix force and work.
template <class T>
struct MomentumEnergyStress {
    T qa, qb;
    T tax, tay, taz, tv;
};

// Requires: p holds the fields of the scheme the template arguments name (PairTerms kTerms, the
// AV switch's alpha with kAlphaField, X and k with kVolumeElements); a is a particle of p.
template <class T, PairTerms kTerms, bool kAlphaField, bool kVolumeElements, class N>
struct MomentumEnergyParticle {
    static constexpr bool kExtras = kTerms != PairTerms::plain;
    static constexpr bool kLimited = kTerms == PairTerms::limited; // the limiter on, no stress
    static constexpr bool kAny = kTerms == PairTerms::any;

    std::uint32_t a;
    const ParticleView<T, N>& p;
    const KernelView<T>& k;
    const Dissipation<T>& diss;
    const T *x, *y, *z, *vx, *vy, *vz, *h, *m, *alpha, *u, *xm, *kx;
    // Stored in N (is_narrow): rho, c, P/(Omega k^2) (and P) of both members of a pair come
    // from the same stored values, so the pair terms stay antisymmetric.
    const N *rho, *pr, *c, *pgrad;
    T alpha_u, inv_ha, inv_ha2, inv_ha3, rho_a, inv_rho_a;
    // Volume elements: the pressure terms carry X_a X_b / m_a and 1/k^2 in place of m_b and
    // 1/rho^2 (identical for X = m, where X_a / m_a = 1 and k = rho).
    T xa_ma, pa;
    // Artificial stress (Monaghan 2000) against the tensile instability: the pressure
    // coefficient of a pair gains R f_ab^n, R = eps |P/(Om k^2)| where P < 0 (eps_positive P
    // where P > 0, stress_coefficient), f_ab = W(r)/W(dp) with dp the mean particle spacing
    // (eta_crit h), so close pairs repel. R enters both members' terms as P does, so momentum
    // stays conserved, and du/dt takes R's work.
    T eps_ts, eps_pos, ra, inv_w0;
    int n_ts;
    bool own_stress_matrix, stress_on; // the schemes without the stress skip its pair work
    T ea[6] = {0, 0, 0, 0, 0, 0};      // the strain rate S_a, with the limiter
    const N* strain[6] = {};           // its fields
    IadMatrixFields<N> cmat;
    PeriodicImage<T> image;

    EXASPH_HD MomentumEnergyParticle(std::uint32_t a_, const ParticleView<T, N>& p_,
                                     const Box<T>& box, const KernelView<T>& k_,
                                     const Dissipation<T>& d)
        : a(a_), p(p_), k(k_), diss(d), x(p[Field::x]), y(p[Field::y]), z(p[Field::z]),
          vx(p[Field::vx]), vy(p[Field::vy]), vz(p[Field::vz]), h(p[Field::h]), m(p[Field::m]),
          alpha(p[Field::alpha]), u(p[Field::u]), xm(p[Field::xm]), kx(p[Field::kx]),
          rho(p.narrow(Field::rho)), pr(p.narrow(Field::p)), c(p.narrow(Field::c)),
          pgrad(p.narrow(Field::pgrad)), alpha_u(d.alpha_u), inv_ha(T(1) / h[a]),
          inv_ha2(inv_ha * inv_ha), inv_ha3(inv_ha2 * inv_ha), rho_a(rho[a]),
          inv_rho_a(T(1) / rho_a), xa_ma(kVolumeElements ? xm[a] / m[a] : T(1)),
          pa(T(pgrad[a]) * xa_ma), eps_ts(kAny ? d.tensile : T(0)),
          eps_pos(kAny ? d.tensile_positive : T(0)), ra(stress_coefficient(pa, eps_ts, eps_pos)),
          inv_w0(kAny ? d.stress_inv_w0(k_) : T(0)), n_ts(d.tensile_exponent),
          own_stress_matrix(kAny && d.stress_matrix), stress_on(kAny && d.stress()), cmat(p_),
          image(box) {
        if (kExtras && d.reconstruct)
            for (int e = 0; e < 6; ++e) {
                strain[e] = p.narrow(strain_rate_field(e));
                ea[e] = strain[e][a];
            }
    }

    EXASPH_HD EXASPH_INLINE MomentumEnergyPairGeometry<T> geometry(std::uint32_t b) const {
        MomentumEnergyPairGeometry<T> q;
        q.dx = image(x[b] - x[a], 0);
        q.dy = image(y[b] - y[a], 1);
        q.dz = image(z[b] - z[a], 2);
        const T r2 = squared_norm(q.dx, q.dy, q.dz); // as the stress matrix computes it
        q.r = std::sqrt(r2);
        // 1/r once for the pair's divisions by r (0 for r = 0, where every numerator is 0)
        q.inv_r = q.r > T(0) ? T(1) / q.r : T(0);
        const T inv_hb = T(1) / h[b];
        q.va = q.r * inv_ha, q.vb = q.r * inv_hb;
        // w in N (float by default: 9-11 % faster on Sedov, docs/performance-log.md), 1/h squared
        // before it multiplies r^2 for both members, so a and b compute the same w_ab(h) to the bit
        q.kwa = k.template w_at<N>(r2, inv_ha2), q.kwb = k.template w_at<N>(r2, inv_hb * inv_hb);
        q.wa = q.kwa * inv_ha3;
        q.wb = q.kwb * inv_hb * inv_hb * inv_hb;
        const IadProduct<T> ca = cmat.times(a, q.dx, q.dy, q.dz);
        const IadProduct<T> cb = cmat.times(b, q.dx, q.dy, q.dz);
        q.aax = ca.x * q.wa, q.aay = ca.y * q.wa, q.aaz = ca.z * q.wa;
        q.abx = cb.x * q.wb, q.aby = cb.y * q.wb, q.abz = cb.z * q.wb;
        q.vabx = vx[a] - vx[b], q.vaby = vy[a] - vy[b], q.vabz = vz[a] - vz[b];
        q.vr = -(q.vabx * q.dx + q.vaby * q.dy + q.vabz * q.dz); // v_ab . r_ab with r_ab = -d
        q.w_ab = q.vr * q.inv_r;
        return q;
    }

    // Pi_ab of approaching pairs; alpha_ab = (alpha_a + alpha_b)/2 keeps it symmetric (= alpha
    // for a constant alpha). Every pair, without a branch (limited_viscosity is 0 unless the
    // pair approaches): kLimited's loop then vectorises.
    EXASPH_HD EXASPH_INLINE T viscosity(std::uint32_t b, const MomentumEnergyPairGeometry<T>& q,
                                        T vsig) const {
        const T alpha_ab = kAlphaField ? T(0.5) * (alpha[a] + alpha[b]) : diss.alpha;
        T pi_ab = q.vr < T(0) ? T(-0.5) * alpha_ab * vsig * q.w_ab : T(0);
        if (kLimited || (kAny && diss.reconstruct)) {
            T eb[6];
            for (int e = 0; e < 6; ++e) eb[e] = strain[e][b];
            const T eta = q.va < q.vb ? q.va : q.vb; // r / max(h_a, h_b)
            pi_ab = limited_viscosity(q.vr, q.w_ab, q.inv_r, q.dx, q.dy, q.dz, ea, eb, eta, diss,
                                      alpha_ab, T(c[a]) + T(c[b]));
        }
        return pi_ab;
    }

    // A(h_a)/rho_a + A(h_b)/rho_b, along the pair axis with --torque-free.
    EXASPH_HD EXASPH_INLINE Vec3<T> viscous_gradient(std::uint32_t b,
                                                     const MomentumEnergyPairGeometry<T>& q) const {
        const T inv_rho_b = T(1) / T(rho[b]);
        const T gx = q.aax * inv_rho_a + q.abx * inv_rho_b;
        const T gy = q.aay * inv_rho_a + q.aby * inv_rho_b;
        const T gz = q.aaz * inv_rho_a + q.abz * inv_rho_b;
        if (kAny && diss.central) // --torque-free: viscosity along the pair axis
            return along_axis(gx, gy, gz, q.dx, q.dy, q.dz, q.inv_r * q.inv_r);
        return {gx, gy, gz};
    }

    // The stress's pair coefficients f_ab^n R_a, f_ab^n R_b, with the pressure's IAD gradients
    // A_ab or, with --torque-free, its own matrix's (M_a d W_a, M_b d W_b: no net torque). (The
    // central form along the pair axis made the square patch unstable by t = 0.12.)
    EXASPH_HD EXASPH_INLINE MomentumEnergyStress<T>
    stress(std::uint32_t b, const MomentumEnergyPairGeometry<T>& q, T pb) const {
        MomentumEnergyStress<T> s{pa, pb, 0, 0, 0, 0};
        if (!stress_on) return s;
        const T fn = stress_weight(q.kwa, q.kwb, inv_w0, n_ts);
        const T rb = stress_coefficient(pb, eps_ts, eps_pos);
        if (own_stress_matrix) {
            const IadProduct<T> sa = stress_matrix_times(p, a, q.dx, q.dy, q.dz);
            const IadProduct<T> sb = stress_matrix_times(p, b, q.dx, q.dy, q.dz);
            const T fa = fn * ra * q.wa, fb = fn * rb * q.wb;
            s.tax = fa * sa.x + fb * sb.x, s.tay = fa * sa.y + fb * sb.y;
            s.taz = fa * sa.z + fb * sb.z;
            s.tv = fn * q.wa * (q.vabx * sa.x + q.vaby * sa.y + q.vabz * sa.z);
        } else {
            s.qa += fn * ra;
            s.qb += fn * rb;
            s.tv = fn * (q.vabx * q.aax + q.vaby * q.aay + q.vabz * q.aaz);
        }
        return s;
    }

    // Artificial conductivity (Price 2008), the amount du_a/dt loses: heat flows from hot to
    // cold along the pair, with signal speed sqrt(|P_a - P_b| / rho_ab) and |grad W| ~ A_bar . d
    // / r, both symmetric in a and b, so sum_a m_a du_a/dt stays zero.
    EXASPH_HD EXASPH_INLINE T conduction(std::uint32_t b,
                                         const MomentumEnergyPairGeometry<T>& q) const {
        const T inv_rho_bar = T(2) / (rho_a + T(rho[b]));
        const T vu = std::sqrt(std::abs(T(pr[a]) - T(pr[b])) * inv_rho_bar);
        const T fbar = T(0.5) *
                       ((q.aax + q.abx) * q.dx + (q.aay + q.aby) * q.dy + (q.aaz + q.abz) * q.dz) *
                       q.inv_r;
        return m[b] * alpha_u * vu * (u[a] - u[b]) * fbar * inv_rho_bar;
    }
};

} // namespace exasph
