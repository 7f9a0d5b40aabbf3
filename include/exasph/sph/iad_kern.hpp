#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_matrix.hpp"
#include "exasph/sph/tensile_stress.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// The IAD velocity gradient G_ij = dv_i/dx_j, row-major.
template <class T>
struct VelocityGradient {
    T g[9];
};

// G_a = D_a C_a with D_a = sum_b V_b (v_b - v_a) (x) (x_b - x_a) W_ab(h_a): the IAD gradient
// (SPEC 5) of each velocity component, exact for a linear velocity field.
template <class T>
EXASPH_HD VelocityGradient<T> velocity_gradient(const T (&d)[9], const IadResult<T>& c) {
    const T cm[9] = {c.c11, c.c12, c.c13, c.c12, c.c22, c.c23, c.c13, c.c23, c.c33};
    VelocityGradient<T> out;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out.g[3 * i + j] =
                d[3 * i] * cm[j] + d[3 * i + 1] * cm[3 + j] + d[3 * i + 2] * cm[6 + j];
    return out;
}

// The strain rate S = (G + G^T) / 2 as S_11, S_12, S_13, S_22, S_23, S_33 (strain_rate_field):
// the reconstructed viscosity reads G only through d.G.d = d.S.d.
template <class T>
struct StrainRate {
    T e[6];
};
template <class T>
EXASPH_HD StrainRate<T> strain_rate(const VelocityGradient<T>& v) {
    const T* g = v.g;
    return {
        {g[0], T(0.5) * (g[1] + g[3]), T(0.5) * (g[2] + g[6]), g[4], T(0.5) * (g[5] + g[7]), g[8]}};
}

