#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_matrix.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/util/box.hpp"

// The artificial stress (Monaghan 2000) against the tensile instability: where P < 0, pairs
// closer than about the mean spacing dp repel with eps |P/(Om k^2)| f_ab^n, f_ab = W(r)/W(dp).
namespace exasph {

// A particle's stress coefficient R from its pressure term q = P/(Om k^2): eps |q| under
// tension, eps_positive q under compression (Monaghan 2000 applies a small stress for P > 0
// too). Repulsive either way.
template <class T>
EXASPH_HD EXASPH_INLINE T stress_coefficient(T q, T eps, T eps_positive) {
    return q < T(0) ? -eps * q : eps_positive * q;
}

// f_ab^n with f_ab = (W(r/h_a) + W(r/h_b)) / (2 W(dp)) from the kernel table's values (no 1/h^3:
// the ratio is a shape, symmetric in a and b). n in [1, 15], by squaring with a fixed trip count
// so that the pair loops still vectorise.
template <class T>
EXASPH_HD EXASPH_INLINE T stress_weight(T kwa, T kwb, T inv_w0, int n) {
    T power = T(0.5) * (kwa + kwb) * inv_w0;
    T fn = T(1);
    for (int bit = 0; bit < 4; ++bit) {
        if ((n >> bit) & 1) fn *= power;
        power *= power;
    }
    return fn;
}

// The stress's matrix (--tensile-stress with --torque-free): particle a's stress term in the
// momentum equation, X_b f_ab^n R_a M_a d W_ab(h_a), exerts no net torque when M_a tau'_a is
// symmetric, with tau'_a = sum_b X_b f_ab^n d (x) d W_ab(h_a) its weights' second moment
// (sum_b w_b d x (M d) = eps_ijk (M tau')_kj). The pressure's C_a gives C_a tau'_a with an
// antisymmetric part (the square patch drifted 0.3 % in L_z with f^8); M_a = sym(C_a tau'_a)
// tau'_a^-1 removes just that part, and is C_a wherever C_a and tau'_a commute (isotropic
// neighbours, or tau' a multiple of tau), so the repulsion keeps its strength and its
// concentration on close pairs. (C'_a = tau'_a^-1 itself is torque-free too, but normalises the
// f^n weighting away: a close pair then repels no more than a far one, and the square patch
// blew up by t = 0.06.) M is not symmetric: nine components, row-major.
template <class T>
struct StressMatrix {
    T m[9];
    bool singular;
};

template <class T, class N, class Span>
EXASPH_HD StressMatrix<T> stress_matrix_kern(std::uint32_t a, Span nb, const ParticleView<T, N>& p,
                                             const Box<T>& box, const KernelView<T>& k, T inv_w0,
                                             int n, const IadResult<T>& c) {
    const T *x = p[Field::x], *y = p[Field::y], *z = p[Field::z], *h = p[Field::h];
    const T* xm = p[Field::xm] ? p[Field::xm] : p[Field::m];
    const T inv_ha = T(1) / h[a], inv_ha2 = inv_ha * inv_ha;
    const PeriodicImage<T> image(box);
    T t11 = 0, t12 = 0, t13 = 0, t22 = 0, t23 = 0, t33 = 0;
#pragma omp simd reduction(+ : t11, t12, t13, t22, t23, t33)
    for (std::uint32_t i = 0; i < nb.count; ++i) {
        const std::uint32_t b = nb[i];
        const T dx = image(x[b] - x[a], 0), dy = image(y[b] - y[a], 1), dz = image(z[b] - z[a], 2);
        const T r2 = squared_norm(dx, dy, dz); // as momentum-energy computes it
        // W evaluated as momentum-energy evaluates it (KernelView::w_at in N), so that M and the
        // force that uses it see the same f_ab.
        const T inv_hb = T(1) / h[b];
        const T kwa = k.template w_at<N>(r2, inv_ha2),
                kwb = k.template w_at<N>(r2, inv_hb * inv_hb);
        const T w = xm[b] * stress_weight(kwa, kwb, inv_w0, n) * kwa;
        add_second_moment(t11, t12, t13, t22, t23, t33, dx, dy, dz, w);
    }
    // M is invariant to the scale of tau' (no 1/h^3, no 1/k_a needed).
    const T tau[9] = {t11, t12, t13, t12, t22, t23, t13, t23, t33};
    const IadResult<T> ti = invert_symmetric3(t11, t12, t13, t22, t23, t33);
    const T inv[9] = {ti.c11, ti.c12, ti.c13, ti.c12, ti.c22, ti.c23, ti.c13, ti.c23, ti.c33};
    const T cm[9] = {c.c11, c.c12, c.c13, c.c12, c.c22, c.c23, c.c13, c.c23, c.c33};
    T ct[9], sym[9];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            ct[3 * i + j] =
                cm[3 * i] * tau[j] + cm[3 * i + 1] * tau[3 + j] + cm[3 * i + 2] * tau[6 + j];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) sym[3 * i + j] = T(0.5) * (ct[3 * i + j] + ct[3 * j + i]);
    StressMatrix<T> out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out.m[3 * i + j] =
                sym[3 * i] * inv[j] + sym[3 * i + 1] * inv[3 + j] + sym[3 * i + 2] * inv[6 + j];
    out.singular = ti.singular;
    return out;
}

// M (x) d for particle i's stress matrix (stored in T).
template <class T, class N>
EXASPH_HD EXASPH_INLINE IadProduct<T> stress_matrix_times(const ParticleView<T, N>& p,
                                                          std::uint32_t i, T dx, T dy, T dz) {
    T r[3];
    for (int row = 0; row < 3; ++row)
        r[row] = p[stress_matrix_field(3 * row)][i] * dx +
                 p[stress_matrix_field(3 * row + 1)][i] * dy +
                 p[stress_matrix_field(3 * row + 2)][i] * dz;
    return {r[0], r[1], r[2]};
}

} // namespace exasph
