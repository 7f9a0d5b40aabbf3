#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/kernel/kernel_poly.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/util/annotate.hpp"

// The IAD matrix (physics.md §5): its inversion and its product with a pair's separation.
namespace exasph {

// The six independent components of the symmetric IAD matrix C_a = tau_a^{-1}.
template <class T>
struct IadResult {
    T c11, c12, c13, c22, c23, c33;
    bool singular;
};

// The sums of physics.md §5's IAD pass over a's neighbours: tau_a's six moments
// sum_b V_b d (x) d w(r / h_a) and, with the velocity gradient, D_a's nine
// sum_b V_b (v_b - v_a) (x) d w (both still to be divided by h_a^3), d = x_b - x_a.
template <class T>
struct IadSums {
    T t[6];
    T d[9];
};

// Inverse of a symmetric 3x3 matrix by its adjugate. Reports singular when |det| is below a
// tiny fraction of the scale (trace/3)^3, i.e. when neighbours are too few or coplanar.
template <class T>
EXASPH_HD IadResult<T> invert_symmetric3(T t11, T t12, T t13, T t22, T t23, T t33) {
    T a11 = t22 * t33 - t23 * t23;
    T a12 = t13 * t23 - t12 * t33;
    T a13 = t12 * t23 - t13 * t22;
    T det = t11 * a11 + t12 * a12 + t13 * a13;
    T scale = (t11 + t22 + t33) / T(3);
    bool singular = !(std::abs(det) > T(1e-12) * scale * scale * scale);
    T inv = singular ? T(0) : T(1) / det;
    return {a11 * inv,
            a12 * inv,
            a13 * inv,
            (t11 * t33 - t13 * t13) * inv,
            (t12 * t13 - t11 * t23) * inv,
            (t11 * t22 - t12 * t12) * inv,
            singular};
}

// Adds w d (x) d to the six sums of a symmetric second moment (tau, physics.md §5). Inlined into
// the vectorised pair loops, whose omp simd reductions are on the six scalars.
template <class T>
EXASPH_HD EXASPH_INLINE void add_second_moment(T& t11, T& t12, T& t13, T& t22, T& t23, T& t33, T dx,
                                               T dy, T dz, T w) {
    t11 += dx * dx * w;
    t12 += dx * dy * w;
    t13 += dx * dz * w;
    t22 += dy * dy * w;
    t23 += dy * dz * w;
    t33 += dz * dz * w;
}

// C (x) d for the symmetric IAD matrix of particle i.
template <class T>
struct IadProduct {
    T x, y, z;
};
// The stored C's six fields (float, or T with --double-precision), taken from the view once
// before a pair loop: read through the view inside the loop, their bases are loads GCC does
// not hoist, and it then cannot vectorise the loop with AVX2's emulated gathers.
template <class N>
struct IadMatrixFields {
    const N *c11, *c12, *c13, *c22, *c23, *c33;

    template <class T>
    EXASPH_HD explicit IadMatrixFields(const ParticleView<T, N>& p)
        : c11(p.narrow(Field::c11)), c12(p.narrow(Field::c12)), c13(p.narrow(Field::c13)),
          c22(p.narrow(Field::c22)), c23(p.narrow(Field::c23)), c33(p.narrow(Field::c33)) {}

    // C_i (x) d, the products in T, with explicit multiply-adds: C can be ill-conditioned (few or
    // one-sided neighbours) and its rows then cancel, so every loop (and the AVX2 one,
    // sph/momentum_energy_avx2.hpp) rounds them alike.
    template <class T>
    EXASPH_HD EXASPH_INLINE IadProduct<T> times(std::uint32_t i, T dx, T dy, T dz) const {
        const T m11 = c11[i], m12 = c12[i], m13 = c13[i], m22 = c22[i], m23 = c23[i], m33 = c33[i];
        return {mul_add(m13, dz, mul_add(m12, dy, m11 * dx)),
                mul_add(m23, dz, mul_add(m22, dy, m12 * dx)),
                mul_add(m33, dz, mul_add(m23, dy, m13 * dx))};
    }
};

} // namespace exasph
