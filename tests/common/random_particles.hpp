#pragma once
#include <cstdint>
#include <random>

#include "exasph/particles/particle_set.hpp"
#include "exasph/util/box.hpp"

namespace exasph::testref {

// `side`^3 particles on a lattice at cell centres of the unit-density periodic box [0, side)^3
// (spacing 1, mass 1), h from the SPEC 9.1 rule for ng0 neighbours.
inline ParticleSet<double> periodic_lattice(int side, double ng0, Box<double>& box) {
    box.lo = {0, 0, 0};
    box.hi = {double(side), double(side), double(side)};
    box.periodic = {true, true, true};
    ParticleSet<double> ps;
    std::uint64_t n1 = side, n = n1 * n1 * n1;
    ps.resize(n);
    double h0 = 0.5 * std::cbrt(3.0 * ng0 / (4.0 * M_PI));
    for (std::uint64_t idx = 0; idx < n; ++idx) {
        ps.id[idx] = idx;
        ps[Field::x][idx] = double(idx / (n1 * n1)) + 0.5;
        ps[Field::y][idx] = double((idx / n1) % n1) + 0.5;
        ps[Field::z][idx] = double(idx % n1) + 0.5;
        ps[Field::m][idx] = 1.0;
        ps[Field::h][idx] = h0;
    }
    return ps;
}

// Moves every particle by up to `amp` per axis and wraps it back into the periodic box.
inline void perturb_positions(ParticleSet<double>& ps, const Box<double>& box, double amp,
                              std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-amp, amp);
    for (std::size_t i = 0; i < ps.size(); ++i)
        for (int d = 0; d < 3; ++d) {
            double& x = ps[static_cast<Field>(int(Field::x) + d)][i];
            x += u(rng);
            x += box.wrap_shift(x, d);
        }
}

} // namespace exasph::testref
