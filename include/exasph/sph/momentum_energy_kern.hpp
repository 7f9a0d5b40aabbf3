#pragma once
#include <cmath>
#include <cstdint>
#include <numbers>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/tensile_stress.hpp"
#include "exasph/sph/timestep.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

template <class T>
struct MomentumEnergyResult {
    T ax, ay, az;
    T du;
    T vsig_max;
    T divv; // sum_b V_b (v_b - v_a) . A_ab(h_a)
};

// Artificial dissipation beyond SPEC 6's viscosity.
template <class T>
struct Dissipation {
    T alpha_u = T(0);          // artificial conductivity coefficient (0: off)
    bool reconstruct = false;  // viscosity from velocities reconstructed to the pair midpoint
    T eta_crit = T(0);         // pairs closer than eta_crit max(h_a, h_b) fade the reconstruction
    T alpha = T(1);            // the AV coefficient where particles carry none (no AV switch)
    T tensile = T(0);          // artificial stress coefficient eps where P < 0 (0: off)
    T tensile_positive = T(0); // the stress's eps where P > 0 (0: off)
    bool central = false;      // viscosity along the pair axis (--torque-free)
    int tensile_exponent = 4;  // n of the stress's f_ab^n
    // --torque-free with the stress: its own matrix M (Field::s11..s33, tensile_stress.hpp)
    bool stress_matrix = false;

    static Dissipation of(double alpha, double alpha_u, bool reconstruct, double ng0,
                          double tensile = 0, bool central = false, int tensile_exponent = 4,
                          double tensile_positive = 0) {
        // eta_crit: about the mean particle spacing in units of h, (4/3 pi (2h)^3 / ng0)^(1/3) / h.
        Dissipation d;
        d.alpha_u = T(alpha_u);
        d.reconstruct = reconstruct;
        d.eta_crit = T(std::cbrt(32.0 * std::numbers::pi / (3.0 * ng0)));
        d.alpha = T(alpha);
        d.tensile = T(tensile);
        d.tensile_positive = T(tensile_positive);
        d.central = central;
        d.tensile_exponent = tensile_exponent;
        d.stress_matrix = central && d.stress();
        return d;
    }
    EXASPH_HD bool stress() const { return tensile > T(0) || tensile_positive > T(0); }
    bool any_extra() const { return reconstruct || alpha_u > T(0) || stress() || central; }
    // 1 / W(dp) of the stress's f_ab (0 without the stress).
    EXASPH_HD T stress_inv_w0(const KernelView<T>& k) const {
        return stress() ? T(1) / k.value(eta_crit) : T(0);
    }
};

// v_ab with both velocities reconstructed linearly to the pair midpoint (Rosswog 2015):
//   v~_a = v_a + Phi/2 G_a d,  v~_b = v_b - Phi/2 G_b d,  d = x_b - x_a,
// G the IAD velocity gradients. The van Leer limiter Phi = 4 q_a q_b / (q_a + q_b)^2 (0 unless
// q_a = d.G_a.d and q_b = d.G_b.d agree in sign) is 1 where the flow is linear across the pair,
// so smooth compression (a uniformly converging inflow) is not dissipated, and falls to 0 where
// the slopes disagree, as at a shock. Pairs closer than eta_crit (about the mean particle
// spacing in units of h) lose the reconstruction smoothly, keeping the viscosity's barrier
// against interpenetration. Phi and the midpoint are symmetric in a and b, so Pi_ab stays
// symmetric and momentum and energy stay conserved. Only v~_ab . d enters Pi_ab, and
// (G d) . d = d.S.d with S the strain rate (G's symmetric part): the six components of S
// (strain_rate_field) are all the pair reads, and
//   v~_ab . r_ab = v_ab . r_ab - Phi/2 (q_a + q_b),  r_ab = -d.
inline constexpr double kReconstructedApproachCap = 2.0;

// d.S.d for the strain rate S = (S_11, S_12, S_13, S_22, S_23, S_33).
template <class T>
EXASPH_HD EXASPH_INLINE T strain_along(const T (&e)[6], T dx, T dy, T dz) {
    return dx * (e[0] * dx + T(2) * (e[1] * dy + e[2] * dz)) + dy * (e[3] * dy + T(2) * e[4] * dz) +
           dz * e[5] * dz;
}

template <class T>
EXASPH_HD EXASPH_INLINE T reconstructed_approach(T vr, T dx, T dy, T dz, const T (&ea)[6],
                                                 const T (&eb)[6], T eta, T eta_crit) {
    const T qa = strain_along(ea, dx, dy, dz);
    const T qb = strain_along(eb, dx, dy, dz);
    T phi = qa * qb > T(0) ? T(4) * qa * qb / ((qa + qb) * (qa + qb)) : T(0);
    if (eta < eta_crit) {
        T e = (eta - eta_crit) / T(0.2);
        phi *= std::exp(-e * e);
    }
    return vr - T(0.5) * phi * (qa + qb);
}

