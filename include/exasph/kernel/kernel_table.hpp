#pragma once
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "exasph/kernel/kernel_poly.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/field_memory.hpp"

namespace exasph {

// Read-only view of a tabulated kernel w(v), v = r/h in [0, 2], with W(r, h) = w(v) / h^3.
// Linear interpolation between kSize equally spaced entries (physics.md §1: no sin/pow in inner
// loops).
template <class T>
struct KernelView {
    const T* w;  // w(v_i)
    const T* dw; // dw/dv(v_i)
    T inv_dv;    // (kSize - 1) / 2
    int size;
    KernelPoly<T> w_sq;     // w as a polynomial in v^2
    KernelPoly<T> gradh_sq; // 3 w + v dw/dv (the grad-h sum's term, physics.md §3) in v^2
    // The same two in single precision: pair loops whose results are stored in float (the
    // derived fields' default storage) evaluate them in float, twice the lanes per instruction.
    KernelPoly<float> w_sq_f, gradh_sq_f;

    // w_sq / gradh_sq in the pair arithmetic's precision P (float or T).
    template <class P>
    EXASPH_HD EXASPH_INLINE const KernelPoly<P>& w_in() const {
        if constexpr (std::is_same_v<P, T>)
            return w_sq;
        else
            return w_sq_f;
    }
    template <class P>
    EXASPH_HD EXASPH_INLINE const KernelPoly<P>& gradh_in() const {
        if constexpr (std::is_same_v<P, T>)
            return gradh_sq;
        else
            return gradh_sq_f;
    }
    // w at v^2 = r^2 (1/h)^2 in precision P: momentum-energy and the artificial stress's matrix
    // evaluate a pair's two W this way, so that both members of the pair, and M and the force
    // that uses it, see the same value to the bit.
    template <class P>
    EXASPH_HD EXASPH_INLINE T w_at(T r2, T inv_h2) const {
        return T(w_in<P>()(P(r2 * inv_h2)));
    }

    // Branch-free, so that neighbour loops calling it vectorise: the index is clamped and the
    // value multiplied by 0 at and beyond v = 2 (a select there makes GCC move the table loads
    // into a branch, which it then cannot vectorise).
    // The index is clamped as unsigned, so that any v (huge or NaN from a corrupted particle,
    // whose conversion gives INT_MIN) reads inside the table.
    EXASPH_HD EXASPH_INLINE T lookup(const T* table, T v) const {
        T s = v * inv_dv;
        int i = static_cast<int>(s);
        int j = unsigned(i) < unsigned(size - 2) ? i : size - 2;
        T f = s - T(i);
        T w = table[j] + f * (table[j + 1] - table[j]);
        return w * T(s < T(size - 1));
    }
    EXASPH_HD EXASPH_INLINE T value(T v) const { return lookup(w, v); }
    EXASPH_HD EXASPH_INLINE T derivative(T v) const { return lookup(dw, v); }
};

// A kernel shape f(v) on [0, 2] and its derivative, before normalisation. A new kernel is a new
// pair of functions; the table, its normalisation and every SPH loop stay the same.
struct KernelShape {
    double (*f)(double v, double param);
    double (*df)(double v, double param);
    double param; // e.g. the sinc exponent n
};

// Normalisation B with 4 pi B \int_0^2 f(v) v^2 dv = 1 (physics.md §1), by composite Simpson
// quadrature on 2e5 intervals: the integrand is smooth, so the error is far below 1e-12.
inline double kernel_normalisation(const KernelShape& k) {
    constexpr int kIntervals = 200000;
    const double dv = 2.0 / kIntervals;
    double sum = 0.0;
    for (int i = 0; i <= kIntervals; ++i) {
        double v = i * dv;
        double weight = (i == 0 || i == kIntervals) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += weight * k.f(v, k.param) * v * v;
    }
    double integral = sum * dv / 3.0;
    return 1.0 / (4.0 * M_PI * integral);
}

// Owns the tables of one normalised kernel.
template <class T>
class KernelTable {
  public:
    static constexpr int kSize = 20000;

    explicit KernelTable(const KernelShape& shape) : shape_(shape), w_(kSize), dw_(kSize) {
        norm_ = kernel_normalisation(shape);
        for (int i = 0; i < kSize; ++i) {
            double v = 2.0 * i / (kSize - 1);
            w_[i] = static_cast<T>(norm_ * shape.f(v, shape.param));
            dw_[i] = static_cast<T>(norm_ * shape.df(v, shape.param));
        }
        w_sq_ = fit_kernel_poly<T>([&](double v) { return exact_value(v); });
        const auto gradh = [&](double v) { return 3 * exact_value(v) + v * exact_derivative(v); };
        gradh_sq_ = fit_kernel_poly<T>(gradh);
        w_sq_f_ = fit_kernel_poly<float>([&](double v) { return exact_value(v); });
        gradh_sq_f_ = fit_kernel_poly<float>(gradh);
    }

    KernelView<T> view() const {
        return {w_.data(), dw_.data(), T(kSize - 1) / T(2), kSize, w_sq_,
                gradh_sq_, w_sq_f_,    gradh_sq_f_};
    }
    double normalisation() const { return norm_; }
    // Direct (non-tabulated) evaluation, for tests and set-up code.
    double exact_value(double v) const { return v >= 2 ? 0 : norm_ * shape_.f(v, shape_.param); }
    double exact_derivative(double v) const {
        return v >= 2 ? 0 : norm_ * shape_.df(v, shape_.param);
    }

  private:
    KernelShape shape_;
    double norm_ = 0;
    FieldArray<T> w_, dw_; // read by the kernels, on a device too
    KernelPoly<T> w_sq_{}, gradh_sq_{};
    KernelPoly<float> w_sq_f_{}, gradh_sq_f_{};
};

} // namespace exasph
