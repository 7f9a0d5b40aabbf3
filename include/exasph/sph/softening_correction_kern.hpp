#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/kernel/softening.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/tree/neighbour_span.hpp"

// The softening follows h (physics.md §8: each pair softened with h_ab = (h_a + h_b)/2), so
// E_pot = 1/2 sum_ab G m_a m_b phi(r_ab, h_ab) also changes when h does, and without a force
// doing the matching work that change is lost from E_tot (Evrard -n 16: -2.6 % of E_pot at the
// bounce, where h shrinks fastest). The correction of Price & Monaghan (2007), for pair
// softening: dE_pot/dh_a = m_a zeta_a with
//   zeta_a = G/2 sum_b m_b dphi/dh(r_ab, h_ab),   dphi/dh = (psi(q) - q^2 F(q)) / h^2, q = r/h
// (psi, F of softening.hpp; 0 beyond q = 2). With h_a following k_a (h ~ k^-1/3, physics.md §2-3),
// dh_a/dt = -h_a / (3 k_a Omega_a) sum_b X_b v_ab . grad_a W_ab(h_a), so with
// xi_a = -zeta_a h_a / (3 k_a Omega_a) the pair force
//   a_a -= sum_b [X_b xi_a grad_a W_ab(h_a) + (m_b X_a / m_a) xi_b grad_a W_ab(h_b)]
// does the work -dE_pot/dt through h and is antisymmetric (momentum stays conserved).
namespace exasph {

// dphi/dh of a unit-mass pair (G = 1) at distance r with softening length h.
template <class T>
EXASPH_HD EXASPH_INLINE T softening_dphi_dh(T r, T h, const SofteningView<T>& soft) {
    const T q = r / h;
    if (q >= T(2)) return T(0);
    T f, psi;
    soft.eval(q, f, psi);
    return (psi - q * q * f) / (h * h);
}

// xi_a = zeta_a * (the factor -h_a / (3 k_a Omega_a) the density pass left in Field::gsoft).
template <class T, class N>
struct SofteningZetaKernel {
    ParticleView<T, N> p;
    SofteningView<T> soft;
    T G;

    template <class Span>
    EXASPH_HD void operator()(std::uint32_t a, Span nb) const {
        const T *x = p[Field::x], *y = p[Field::y], *z = p[Field::z];
        const T *h = p[Field::h], *m = p[Field::m];
        double sum = 0;
        for (std::uint32_t n = 0; n < nb.count; ++n) {
            const std::uint32_t b = nb[n];
            const T dx = x[b] - x[a], dy = y[b] - y[a], dz = z[b] - z[a];
            const T r = std::sqrt(dx * dx + dy * dy + dz * dz);
            sum += double(m[b]) * double(softening_dphi_dh(r, T(0.5) * (h[a] + h[b]), soft));
        }
        p[Field::gsoft][a] *= T(0.5) * G * T(sum);
    }
};

// Adds the correction force to Field::ax..az (xi of the halos exchanged with the density).
template <class T, class N>
struct SofteningForceKernel {
    ParticleView<T, N> p;
    KernelView<T> k;

    template <class Span>
    EXASPH_HD void operator()(std::uint32_t a, Span nb) const {
        const T *x = p[Field::x], *y = p[Field::y], *z = p[Field::z];
        const T *h = p[Field::h], *m = p[Field::m], *xi = p[Field::gsoft];
        const T* xm = p[Field::xm] ? p[Field::xm] : m; // X = m for standard SPH
        const T inv_ha = T(1) / h[a], inv_ha4 = inv_ha * inv_ha * inv_ha * inv_ha;
        const T xa_ma = xm[a] / m[a], xi_a = xi[a];
        T ax = 0, ay = 0, az = 0;
#pragma omp simd reduction(+ : ax, ay, az)
        for (std::uint32_t n = 0; n < nb.count; ++n) {
            const std::uint32_t b = nb[n];
            const T dx = x[a] - x[b], dy = y[a] - y[b], dz = z[a] - z[b]; // r_ab
            const T r = std::sqrt(dx * dx + dy * dy + dz * dz);
            const T inv_hb = T(1) / h[b], inv_hb4 = inv_hb * inv_hb * inv_hb * inv_hb;
            // |grad_a W_ab(h)| = w'(r/h) / h^4 along r_ab / r
            const T ga = k.derivative(r * inv_ha) * inv_ha4;
            const T gb = k.derivative(r * inv_hb) * inv_hb4;
            const T s = (xm[b] * xi_a * ga + m[b] * xa_ma * xi[b] * gb) / (r > T(0) ? r : T(1));
            ax -= s * dx;
            ay -= s * dy;
            az -= s * dz;
        }
        p[Field::ax][a] += ax;
        p[Field::ay][a] += ay;
        p[Field::az][a] += az;
    }
};

} // namespace exasph
