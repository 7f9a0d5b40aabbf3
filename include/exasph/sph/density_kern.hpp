#pragma once
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/density_simd.hpp"
#include "exasph/sph/eos.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

template <class T>
struct DensityResult {
    T rho;
    T kx; // k_a = sum_b X_b W_ab(h_a): the volume-element normalisation (= rho when X = m)
    T omega;
    std::uint32_t nc; // neighbours with r < 2 h_a, self excluded (physics.md §2)
};

// The pair sums of density_kern: k starts from k0 and the grad-h sum from dh0 (a's own terms).
template <class T>
struct DensityPairSums {
    double k, dh;
    T nc;
};

// Pairs beyond 2 h_a (listed because of h_b) are masked rather than skipped, so that the loop
// vectorises. simdlen(8): left to itself GCC 12 picks 16 doubles per step for this loop (two
// zmm registers per value, spilled, AVX-512 gathers); with 8 it reads the neighbours with scalar
// loads into ymm pairs, 8-16 % faster on Zen 4 (docs/performance-log.md).
// The kernel's polynomials run in N, the precision rho, P/(Omega k^2) and nc are stored in (float
// by default: the pass 22 % faster on Sedov, docs/performance-log.md; each term errs by up to 3e-7
// of w(0), 1.4e-6 in the grad-h term, from float's rounding of v^2, test_kernel); the distances
// and the sums stay in T, so the results do not depend on the order of the neighbours beyond
// T's round-off (ranks and threads agree).
template <class T, class N, class Span>
EXASPH_HD DensityPairSums<T> density_pairs_portable(std::uint32_t a, Span nb,
                                                    const ParticleView<T, N>& p, const Box<T>& box,
                                                    const KernelView<T>& k, double k0, double dh0) {
    const T *x = p[Field::x], *y = p[Field::y], *z = p[Field::z];
    const T* xm = p[Field::xm] ? p[Field::xm] : p[Field::m]; // standard SPH: X = m
    const T ha = p[Field::h][a];
    const T inv_h2 = T(1) / (ha * ha);
    double k_sum = k0, dh_sum = dh0;
    T nc = 0; // counted in T: one type in the simd reductions (GCC rejects mixed ones)
    const KernelPoly<N>& w_poly = k.template w_in<N>();
    const KernelPoly<N>& gradh_poly = k.template gradh_in<N>();
    const PeriodicImage<T> image(box);
#pragma omp simd simdlen(8) reduction(+ : k_sum, dh_sum, nc)
    for (std::uint32_t n = 0; n < nb.count; ++n) {
        std::uint32_t b = nb[n];
        T dx = image(x[b] - x[a], 0);
        T dy = image(y[b] - y[a], 1);
        T dz = image(z[b] - z[a], 2);
        const N s = N(squared_norm(dx, dy, dz) * inv_h2); // v^2
        T inside = T(s < N(4));
        nc += inside;
        T xb = xm[b] * inside;
        k_sum += xb * T(w_poly(s));
        dh_sum += xb * T(gradh_poly(s));
    }
    return {k_sum, dh_sum, nc};
}

// The pair sums, with AVX2 or AVX-512 where the build targets it (the portable loop's arithmetic,
// lane for lane: sph/density_simd.hpp).
template <class T, class N, class Span>
EXASPH_HD DensityPairSums<T> density_pairs(std::uint32_t a, Span nb, const ParticleView<T, N>& p,
                                           const Box<T>& box, const KernelView<T>& k, double k0,
                                           double dh0) {
#ifdef EXASPH_SIMD_LANES
    if constexpr (std::is_same_v<T, double> && std::is_same_v<N, float> &&
                  std::is_same_v<Span, ContiguousSpan>) {
        const simd::DensitySums s = simd::DensityPairs<simd::Native>(a, p, box, k).sum(nb);
        return {k0 + s.k, dh0 + s.dh, T(s.nc)};
    }
#endif
    return density_pairs_portable(a, nb, p, box, k, k0, dh0);
}

// physics.md §3 with generalised volume elements (Hopkins 2013; Cabezon et al. 2017): every
// particle carries a weight X (X = m gives standard SPH exactly), k_a = sum_b X_b W_ab(h_a)
// including b = a, V_a = X_a / k_a, rho_a = m_a / V_a, and the grad-h term Omega_a = 1 - 1/(3 k_a
// h_a^3) sum_b X_b (3 w(v) + v w'(v)). Both terms come from the kernel's polynomials in v^2
// (KernelPoly): no square root and no table gathers per pair.
template <class T, class N, class Span>
EXASPH_HD DensityResult<T> density_kern(std::uint32_t a, Span nb, const ParticleView<T, N>& p,
                                        const Box<T>& box, const KernelView<T>& k) {
    // Standard SPH carries no X field: X = m.
    const T* xm = p[Field::xm] ? p[Field::xm] : p[Field::m];
    const T ha = p[Field::h][a];
    const T w0 = k.w_sq(T(0));
    const DensityPairSums<T> s = density_pairs(a, nb, p, box, k, xm[a] * w0, xm[a] * T(3) * w0);
    T h3 = ha * ha * ha;
    T kx = static_cast<T>(s.k) / h3;
    T rho = kx * (p[Field::m][a] / xm[a]); // m/X = 1 exactly for standard SPH
    T omega = T(1) - static_cast<T>(s.dh) / (T(3) * kx * h3);
    return {rho, kx, omega, std::uint32_t(s.nc)};
}

// The density pass of one particle (physics.md §3 and 4): rho, nc (and k with volume elements),
// then P and c from the equation of state, and the pressure-force coefficient P / (Omega k^2) of
// physics.md §6 that momentum-energy reads for both members of a pair (Omega itself is not stored:
// one float array and one division per pair less). With `capture_rho0` (Tait, first step) the
// density becomes the reference density rho0 first.
template <class T, class N = float>
struct DensityEosKernel {
    ParticleView<T, N> p;
    Box<T> box;
    KernelView<T> k;
    EosParams eos;
    bool capture_rho0 = false;

    template <class Span>
    EXASPH_HD void operator()(ParticleIndex i, Span nb) const {
        auto r = density_kern(i, nb, p, box, k);
        const N rho = N(r.rho); // N: float, or T with --double-precision (is_narrow)
        p.narrow(Field::rho)[i] = rho;
        if (p[Field::kx]) p[Field::kx][i] = r.kx;
        p.narrow(Field::nc)[i] = N(r.nc);
        if (capture_rho0) p[Field::rho0][i] = T(rho);
        auto e = eos.kind == EosKind::tait
                     ? tait_eos(T(rho), p[Field::rho0][i], p[Field::p0][i], T(eos.c0))
                     : ideal_gas_eos(T(rho), p[Field::u][i], T(eos.gamma));
        p.narrow(Field::p)[i] = N(e.p);
        p.narrow(Field::c)[i] = N(e.c);
        // k = rho for standard SPH (the stored value, as the pair terms read it)
        const T kk = p[Field::kx] ? r.kx : T(rho);
        p.narrow(Field::pgrad)[i] = N(e.p / (r.omega * kk * kk));
        // With gravity: dh/dk / Omega, which the softening correction's zeta multiplies
        if (p[Field::gsoft]) p[Field::gsoft][i] = -p[Field::h][i] / (T(3) * kk * r.omega);
    }
};

} // namespace exasph
