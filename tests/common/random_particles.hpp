#pragma once
#include <cstdint>
#include <random>

#include "exasph/particles/particle_set.hpp"
#include "exasph/util/box.hpp"

namespace exasph::testref {

// `side`^3 particles on a lattice at cell centres of the unit-density periodic box [0, side)^3
// (spacing 1, mass 1), h from the physics.md §9.1 rule for ng0 neighbours.
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

// The unit cube [0, 1)^3, periodic on every axis or open.
inline Box<double> unit_box(bool periodic) {
    Box<double> box;
    box.lo = {0, 0, 0};
    box.hi = {1, 1, 1};
    box.periodic = {periodic, periodic, periodic};
    return box;
}

// n particles uniformly at random in the unit cube, ids first_id + i, h uniform in
// [h_lo, h_hi); per particle x, y, z and h are drawn in that order from one generator.
inline ParticleSet<double> random_cube(std::uint32_t n, std::uint64_t seed, double h_lo,
                                       double h_hi, std::uint64_t first_id = 0) {
    ParticleSet<double> ps;
    ps.resize(n);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0), hs(h_lo, h_hi);
    for (std::uint32_t i = 0; i < n; ++i) {
        ps.id[i] = first_id + i;
        ps[Field::x][i] = u(rng);
        ps[Field::y][i] = u(rng);
        ps[Field::z][i] = u(rng);
        ps[Field::h][i] = hs(rng);
    }
    return ps;
}

} // namespace exasph::testref
