#pragma once
#include <cmath>
#include <cstdint>
#include <numbers>
#include <type_traits>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/momentum_energy_simd.hpp"
#include "exasph/sph/pair_dissipation.hpp"
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

// physics.md §6 with IAD gradients, with a per-particle alpha (physics.md §6's "later switch")
// (physics.md §5), over a symmetric neighbour list (r_ab < 2 max(h_a, h_b)), which makes every
// pair's contribution appear with opposite sign in b's sum: momentum is conserved to round-off and
// energy up to time-integration error.
//   A_ab(h_a) = C_a (x_b - x_a) W_ab(h_a),  A_ab(h_b) = C_b (x_b - x_a) W_ab(h_b)
//   dv_a/dt = -sum_b m_b [P_a/(Om_a rho_a^2) A_ab(h_a) + P_b/(Om_b rho_b^2) A_ab(h_b)]
//             (with volume elements: -sum_b (X_a X_b / m_a) [P_a/(Om_a k_a^2) A_ab(h_a) + ...])
//             -1/2 sum_b m_b Pi_ab [A_ab(h_a)/rho_a + A_ab(h_b)/rho_b]
//   du_a/dt = P_a/(Om_a rho_a^2) sum_b m_b v_ab . A_ab(h_a)
//             +1/4 sum_b m_b Pi_ab v_ab . [A_ab(h_a)/rho_a + A_ab(h_b)/rho_b]
// kTerms: the options the loop carries (PairTerms). kAlphaField: alpha per particle (the AV
// switch, which also wants the velocity divergence), else the constant diss.alpha (divv is
// then not computed). kVolumeElements: X and k are fields; without them X = m is read once per
// neighbour (not twice through an aliased pointer) and X_a / m_a = 1. P/(Om k^2) comes
// precomputed per particle (Field::pgrad, set by the density pass).
template <class T, PairTerms kTerms = PairTerms::any, bool kAlphaField = true,
          bool kVolumeElements = true, class N, class Span>