// SPEC 5, with the volume V_b = X_b / k_b (= m_b / rho_b for standard SPH):
// tau_a = sum_b V_b (x_b - x_a) (x) (x_b - x_a) W_ab(h_a), C_a = tau_a^{-1}.
// With a non-null `grad`, the same pass also yields the velocity gradient (velocity_gradient).
// `kx`: k_b, the volume-element field, or rho_b (stored in N, is_narrow) for standard SPH.
// `own_k` (--torque-free): V_b = X_b / k_a, the weights of particle a's pressure term in the
// momentum equation (X_b P_a/(Om_a k_a^2) C_a d W), so that sum_b X_b d x (C_a d) W vanishes with
// C_a tau_a = I: the IAD pressure forces exert no net torque. Still exact for linear fields.
template <class T, class K, class N, class Span>
EXASPH_HD IadResult<T> iad_kern_with(std::uint32_t a, Span nb, const ParticleView<T, N>& p,
                                     const Box<T>& box, const KernelView<T>& k,
                                     VelocityGradient<T>* grad, const K* kx, bool own_k) {
    const T* x = p[Field::x];
    const T* y = p[Field::y];
    const T* z = p[Field::z];
    // Standard SPH carries no X field: X = m, so X_b / k_b = m_b / rho_b.
    const T* xm = p[Field::xm] ? p[Field::xm] : p[Field::m];
    const T ha = p[Field::h][a];
    const T inv_h = T(1) / ha;
    const T *vx = p[Field::vx], *vy = p[Field::vy], *vz = p[Field::vz];
    T t11 = 0, t12 = 0, t13 = 0, t22 = 0, t23 = 0, t33 = 0;
    T d[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    // Pairs beyond 2 h_a have W = 0 (the table is 0 there): no test needed. The velocity
    // gradient's nine sums, wanted only with --av-limiter, join the same loop (one kernel
    // evaluation per pair for both).
    const PeriodicImage<T> image(box);
    auto pair = [&](std::uint32_t b, T& dx, T& dy, T& dz) {
        dx = image(x[b] - x[a], 0);
        dy = image(y[b] - y[a], 1);
        dz = image(z[b] - z[a], 2);
        return xm[b] / T(kx[own_k ? a : b]) *
               k.value(std::sqrt(dx * dx + dy * dy + dz * dz) * inv_h);
    };
    // Scalar loops on purpose: vectorised (gathers for every neighbour field, no select of
    // indices), this pass ran 1.8x slower on this project's Zen 4 machine (docs/performance.md).
    if (!grad) {
        for (std::uint32_t n = 0; n < nb.count; ++n) {
            T dx, dy, dz;
            T vw = pair(nb[n], dx, dy, dz); // V_b W_ab(h_a)
            add_second_moment(t11, t12, t13, t22, t23, t33, dx, dy, dz, vw);
        }
    } else {
        for (std::uint32_t n = 0; n < nb.count; ++n) {
            const std::uint32_t b = nb[n];
            T dx, dy, dz;
            T vw = pair(b, dx, dy, dz);
            add_second_moment(t11, t12, t13, t22, t23, t33, dx, dy, dz, vw);
            const T dv[3] = {vx[b] - vx[a], vy[b] - vy[a], vz[b] - vz[a]};
            for (int i = 0; i < 3; ++i) {
                d[3 * i] += dv[i] * dx * vw;
                d[3 * i + 1] += dv[i] * dy * vw;
                d[3 * i + 2] += dv[i] * dz * vw;
            }
        }
    }
    // W = w / h^3: the 1/h^3 factor is applied once here instead of per pair.
    T s = inv_h * inv_h * inv_h;
    IadResult<T> c = invert_symmetric3(t11 * s, t12 * s, t13 * s, t22 * s, t23 * s, t33 * s);
    if (grad) {
        for (T& di : d) di *= s;
        *grad = velocity_gradient(d, c);
    }
    return c;
}

template <class T, class N, class Span>
EXASPH_HD IadResult<T> iad_kern(std::uint32_t a, Span nb, const ParticleView<T, N>& p,
                                const Box<T>& box, const KernelView<T>& k,
                                VelocityGradient<T>* grad = nullptr, bool own_k = false) {
    return p[Field::kx] ? iad_kern_with(a, nb, p, box, k, grad, p[Field::kx], own_k)
                        : iad_kern_with(a, nb, p, box, k, grad, p.narrow(Field::rho), own_k);
}

// The IAD pass of one particle: C_a stored in N (is_narrow: float, or T with --double-precision),
// `with_gradient` also the strain rate (Field::e11..e33, in N) for the reconstructed artificial
// viscosity. Returns i where tau_a is singular, else +infinity (the launcher's minimum names the
// first such particle).
template <class T, class N = float>
struct IadKernel {
    ParticleView<T, N> p;
    Box<T> box;
    KernelView<T> k;
    bool with_gradient = false;
    bool own_k = false; // --torque-free
    // The artificial stress's matrix M (Field::s11..s33; with own_k): 1 / W(dp) and the
    // exponent of f_ab (tensile_stress.hpp); 0: none.
    T stress_inv_w0 = T(0);
    int stress_exponent = 4;

    template <class Span>
    EXASPH_HD double operator()(std::uint32_t i, Span nb) const {
        VelocityGradient<T> g;
        auto r = iad_kern(i, nb, p, box, k, with_gradient ? &g : nullptr, own_k);
        if (stress_inv_w0 > T(0)) {
            const auto s = stress_matrix_kern(i, nb, p, box, k, stress_inv_w0, stress_exponent, r);
            for (int c = 0; c < 9; ++c) p[stress_matrix_field(c)][i] = s.m[c];
            r.singular = r.singular || s.singular;
        }
        if (with_gradient) {
            const StrainRate<T> e = strain_rate(g);
            for (int c = 0; c < 6; ++c) p.narrow(strain_rate_field(c))[i] = N(e.e[c]);
        }
        p.narrow(Field::c11)[i] = N(r.c11);
        p.narrow(Field::c12)[i] = N(r.c12);
        p.narrow(Field::c13)[i] = N(r.c13);
        p.narrow(Field::c22)[i] = N(r.c22);
        p.narrow(Field::c23)[i] = N(r.c23);
        p.narrow(Field::c33)[i] = N(r.c33);
        return r.singular ? double(i) : 1e300;
    }
};

} // namespace exasph