// The component of g along the pair axis d, (g . d) d / r^2: a pair force along it is central
// (exerts no torque), which IAD's C_a d W is not.
template <class T>
struct Vec3 {
    T x, y, z;
};
template <class T>
EXASPH_HD EXASPH_INLINE Vec3<T> along_axis(T gx, T gy, T gz, T dx, T dy, T dz, T inv_r2) {
    const T s = (gx * dx + gy * dy + gz * dz) * inv_r2;
    return {s * dx, s * dy, s * dz};
}

// SPEC 6 with IAD gradients, with a per-particle alpha (SPEC 6's "later switch") (SPEC 5), over a
// symmetric neighbour list (r_ab < 2 max(h_a, h_b)), which makes every pair's contribution appear
// with opposite sign in b's sum: momentum is conserved to round-off and energy up to
// time-integration error.
//   A_ab(h_a) = C_a (x_b - x_a) W_ab(h_a),  A_ab(h_b) = C_b (x_b - x_a) W_ab(h_b)
//   dv_a/dt = -sum_b m_b [P_a/(Om_a rho_a^2) A_ab(h_a) + P_b/(Om_b rho_b^2) A_ab(h_b)]
//             (with volume elements: -sum_b (X_a X_b / m_a) [P_a/(Om_a k_a^2) A_ab(h_a) + ...])
//             -1/2 sum_b m_b Pi_ab [A_ab(h_a)/rho_a + A_ab(h_b)/rho_b]
//   du_a/dt = P_a/(Om_a rho_a^2) sum_b m_b v_ab . A_ab(h_a)
//             +1/4 sum_b m_b Pi_ab v_ab . [A_ab(h_a)/rho_a + A_ab(h_b)/rho_b]
// kExtras: conductivity or the limiter may be on. kAlphaField: alpha per particle (the AV
// switch, which also wants the velocity divergence), else the constant diss.alpha (divv is
// then not computed). kVolumeElements: X and k are fields; without them X = m is read once per
// neighbour (not twice through an aliased pointer) and X_a / m_a = 1. P/(Om k^2) comes
// precomputed per particle (Field::pgrad, set by the density pass).
template <class T, bool kExtras = true, bool kAlphaField = true, bool kVolumeElements = true,
          class N>