EXASPH_HD MomentumEnergyResult<T>
momentum_energy_portable(std::uint32_t a, Span nb, const ParticleView<T, N>& p, const Box<T>& box,
                         const KernelView<T>& k, const Dissipation<T>& diss = {}) {
    constexpr bool kExtras = kTerms != PairTerms::plain;
    constexpr bool kLimited = kTerms == PairTerms::limited; // the limiter on, no stress
    const T alpha_u = diss.alpha_u;
    const T *x = p[Field::x], *y = p[Field::y], *z = p[Field::z];
    const T *vx = p[Field::vx], *vy = p[Field::vy], *vz = p[Field::vz];
    const T *h = p[Field::h], *m = p[Field::m];
    // Stored in N (is_narrow): rho, c, P/(Omega k^2) (and P) of both members of a pair come
    // from the same stored values, so the pair terms stay antisymmetric.
    const N *rho = p.narrow(Field::rho), *pr = p.narrow(Field::p), *c = p.narrow(Field::c),
            *pgrad = p.narrow(Field::pgrad);
    const T* alpha = p[Field::alpha];
    const T ha = h[a], inv_ha = T(1) / ha, inv_ha2 = inv_ha * inv_ha, inv_ha3 = inv_ha2 * inv_ha;
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
    constexpr bool kAny = kTerms == PairTerms::any;
    const T eps_ts = kAny ? diss.tensile : T(0);
    const T eps_pos = kAny ? diss.tensile_positive : T(0);
    const T ra = stress_coefficient(pa, eps_ts, eps_pos);
    const T inv_w0 = kAny ? diss.stress_inv_w0(k) : T(0);
    const int n_ts = diss.tensile_exponent;
    const bool own_stress_matrix = kAny && diss.stress_matrix;
    const bool stress_on = kAny && diss.stress(); // the schemes without it skip its pair work
    T du_ts = 0;
    const T* u = p[Field::u];
    T ea[6] = {0, 0, 0, 0, 0, 0}; // the strain rate S_a, with the limiter
    const N* strain[6] = {};      // its fields
    if (kExtras && diss.reconstruct)
        for (int e = 0; e < 6; ++e) {
            strain[e] = p.narrow(strain_rate_field(e));
            ea[e] = strain[e][a];
        }
    const IadMatrixFields<N> cmat(p);
    const PeriodicImage<T> image(box);
    // simdlen(8): on AVX2 GCC 12 emulates the gathers, and only with as many lanes as a vector
    // of the 32-bit indices (8) does it accept the float fields' ones; with its own choice (4
    // doubles) the loop stayed scalar there (2x slower on Zen 2, docs/performance-log.md).
#pragma omp simd simdlen(8) reduction(+ : ax, ay, az, du_p, du_av, divv, du_cond, du_ts) \
    reduction(max : vsig_max)
    for (std::uint32_t n = 0; n < nb.count; ++n) {
        const std::uint32_t b = nb[n];
        // d = x_b - x_a = -r_ab
        T dx = image(x[b] - x[a], 0);
        T dy = image(y[b] - y[a], 1);
        T dz = image(z[b] - z[a], 2);
        T r2 = squared_norm(dx, dy, dz); // as the stress matrix computes it
        T r = std::sqrt(r2);
        // 1/r once for the pair's divisions by r (0 for r = 0, where every numerator is 0)
        T inv_r = r > T(0) ? T(1) / r : T(0);
        T hb = h[b], inv_hb = T(1) / hb;
        T va = r * inv_ha, vb = r * inv_hb;
        // w in N (float by default: 9-11 % faster on Sedov, docs/performance-log.md), 1/h squared
        // before it multiplies r^2 for both members, so a and b compute the same w_ab(h) to the bit
        T kwa = k.template w_at<N>(r2, inv_ha2), kwb = k.template w_at<N>(r2, inv_hb * inv_hb);
        T wa = kwa * inv_ha3;
        T wb = kwb * inv_hb * inv_hb * inv_hb;
        IadProduct<T> ca = cmat.times(a, dx, dy, dz);
        IadProduct<T> cb = cmat.times(b, dx, dy, dz);
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
        // Every pair, without a branch (limited_viscosity is 0 unless the pair approaches):
        // kLimited's loop then vectorises.
        if (kLimited || (kAny && diss.reconstruct)) {
            T eb[6];
            for (int e = 0; e < 6; ++e) eb[e] = strain[e][b];
            const T eta = va < vb ? va : vb; // r / max(h_a, h_b)
            pi_ab = limited_viscosity(vr, w_ab, inv_r, dx, dy, dz, ea, eb, eta, diss, alpha_ab,
                                      T(c[a]) + T(c[b]));
        }
        T pb = T(pgrad[b]) * xa_ma;
        T inv_rho_b = T(1) / T(rho[b]);
        T mb = m[b];
        T gx = aax * inv_rho_a + abx * inv_rho_b; // A(h_a)/rho_a + A(h_b)/rho_b
        T gy = aay * inv_rho_a + aby * inv_rho_b;
        T gz = aaz * inv_rho_a + abz * inv_rho_b;
        if (kAny && diss.central) { // --torque-free: viscosity along the pair axis
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
        if (kLimited || (kExtras && alpha_u > T(0))) {
            // Artificial conductivity (Price 2008): heat flows from hot to cold along the pair,
            // with signal speed sqrt(|P_a - P_b| / rho_ab) and |grad W| ~ A_bar . d / r, both
            // symmetric in a and b, so sum_a m_a du_a/dt stays zero. (With kLimited on every
            // pair, times alpha_u = 0 where it is off: a branch on alpha_u keeps GCC from
            // vectorising the loop.)
            T inv_rho_bar = T(2) / (rho_a + T(rho[b]));
            T vu = std::sqrt(std::abs(T(pr[a]) - T(pr[b])) * inv_rho_bar);
            T fbar = T(0.5) * ((aax + abx) * dx + (aay + aby) * dy + (aaz + abz) * dz) * inv_r;
            du_cond -= mb * alpha_u * vu * (u[a] - u[b]) * fbar * inv_rho_bar;
        }
    }
    return {ax, ay, az, pa * du_p + ra * du_ts + T(0.25) * du_av + du_cond, vsig_max, divv};
}

// The pass's sums, with AVX2 or AVX-512 for the plain form (standard SPH, constant alpha) and
// the limited one (volume elements, the limiter and the conductivity, constant alpha) where the
// build targets it (sph/momentum_energy_simd.hpp: the same terms, in the same order per pair).
template <class T, PairTerms kTerms = PairTerms::any, bool kAlphaField = true,
          bool kVolumeElements = true, class N, class Span>
EXASPH_HD MomentumEnergyResult<T>
momentum_energy_kern(std::uint32_t a, Span nb, const ParticleView<T, N>& p, const Box<T>& box,
                     const KernelView<T>& k, const Dissipation<T>& diss = {}) {
#ifdef EXASPH_SIMD_PAIRS
    constexpr bool kSimdTypes = std::is_same_v<T, double> && std::is_same_v<N, float> &&
                                std::is_same_v<Span, ContiguousSpan>;
    if constexpr (kTerms == PairTerms::plain && !kAlphaField && !kVolumeElements && kSimdTypes) {
        const auto s = simd::MomentumEnergyPairs<simd::Native, false>(a, p, box, k, diss).sum(nb);
        return {s.ax, s.ay, s.az, s.du, s.vsig_max, T(0)};
    }
    if constexpr (kTerms == PairTerms::limited && !kAlphaField && kVolumeElements && kSimdTypes) {
        const auto s = simd::MomentumEnergyPairs<simd::Native, true>(a, p, box, k, diss).sum(nb);
        return {s.ax, s.ay, s.az, s.du, s.vsig_max, T(0)};
    }
#endif
    return momentum_energy_portable<T, kTerms, kAlphaField, kVolumeElements>(a, nb, p, box, k,
                                                                             diss);
}

// The momentum-energy pass of one particle: a, du/dt (and div v for the AV switch) stored;
// returns the particle's Courant time step (physics.md §7) for the factor `courant`, so that signal
// velocities are used where they are computed, not stored.
template <class T, PairTerms kTerms, bool kAlphaField, bool kVolumeElements, class N = float>
struct MomentumEnergyKernel {
    ParticleView<T, N> p;
    Box<T> box;
    KernelView<T> k;
    Dissipation<T> diss;
    T courant;

    template <class Span>
    EXASPH_HD T operator()(std::uint32_t i, Span nb) const {
        auto r =
            momentum_energy_kern<T, kTerms, kAlphaField, kVolumeElements>(i, nb, p, box, k, diss);
        p[Field::ax][i] = r.ax;
        p[Field::ay][i] = r.ay;
        p[Field::az][i] = r.az;
        p[Field::du][i] = r.du;
        if (p[Field::divv]) p[Field::divv][i] = r.divv;
        return courant_time_step(p[Field::h][i], r.vsig_max, T(p.narrow(Field::c)[i]), courant);
    }
};

} // namespace exasph
