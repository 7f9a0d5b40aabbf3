#pragma once
#include <cmath>

#include "exasph/util/annotate.hpp"

namespace exasph {

// An even function of v = r/h on the kernel's support [0, 2] as a polynomial in s = v^2 (in the
// variable t = s/2 - 1, which maps the support onto [-1, 1]): a pair loop evaluates it from
// r^2/h^2 with multiply-adds, without the square root and the four table gathers (two per
// linear interpolation, from tables that do not fit L1) of KernelView::value/derivative. Every
// hydro pass evaluates W this way (density: w and the grad-h term, 10-12 % faster on Sedov; IAD,
// the stress matrix and momentum-energy: w, IAD 19 % faster, docs/performance-log.md): the IAD
// matrix and the gradients it corrects must use the same W (physics.md §5: exact for linear
// fields). A sinc kernel with an integer exponent is an entire function of s: the degree-20
// Chebyshev interpolant is exact to rounding for n <= 8 (w and the grad-h term within 5e-13 of
// w(0), unit test), 8e-11 for n = 10, 4e-9 for n = 12, against the table's interpolation error of
// ~1e-9 (dv^2/8 |w''|). A non-integer n has a (2 - v)^n end that no polynomial follows as closely:
// 1.3e-7 of w(0) for n = 3.5. In single precision (the pair loops with float derived fields) 16
// terms suffice: evaluated in float at float v^2, the degree-15 interpolant is within 1.0e-6 /
// 1.3e-6 / 1.6e-6 of w(0) for n = 4 / 6 / 8, as the degree-20 one (float arithmetic sets that
// error: the rounding of t), 4e-6 for n = 10 and 2.6e-5 for n = 12 (the grad-h term; 21 terms: 2e-6
// and 2.5e-6), far below the kernel's discretisation error. Five multiply-adds less per evaluation,
// in every pair loop (Sedov std: density 6 %, IAD 8 %, momentum-energy 5 % faster on Zen 2).
template <class T>
inline constexpr int kPolyTerms = sizeof(T) < sizeof(double) ? 16 : 21;

// a b + c, fused (one rounding) wherever the hardware has FMA, explicitly: left to the
// compiler, the vectorised body of a pair loop and its scalar remainder may contract different
// products, and a pair's two members (one in each) would then see W differing by an ulp; in
// single precision that breaks the pair terms' antisymmetry at 1e-10 of the momentum.
template <class T>
EXASPH_HD EXASPH_INLINE T mul_add(T a, T b, T c) {
#if defined(__CUDA_ARCH__) || defined(__FMA__)
    return std::fma(a, b, c);
#else
    return a * b + c; // no FMA: nothing to contract either
#endif
}

// |d|^2 with the same roundings in every loop and lane (mul_add).
template <class T>
EXASPH_HD EXASPH_INLINE T squared_norm(T dx, T dy, T dz) {
    return mul_add(dz, dz, mul_add(dy, dy, dx * dx));
}

template <class T>
struct KernelPoly {
    static constexpr int kTerms = kPolyTerms<T>;
    T c[kTerms]; // power series in t

    // The function at s = v^2; 0 at and beyond v = 2 and for a NaN s (a product and a select,
    // not a branch, so that pair loops vectorise).
    EXASPH_HD EXASPH_INLINE T operator()(T s) const {
        // Estrin's scheme: levels of independent multiply-adds instead of Horner's chain of
        // twenty (whose latency bound the loop, and its scalar remainder, when tried).
        const T t = (s < T(4) ? s : T(4)) * T(0.5) - T(1); // finite for any s, NaN included
        const T t2 = t * t, t4 = t2 * t2, t8 = t4 * t4;
        const T p0 = mul_add(c[1], t, c[0]), p1 = mul_add(c[3], t, c[2]);
        const T p2 = mul_add(c[5], t, c[4]), p3 = mul_add(c[7], t, c[6]);
        const T p4 = mul_add(c[9], t, c[8]), p5 = mul_add(c[11], t, c[10]);
        const T p6 = mul_add(c[13], t, c[12]), p7 = mul_add(c[15], t, c[14]);
        const T q0 = mul_add(p1, t2, p0), q1 = mul_add(p3, t2, p2);
        const T q2 = mul_add(p5, t2, p4), q3 = mul_add(p7, t2, p6);
        const T o0 = mul_add(q1, t4, q0), o1 = mul_add(q3, t4, q2);
        T acc;
        if constexpr (kTerms == 16) {
            acc = mul_add(o1, t8, o0);
        } else {
            static_assert(kTerms == 21, "Estrin's scheme written out for 16 and 21 terms");
            const T p8 = mul_add(c[17], t, c[16]), p9 = mul_add(c[19], t, c[18]);
            const T q4 = mul_add(p9, t2, p8);
            const T o2 = mul_add(c[20], t4, q4);
            acc = mul_add(o2, t8 * t8, mul_add(o1, t8, o0));
        }
        return acc * T(s < T(4));
    }
};

// The Chebyshev interpolant of g(v) (an even function, given on [0, 2]) at kTerms Chebyshev
// nodes of t, converted to the power basis in t (the coefficients stay below 1 for the sinc
// family, so evaluating in powers of t loses nothing to cancellation).
template <class T, class G>
KernelPoly<T> fit_kernel_poly(G g) {
    constexpr int n = KernelPoly<T>::kTerms;
    double cheb[n] = {};
    for (int j = 0; j < n; ++j) {
        double sum = 0;
        for (int k = 0; k < n; ++k) {
            const double theta = M_PI * (k + 0.5) / n;
            const double v = std::sqrt(2.0 * (std::cos(theta) + 1.0));
            sum += g(v) * std::cos(j * theta);
        }
        cheb[j] = sum * 2.0 / n;
    }
    cheb[0] *= 0.5;
    // sum_j cheb_j T_j(t) in powers of t: T_0 = 1, T_1 = t, T_{j+1} = 2 t T_j - T_{j-1}.
    double power[n] = {}, prev[n] = {}, cur[n] = {}, next[n] = {};
    prev[0] = 1;
    cur[1] = 1;
    power[0] = cheb[0];
    for (int i = 0; i < n; ++i) power[i] += cheb[1] * cur[i];
    for (int j = 2; j < n; ++j) {
        for (int i = 0; i < n; ++i) next[i] = (i > 0 ? 2 * cur[i - 1] : 0.0) - prev[i];
        for (int i = 0; i < n; ++i) {
            power[i] += cheb[j] * next[i];
            prev[i] = cur[i];
            cur[i] = next[i];
        }
    }
    KernelPoly<T> p{};
    for (int i = 0; i < n; ++i) p.c[i] = static_cast<T>(power[i]);
    return p;
}

} // namespace exasph
