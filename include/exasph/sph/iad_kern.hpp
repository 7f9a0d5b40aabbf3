#pragma once
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_matrix.hpp"
#include "exasph/sph/iad_simd.hpp"
#include "exasph/sph/reduction.hpp"
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
// (physics.md §5) of each velocity component, exact for a linear velocity field.
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

// The sums of physics.md §5's IAD pass (IadSums) over a's neighbours, with V_b = X_b / k_b, or X_b
// / k_a with kOwnK; kGrad: D_a as well.
template <bool kGrad, bool kOwnK, class T, class K, class N, class Span>
EXASPH_HD IadSums<T> iad_sums_portable(std::uint32_t a, Span nb, const ParticleView<T, N>& p,
                                       const Box<T>& box, const KernelView<T>& k, const K* kx) {
    const T *x = p[Field::x], *y = p[Field::y], *z = p[Field::z];
    const T *vx = p[Field::vx], *vy = p[Field::vy], *vz = p[Field::vz];
    // Standard SPH carries no X field: X = m, so X_b / k_b = m_b / rho_b.
    const T* xm = p[Field::xm] ? p[Field::xm] : p[Field::m];
    const T inv_h = T(1) / p[Field::h][a];
    const T inv_h2 = inv_h * inv_h;
    const T inv_ka = kOwnK ? T(1) / T(kx[a]) : T(1);
    T t11 = 0, t12 = 0, t13 = 0, t22 = 0, t23 = 0, t33 = 0;
    T dxx = 0, dxy = 0, dxz = 0, dyx = 0, dyy = 0, dyz = 0, dzx = 0, dzy = 0, dzz = 0;
    // Pairs beyond 2 h_a have W = 0 (KernelPoly is 0 there): no test needed. One kernel
    // evaluation per pair serves both sums: w at v^2 in N as momentum-energy evaluates it
    // (KernelView::w_at: the same W in C_a and in the gradients it corrects, physics.md §5).
    // Vectorised: with the contiguous span and the options as template parameters (no select of
    // indices) the loop runs 10-20 % faster than the scalar one it replaced, and simdlen(8) (as in
    // the density pass: 8 doubles per step in ymm pairs) another 10-18 % (docs/performance-log.md).
    const PeriodicImage<T> image(box);
#pragma omp simd simdlen(8) \
    reduction(+ : t11, t12, t13, t22, t23, t33, dxx, dxy, dxz, dyx, dyy, dyz, dzx, dzy, dzz)
    for (std::uint32_t n = 0; n < nb.count; ++n) {
        const std::uint32_t b = nb[n];
        const T dx = image(x[b] - x[a], 0);
        const T dy = image(y[b] - y[a], 1);
        const T dz = image(z[b] - z[a], 2);
        const T vol = kOwnK ? xm[b] * inv_ka : xm[b] / T(kx[b]);
        const T vw = vol * k.template w_at<N>(squared_norm(dx, dy, dz), inv_h2);
        add_second_moment(t11, t12, t13, t22, t23, t33, dx, dy, dz, vw);
        if constexpr (kGrad) {
            const T wx = (vx[b] - vx[a]) * vw, wy = (vy[b] - vy[a]) * vw, wz = (vz[b] - vz[a]) * vw;
            dxx += wx * dx, dxy += wx * dy, dxz += wx * dz;
            dyx += wy * dx, dyy += wy * dy, dyz += wy * dz;
            dzx += wz * dx, dzy += wz * dy, dzz += wz * dz;
        }
    }
    return {{t11, t12, t13, t22, t23, t33}, {dxx, dxy, dxz, dyx, dyy, dyz, dzx, dzy, dzz}};
}

// The sums, with AVX2 or AVX-512 where the build targets it (sph/iad_simd.hpp: the portable
// loop's arithmetic lane for lane).
template <bool kGrad, bool kOwnK, class T, class K, class N, class Span>
EXASPH_HD IadSums<T> iad_sums(std::uint32_t a, Span nb, const ParticleView<T, N>& p,
                              const Box<T>& box, const KernelView<T>& k, const K* kx) {
#ifdef EXASPH_SIMD_LANES
    if constexpr (!kOwnK && std::is_same_v<T, double> && std::is_same_v<N, float> &&
                  std::is_same_v<Span, ContiguousSpan>)
        return simd::IadPairs<simd::Native, kGrad, K>(a, p, box, k, kx).sum(nb);
#endif
    return iad_sums_portable<kGrad, kOwnK>(a, nb, p, box, k, kx);
}

// physics.md §5, with the volume V_b = X_b / k_b (= m_b / rho_b for standard SPH):
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
    const IadSums<T> m = grad ? (own_k ? iad_sums<true, true>(a, nb, p, box, k, kx)
                                       : iad_sums<true, false>(a, nb, p, box, k, kx))
                              : (own_k ? iad_sums<false, true>(a, nb, p, box, k, kx)
                                       : iad_sums<false, false>(a, nb, p, box, k, kx));
    // W = w / h^3: the 1/h^3 factor is applied once here instead of per pair.
    const T inv_h = T(1) / p[Field::h][a];
    const T s = inv_h * inv_h * inv_h;
    const T* t = m.t;
    IadResult<T> c = invert_symmetric3(t[0] * s, t[1] * s, t[2] * s, t[3] * s, t[4] * s, t[5] * s);
    if (grad) {
        T d[9];
        for (int i = 0; i < 9; ++i) d[i] = m.d[i] * s;
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
// viscosity. Returns i where tau_a is singular (the launcher's reduction names the first such
// particle).
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
    using Reduction = FirstIndexWhere;

    template <class Span>
    EXASPH_HD FoundIndex operator()(ParticleIndex i, Span nb) const {
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
        return r.singular ? FoundIndex::at(i) : FoundIndex::none();
    }
};

} // namespace exasph
