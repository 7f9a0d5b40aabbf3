#pragma once
#include <cmath>
#include <cstdint>
#include <numbers>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/branch_free_exp.hpp"

// What the momentum-energy pair loop adds to physics.md §6's pressure and viscosity terms: the
// options (Dissipation), the slope-limited viscosity's reconstruction, and the central projection
// of
// --torque-free.
namespace exasph {

// The pair terms one instantiation of the momentum-energy loop carries: `plain` none of the
// options below, `limited` the slope-limited viscosity (with the conductivity if alpha_u > 0)
// and nothing else (the ve, pe and sh schemes) in a loop without a branch, which vectorises,
// `any` every option (the artificial stress, --torque-free, conductivity without the limiter).
enum class PairTerms { plain, limited, any };

// Artificial dissipation beyond physics.md §6's viscosity.
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
    PairTerms terms() const {
        if (stress() || central || (alpha_u > T(0) && !reconstruct)) return PairTerms::any;
        return reconstruct ? PairTerms::limited : PairTerms::plain;
    }
    // 1 / W(dp) of the stress's f_ab (0 without the stress).
    EXASPH_HD T stress_inv_w0(const KernelView<T>& k) const {
        return stress() ? T(1) / k.w_sq(eta_crit * eta_crit) : T(0);
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
    const T e = (eta - eta_crit) / T(0.2);
    phi *= eta < eta_crit ? exp_nonpositive(-e * e) : T(1); // no branch: the loop vectorises
    return vr - T(0.5) * phi * (qa + qb);
}

// Pi_ab of the slope-limited viscosity from the pair's approach vr = v_ab . r_ab (w_ab = vr / r)
// and both strain rates: 0 unless the pair approaches (vr < 0: the heating Pi_ab v_ab . A stays
// positive) and its reconstructed velocities approach too. The reconstructed approach is at most
// kReconstructedApproachCap times the pair's own, so Pi_ab goes to 0 continuously as a pair
// stops approaching (a jump there turned the round-off of the summation order into 1e-7 force
// differences between rank counts); beyond 1, noisy gradients still damp velocity noise
// (Gresho-Chan). c_ab = c_a + c_b, eta = r / max(h_a, h_b).
template <class T>
EXASPH_HD EXASPH_INLINE T limited_viscosity(T vr, T w_ab, T inv_r, T dx, T dy, T dz,
                                            const T (&ea)[6], const T (&eb)[6], T eta,
                                            const Dissipation<T>& diss, T alpha_ab, T c_ab) {
    T wt = reconstructed_approach(vr, dx, dy, dz, ea, eb, eta, diss.eta_crit) * inv_r;
    wt = wt > T(kReconstructedApproachCap) * w_ab ? wt : T(kReconstructedApproachCap) * w_ab;
    return vr < T(0) && wt < T(0) ? T(-0.5) * alpha_ab * (c_ab - T(3) * wt) * wt : T(0);
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

} // namespace exasph
