#pragma once
#include <algorithm>
#include <array>
#include <cstdint>

#include "exasph/particles/particle_set.hpp"
#include "exasph/util/block_sum.hpp"

namespace exasph {

// Global conserved quantities and neighbour statistics of one step (SPEC 10).
struct Diagnostics {
    std::int64_t step = 0;
    double time = 0, dt = 0;
    std::uint64_t n = 0;
    double ekin = 0, eint = 0, epot = 0, etot = 0;
    std::array<double, 3> momentum{};
    std::array<double, 3> angular_momentum{}; // about the origin
    double nc_min = 0, nc_mean = 0, nc_max = 0;
};

// Sums over all particles, independent of the thread count (block_sum).
template <class T>
Diagnostics measure_conserved(const ParticleSet<T>& ps) {
    const T *x = ps.data(Field::x), *y = ps.data(Field::y), *z = ps.data(Field::z);
    const T *vx = ps.data(Field::vx), *vy = ps.data(Field::vy), *vz = ps.data(Field::vz);
    const T *m = ps.data(Field::m), *u = ps.data(Field::u), *nc = ps.data(Field::nc);
    auto s = block_sum<9>(ps.size(), [&](std::size_t i) -> std::array<double, 9> {
        double mi = m[i];
        double v2 = double(vx[i]) * vx[i] + double(vy[i]) * vy[i] + double(vz[i]) * vz[i];
        return {0.5 * mi * v2,
                mi * u[i],
                mi * vx[i],
                mi * vy[i],
                mi * vz[i],
                mi * (double(y[i]) * vz[i] - double(z[i]) * vy[i]),
                mi * (double(z[i]) * vx[i] - double(x[i]) * vz[i]),
                mi * (double(x[i]) * vy[i] - double(y[i]) * vx[i]),
                double(nc[i])};
    });
    Diagnostics d;
    d.n = ps.size();
    d.ekin = s[0];
    d.eint = s[1];
    d.etot = d.ekin + d.eint + d.epot;
    d.momentum = {s[2], s[3], s[4]};
    d.angular_momentum = {s[5], s[6], s[7]};
    if (ps.size() > 0) {
        auto [lo, hi] = std::minmax_element(ps[Field::nc].begin(), ps[Field::nc].end());
        d.nc_min = *lo;
        d.nc_max = *hi;
        d.nc_mean = s[8] / double(ps.size());
    }
    return d;
}

} // namespace exasph
