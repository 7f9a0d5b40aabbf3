#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "exasph/kernel/kernel_table.hpp"

namespace exasph {

// The kernel integrated along a line of sight: a particle of smoothing length h adds
// F(R/h) / h^2 per unit of its (volume x quantity) to the column through a point at projected
// distance R, with F(q) = \int w(sqrt(q^2 + s^2)) ds over the support (W = w(v) / h^3, physics.md
// §1), so that 2 pi \int_0^2 F(q) q dq = 1. Tabulated at kSize points of q in [0, 2] (Simpson rule
// on the exact kernel), read by linear interpolation.
class ProjectedKernel {
  public:
    static constexpr int kSize = 2000;

    explicit ProjectedKernel(const KernelTable<double>& k) : f_(kSize) {
        constexpr int kIntervals = 400; // even: Simpson
        for (int i = 0; i < kSize; ++i) {
            const double q = 2.0 * i / (kSize - 1);
            const double smax = std::sqrt(std::max(0.0, 4.0 - q * q));
            const double ds = smax / kIntervals;
            double sum = 0;
            for (int j = 0; j <= kIntervals; ++j) {
                const double weight = (j == 0 || j == kIntervals) ? 1 : (j % 2 ? 4 : 2);
                const double s = j * ds;
                sum += weight * k.exact_value(std::sqrt(q * q + s * s));
            }
            f_[i] = 2.0 * sum * ds / 3.0; // both halves of the chord
        }
    }

    double operator()(double q) const {
        if (!(q < 2.0)) return 0.0;
        const double s = q * (kSize - 1) / 2.0;
        const int i = std::min(int(s), kSize - 2);
        return f_[i] + (s - i) * (f_[i + 1] - f_[i]);
    }

  private:
    std::vector<double> f_;
};

} // namespace exasph
