#pragma once
#include <cmath>
#include <vector>

#include "exasph/particles/particle_set.hpp"

namespace exasph::testref {

// Mean density in radial bins of `width` out to rmax, at the positions the density was computed
// at (x_{n-1} after the update), of the first n particles.
struct RadialProfile {
    double width = 0;
    std::vector<double> sum, count;

    int bins() const { return int(sum.size()); }
    double mean(int b) const { return sum[b] / count[b]; }
    double centre(int b) const { return (b + 0.5) * width; }
};

inline RadialProfile radial_density(const ParticleSet<double>& ps, std::size_t n, double rmax,
                                    int bins) {
    RadialProfile p{rmax / bins, std::vector<double>(bins, 0), std::vector<double>(bins, 0)};
    for (std::size_t i = 0; i < n; ++i) {
        const double x = ps[Field::x_m1][i], y = ps[Field::y_m1][i], z = ps[Field::z_m1][i];
        const int b = int(std::sqrt(x * x + y * y + z * z) / rmax * bins);
        if (b >= bins) continue;
        p.sum[b] += ps.value(Field::rho, i);
        p.count[b] += 1;
    }
    return p;
}

} // namespace exasph::testref
