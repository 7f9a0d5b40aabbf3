#pragma once
#include <cmath>
#include <vector>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/util/annotate.hpp"
#include "exasph/util/field_memory.hpp"

namespace exasph {

// Gravity of a particle whose mass is spread like the SPH kernel (physics.md §8: softened inside
// 2h). With q = r/h and M(q) = 4 pi \int_0^q w(s) s^2 ds the mass fraction inside q:
//   acceleration  a = -G m F(q) r_vec / h^3,  F(q) = M(q) / q^3   (= 1/q^3 for q >= 2)
//   potential     phi = -G m psi(q) / h,      psi(q) = M(q)/q + 4 pi \int_q^2 w(s) s ds  (= 1/q)
// Both are tabulated on [0, 2] and interpolated linearly; outside they are the point-mass laws.
template <class T>
struct SofteningView {
    const T* force;
    const T* potential;
    T inv_dq;
    int size;

    EXASPH_HD EXASPH_INLINE void eval(T q, T& f, T& psi) const {
        if (q >= T(2)) {
            T iq = T(1) / q;
            psi = iq;
            f = iq * iq * iq;
            return;
        }
        T s = q * inv_dq;
        int i = static_cast<int>(s);
        if (i > size - 2) i = size - 2;
        T t = s - T(i);
        f = force[i] + t * (force[i + 1] - force[i]);
        psi = potential[i] + t * (potential[i + 1] - potential[i]);
    }
};

template <class T>
class SofteningTable {
  public:
    static constexpr int kSize = 4096;
    static constexpr int kSubsteps = 16; // Simpson sub-intervals per table cell

    // `kernel` must be normalised (KernelTable::exact_value): then M(2) = 1.
    explicit SofteningTable(const KernelTable<T>& kernel) : force_(kSize), potential_(kSize) {
        const double dq = 2.0 / (kSize - 1);
        std::vector<double> mass(kSize, 0.0), outer(kSize, 0.0);
        auto w = [&](double s) { return kernel.exact_value(s); };
        for (int i = 1; i < kSize; ++i) {
            mass[i] =
                mass[i - 1] + simpson([&](double s) { return w(s) * s * s; }, (i - 1) * dq, i * dq);
        }
        for (int i = kSize - 2; i >= 0; --i)
            outer[i] =
                outer[i + 1] + simpson([&](double s) { return w(s) * s; }, i * dq, (i + 1) * dq);
        const double four_pi = 4.0 * M_PI;
        for (int i = 0; i < kSize; ++i) {
            const double q = i * dq, m = four_pi * mass[i];
            force_[i] = T(i == 0 ? four_pi * w(0.0) / 3.0 : m / (q * q * q));
            potential_[i] = T((i == 0 ? 0.0 : m / q) + four_pi * outer[i]);
        }
        enclosed_ = four_pi * mass[kSize - 1];
    }

    SofteningView<T> view() const {
        return {force_.data(), potential_.data(), T(kSize - 1) / T(2), kSize};
    }
    // M(2): 1 up to quadrature error (a test checks it).
    double enclosed_mass() const { return enclosed_; }

  private:
    template <class F>
    static double simpson(F f, double a, double b) {
        const double h = (b - a) / kSubsteps;
        double s = f(a) + f(b);
        for (int k = 1; k < kSubsteps; ++k) s += (k % 2 ? 4.0 : 2.0) * f(a + k * h);
        return s * h / 3.0;
    }

    FieldArray<T> force_, potential_; // read by the kernels, on a device too
    double enclosed_ = 0;
};

} // namespace exasph