EXASPH_HD MomentumEnergyResult<T>
momentum_energy_kern(std::uint32_t a, NeighbourSpan nb, const ParticleView<T, N>& p,
                     const Box<T>& box, const KernelView<T>& k, const Dissipation<T>& diss = {}) {
    const T alpha_u = diss.alpha_u;
    const T *x = p[Field::x], *y = p[Field::y], *z = p[Field::z];
    const T *vx = p[Field::vx], *vy = p[Field::vy], *vz = p[Field::vz];
    const T *h = p[Field::h], *m = p[Field::m];
    // Stored in N (is_narrow): rho, c, P/(Omega k^2) (and P) of both members of a pair come
    // from the same stored values, so the pair terms stay antisymmetric.
    const N *rho = p.narrow(Field::rho), *pr = p.narrow(Field::p), *c = p.narrow(Field::c),
            *pgrad = p.narrow(Field::pgrad);
    const T* alpha = p[Field::alpha];
    const T ha = h[a], inv_ha = T(1) / ha, inv_ha3 = inv_ha * inv_ha * inv_ha;
    const T rho_a = rho[a], inv_rho_a = T(1) / rho_a;
    // Standard SPH carries no X and k fields: X = m, k = rho.
    const T *xm = p[Field::xm], *kx = p[Field::kx];
    // Volume elements: the pressure terms carry X_a X_b / m_a and 1/k^2 in place of m_b and
    // 1/rho^2 (identical for X = m, where X_a / m_a = 1 and k = rho).
    const T xa_ma = kVolumeElements ? xm[a] / m[a] : T(1);
    const T pa = T(pgrad[a]) * xa_ma;
    T ax = 0, ay = 0, az = 0, du_p = 0, du_av = 0, vsig_max = 0, divv = 0, du_cond = 0;
    // Artificial stress (Monaghan 2000) against the tensile instability: the pressure
    // coefficient of a pair gains R f_ab^n, R = eps |P/(Om k^2)| where P < 0 (eps_positive P
    // where P > 0, stress_coefficient), f_ab = W(r)/W(dp) with dp the mean particle spacing
    // (eta_crit h), so close pairs repel. R enters both members' terms as P does, so momentum
    // stays conserved, and du/dt takes R's work.
    const T eps_ts = kExtras ? diss.tensile : T(0);
    const T eps_pos = kExtras ? diss.tensile_positive : T(0);
    const T ra = stress_coefficient(pa, eps_ts, eps_pos);
    const T inv_w0 = kExtras ? diss.stress_inv_w0(k) : T(0);
    const int n_ts = diss.tensile_exponent;
    const bool own_stress_matrix = kExtras && diss.stress_matrix;
    const bool stress_on = kExtras && diss.stress(); // the schemes without it skip its pair work
    T du_ts = 0;
    const T* u = p[Field::u];
    T ea[6] = {0, 0, 0, 0, 0, 0}; // the strain rate S_a, with the limiter
    if (diss.reconstruct)
        for (int e = 0; e < 6; ++e) ea[e] = p.narrow(strain_rate_field(e))[a];
    const PeriodicImage<T> image(box);
#pragma omp simd reduction(+ : ax, ay, az, du_p, du_av, divv, du_cond, du_ts) \
    reduction(max : vsig_max)
    for (std::uint32_t n = 0; n < nb.count; ++n) {
        const std::uint32_t b = nb[n];
        // d = x_b - x_a = -r_ab
        T dx = image(x[b] - x[a], 0);
        T dy = image(y[b] - y[a], 1);
        T dz = image(z[b] - z[a], 2);
        T r = std::sqrt(dx * dx + dy * dy + dz * dz);
        // 1/r once for the pair's divisions by r (0 for r = 0, where every numerator is 0)
        T inv_r = r > T(0) ? T(1) / r : T(0);
        T hb = h[b], inv_hb = T(1) / hb;
        T va = r * inv_ha, vb = r * inv_hb;
        T kwa = k.value(va), kwb = k.value(vb);
        T wa = kwa * inv_ha3;
        T wb = kwb * inv_hb * inv_hb * inv_hb;
        IadProduct<T> ca = iad_times(p, a, dx, dy, dz);
        IadProduct<T> cb = iad_times(p, b, dx, dy, dz);
        T aax = ca.x * wa, aay = ca.y * wa, aaz = ca.z * wa; // A_ab(h_a)
        T abx = cb.x * wb, aby = cb.y * wb, abz = cb.z * wb; // A_ab(h_b)
        T vabx = vx[a] - vx[b], vaby = vy[a] - vy[b], vabz = vz[a] - vz[b];
        // v_ab . r_ab with r_ab = -d
        T vr = -(vabx * dx + vaby * dy + vabz * dz);
        T w_ab = vr * inv_r;

        T vsig = T(c[a]) + T(c[b]) - T(3) * w_ab;
        vsig_max = vsig > vsig_max ? vsig : vsig_max;
        // alpha_ab = (alpha_a + alpha_b)/2 keeps Pi_ab symmetric (= alpha for a constant alpha)
        T alpha_ab = kAlphaField ? T(0.5) * (alpha[a] + alpha[b]) : diss.alpha;
        T pi_ab = vr < T(0) ? T(-0.5) * alpha_ab * vsig * w_ab : T(0);
        if (kExtras && diss.reconstruct && vr < T(0)) {
            // Only pairs that really approach are dissipated: the heating Pi_ab v_ab . A stays
            // positive.
            T eb[6];
            for (int e = 0; e < 6; ++e) eb[e] = p.narrow(strain_rate_field(e))[b];
            T eta = va < vb ? va : vb; // r / max(h_a, h_b)
            T wt = reconstructed_approach(vr, dx, dy, dz, ea, eb, eta, diss.eta_crit) * inv_r;
            // The reconstructed approach is at most kReconstructedApproachCap times the pair's
            // own, so Pi_ab goes to 0 continuously as a pair stops approaching (a jump there
            // turned the round-off of the summation order into 1e-7 force differences between
            // rank counts); beyond 1, noisy gradients still damp velocity noise (Gresho-Chan).
            wt = wt > kReconstructedApproachCap * w_ab ? wt : kReconstructedApproachCap * w_ab;
            pi_ab = wt < T(0) ? T(-0.5) * alpha_ab * (T(c[a]) + T(c[b]) - T(3) * wt) * wt : T(0);
        }
        T pb = T(pgrad[b]) * xa_ma;
        T inv_rho_b = T(1) / T(rho[b]);
        T mb = m[b];
        T gx = aax * inv_rho_a + abx * inv_rho_b; // A(h_a)/rho_a + A(h_b)/rho_b
        T gy = aay * inv_rho_a + aby * inv_rho_b;
        T gz = aaz * inv_rho_a + abz * inv_rho_b;
        if (kExtras && diss.central) { // --torque-free: viscosity along the pair axis
            const Vec3<T> g = along_axis(gx, gy, gz, dx, dy, dz, inv_r * inv_r);
            gx = g.x, gy = g.y, gz = g.z;
        }
        T half_pi = T(0.5) * pi_ab;
        T xb = kVolumeElements ? xm[b] : mb;
        // The stress's pair coefficients f_ab^n R_a, f_ab^n R_b, with the pressure's IAD
        // gradients A_ab or, with --torque-free, its own matrix's (M_a d W_a, M_b d W_b: no net
        // torque). (The central form along the pair axis made the square patch unstable by
        // t = 0.12.)
        T qa = pa, qb = pb;
        T tax = 0, tay = 0, taz = 0, tv = 0; // the own-matrix stress force and its work
        if (stress_on) {
            const T fn = stress_weight(kwa, kwb, inv_w0, n_ts);
            const T rb = stress_coefficient(pb, eps_ts, eps_pos);
            if (own_stress_matrix) {
                const IadProduct<T> sa = stress_matrix_times(p, a, dx, dy, dz);
                const IadProduct<T> sb = stress_matrix_times(p, b, dx, dy, dz);
                const T fa = fn * ra * wa, fb = fn * rb * wb;
                tax = fa * sa.x + fb * sb.x, tay = fa * sa.y + fb * sb.y;
                taz = fa * sa.z + fb * sb.z;
                tv = fn * wa * (vabx * sa.x + vaby * sa.y + vabz * sa.z);
            } else {
                qa += fn * ra;
                qb += fn * rb;
                tv = fn * (vabx * aax + vaby * aay + vabz * aaz);
            }
        }
        ax -= xb * (qa * aax + qb * abx + tax) + mb * half_pi * gx;
        ay -= xb * (qa * aay + qb * aby + tay) + mb * half_pi * gy;
        az -= xb * (qa * aaz + qb * abz + taz) + mb * half_pi * gz;
        T v_dot_a = vabx * aax + vaby * aay + vabz * aaz;
        du_p += xb * v_dot_a;
        du_ts += xb * tv;
        if constexpr (kAlphaField) { // the AV switch's input only
            const T kb = kVolumeElements ? kx[b] : T(rho[b]);
            divv -= xb / kb * v_dot_a;
        }
        du_av += mb * pi_ab * (vabx * gx + vaby * gy + vabz * gz);
        if (kExtras && alpha_u > T(0)) {
            // Artificial conductivity (Price 2008): heat flows from hot to cold along the pair,
            // with signal speed sqrt(|P_a - P_b| / rho_ab) and |grad W| ~ A_bar . d / r, both
            // symmetric in a and b, so sum_a m_a du_a/dt stays zero.
            T inv_rho_bar = T(2) / (rho_a + T(rho[b]));
            T vu = std::sqrt(std::abs(T(pr[a]) - T(pr[b])) * inv_rho_bar);
            T fbar = T(0.5) * ((aax + abx) * dx + (aay + aby) * dy + (aaz + abz) * dz) * inv_r;
            du_cond -= mb * alpha_u * vu * (u[a] - u[b]) * fbar * inv_rho_bar;
        }
    }
    return {ax, ay, az, pa * du_p + ra * du_ts + T(0.25) * du_av + du_cond, vsig_max, divv};
}

// The momentum-energy pass of one particle: a, du/dt (and div v for the AV switch) stored;
// returns the particle's Courant time step (SPEC 7) for the factor `courant`, so that signal
// velocities are used where they are computed, not stored.
template <class T, bool kExtras, bool kAlphaField, bool kVolumeElements, class N = float>
struct MomentumEnergyKernel {
    ParticleView<T, N> p;
    Box<T> box;
    KernelView<T> k;
    Dissipation<T> diss;
    T courant;

    EXASPH_HD T operator()(std::uint32_t i, NeighbourSpan nb) const {
        auto r =
            momentum_energy_kern<T, kExtras, kAlphaField, kVolumeElements>(i, nb, p, box, k, diss);
        p[Field::ax][i] = r.ax;
        p[Field::ay][i] = r.ay;
        p[Field::az][i] = r.az;
        p[Field::du][i] = r.du;
        if (p[Field::divv]) p[Field::divv][i] = r.divv;
        return courant_time_step(p[Field::h][i], r.vsig_max, T(p.narrow(Field::c)[i]), courant);
    }
};

} // namespace exasph
