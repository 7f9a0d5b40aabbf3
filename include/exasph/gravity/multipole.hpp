#pragma once
#include <cmath>

#include "exasph/util/annotate.hpp"

namespace exasph {

// Monopole, traceless quadrupole and octupole of a group of particles about its centre of mass
// (physics.md §8 asks for at least the quadrupole; the octupole makes the error fall as theta^4,
// which the force-accuracy acceptance needs at theta = 0.5 where the forces nearly cancel):
//   Q_ij  = sum_k m_k (3 d_i d_j - |d|^2 delta_ij),  d = x_k - com,
//   S_ijk = sum_k m_k d_i d_j d_k (raw; the field formula below applies the trace terms),
//   d2    = sum_k m_k |d|^2 (needed to shift the octupole to a parent's centre).
// q = {Q_xx, Q_xy, Q_xz, Q_yy, Q_yz, Q_zz}; s in the order of kOctupoleIndex. Double precision
// whatever T is: the moments of large nodes are sums of many terms.
struct Multipole {
    double mass = 0;
    double com[3] = {0, 0, 0};
    double q[6] = {0, 0, 0, 0, 0, 0};
    double s[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0}; // xxx xxy xxz xyy xyz xzz yyy yyz yzz zzz
    double d2 = 0;
};

// Position of S_ijk in Multipole::s.
inline constexpr int kOctupoleIndex[3][3][3] = {{{0, 1, 2}, {1, 3, 4}, {2, 4, 5}},
                                                {{1, 3, 4}, {3, 6, 7}, {4, 7, 8}},
                                                {{2, 4, 5}, {4, 7, 8}, {5, 8, 9}}};

// Adds m d_i d_j d_k to s.
EXASPH_HD inline void add_octupole(double* s, double m, double dx, double dy, double dz) {
    const double mx = m * dx, my = m * dy, mz = m * dz;
    s[0] += mx * dx * dx;
    s[1] += mx * dx * dy;
    s[2] += mx * dx * dz;
    s[3] += mx * dy * dy;
    s[4] += mx * dy * dz;
    s[5] += mx * dz * dz;
    s[6] += my * dy * dy;
    s[7] += my * dy * dz;
    s[8] += my * dz * dz;
    s[9] += mz * dz * dz;
}

// Adds 3 d d^T - |d|^2 I, times m, to q.
EXASPH_HD inline void add_quadrupole(double* q, double m, double dx, double dy, double dz) {
    const double d2 = dx * dx + dy * dy + dz * dz;
    q[0] += m * (3 * dx * dx - d2);
    q[1] += m * (3 * dx * dy);
    q[2] += m * (3 * dx * dz);
    q[3] += m * (3 * dy * dy - d2);
    q[4] += m * (3 * dy * dz);
    q[5] += m * (3 * dz * dz - d2);
}

// Multipole of particles [b, e) of the arrays x, y, z, m.
template <class T>
Multipole particle_multipole(const T* x, const T* y, const T* z, const T* m, std::size_t b,
                             std::size_t e) {
    Multipole mp;
    double sx = 0, sy = 0, sz = 0;
    for (std::size_t k = b; k < e; ++k) {
        mp.mass += m[k];
        sx += double(m[k]) * x[k];
        sy += double(m[k]) * y[k];
        sz += double(m[k]) * z[k];
    }
    if (mp.mass <= 0) return mp;
    mp.com[0] = sx / mp.mass;
    mp.com[1] = sy / mp.mass;
    mp.com[2] = sz / mp.mass;
    for (std::size_t k = b; k < e; ++k) {
        const double dx = x[k] - mp.com[0], dy = y[k] - mp.com[1], dz = z[k] - mp.com[2];
        add_quadrupole(mp.q, m[k], dx, dy, dz);
        add_octupole(mp.s, m[k], dx, dy, dz);
        mp.d2 += m[k] * (dx * dx + dy * dy + dz * dz);
    }
    return mp;
}

// Multipole of the union of `n` groups: each part's moments shifted to the new centre of mass.
// With t = com_part - com and the part's raw second moment I = (Q + d2 delta) / 3:
//   Q += M (3 t t - |t|^2 delta),  S_ijk += t_i I_jk + t_j I_ik + t_k I_ij + M t_i t_j t_k,
//   d2 += M |t|^2 (the parts' first moments about their own centres vanish).
inline Multipole combine_multipoles(const Multipole* parts, int n) {
    Multipole mp;
    double sx = 0, sy = 0, sz = 0;
    for (int c = 0; c < n; ++c) {
        mp.mass += parts[c].mass;
        sx += parts[c].mass * parts[c].com[0];
        sy += parts[c].mass * parts[c].com[1];
        sz += parts[c].mass * parts[c].com[2];
    }
    if (mp.mass <= 0) return mp;
    mp.com[0] = sx / mp.mass;
    mp.com[1] = sy / mp.mass;
    mp.com[2] = sz / mp.mass;
    for (int c = 0; c < n; ++c) {
        const Multipole& p = parts[c];
        if (p.mass <= 0) continue;
        const double t[3] = {p.com[0] - mp.com[0], p.com[1] - mp.com[1], p.com[2] - mp.com[2]};
        for (int k = 0; k < 6; ++k) mp.q[k] += p.q[k];
        for (int k = 0; k < 10; ++k) mp.s[k] += p.s[k];
        add_quadrupole(mp.q, p.mass, t[0], t[1], t[2]);
        add_octupole(mp.s, p.mass, t[0], t[1], t[2]);
        const double t2 = t[0] * t[0] + t[1] * t[1] + t[2] * t[2];
        mp.d2 += p.d2 + p.mass * t2;
        const double raw[6] = {(p.q[0] + p.d2) / 3, p.q[1] / 3, p.q[2] / 3,
                               (p.q[3] + p.d2) / 3, p.q[4] / 3, (p.q[5] + p.d2) / 3};
        constexpr int q_index[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
        for (int i = 0; i < 3; ++i)
            for (int j = i; j < 3; ++j)
                for (int k = j; k < 3; ++k)
                    mp.s[kOctupoleIndex[i][j][k]] += t[i] * raw[q_index[j][k]] +
                                                     t[j] * raw[q_index[i][k]] +
                                                     t[k] * raw[q_index[i][j]];
    }
    return mp;
}

// Field of a multipole at displacement d = x - com (|d| > 0), with G = 1 (Legendre expansion of
// 1/|d - d_k| to third order):
//   phi = -M/r - d.Q.d / (2 r^5) - (5 A / r^7 - 3 B / r^5) / 2,  A = S_ijk d_i d_j d_k,
//         B = T.d, T_i = S_ijj,
//   a = -grad phi = -M d/r^3 + Q.d/r^5 - 5/2 (d.Q.d) d / r^7
//       + (15 (S:dd) / r^7 - 35 A d / r^9 - 3 T / r^5 + 15 B d / r^7) / 2.
struct GravityField {
    double ax = 0, ay = 0, az = 0, phi = 0;
};

EXASPH_HD EXASPH_INLINE void add_field(GravityField& f, const GravityField& g) {
    f.ax += g.ax;
    f.ay += g.ay;
    f.az += g.az;
    f.phi += g.phi;
}

// The terms of one multipole at displacement d; q(c) and s(c) return the components c of the
// quadrupole and octupole in the order of Multipole (accessors, so that the same code reads a
// Multipole or a column of packed moments inside a vectorised loop).
template <class Q, class S>
EXASPH_HD EXASPH_INLINE GravityField multipole_field(double mass, Q q, S s, double dx, double dy,
                                                     double dz) {
    const double r2 = dx * dx + dy * dy + dz * dz;
    const double inv_r = 1.0 / std::sqrt(r2);
    const double inv_r2 = inv_r * inv_r;
    const double inv_r3 = inv_r * inv_r2;
    const double inv_r5 = inv_r3 * inv_r2;
    const double qx = q(0) * dx + q(1) * dy + q(2) * dz;
    const double qy = q(1) * dx + q(3) * dy + q(4) * dz;
    const double qz = q(2) * dx + q(4) * dy + q(5) * dz;
    const double dqd = dx * qx + dy * qy + dz * qz;
    // S:dd (vector), A and T from the ten octupole components.
    const double sx = s(0) * dx * dx + 2 * s(1) * dx * dy + 2 * s(2) * dx * dz + s(3) * dy * dy +
                      2 * s(4) * dy * dz + s(5) * dz * dz;
    const double sy = s(1) * dx * dx + 2 * s(3) * dx * dy + 2 * s(4) * dx * dz + s(6) * dy * dy +
                      2 * s(7) * dy * dz + s(8) * dz * dz;
    const double sz = s(2) * dx * dx + 2 * s(4) * dx * dy + 2 * s(5) * dx * dz + s(7) * dy * dy +
                      2 * s(8) * dy * dz + s(9) * dz * dz;
    const double a3 = sx * dx + sy * dy + sz * dz;
    const double tx = s(0) + s(3) + s(5), ty = s(1) + s(6) + s(8), tz = s(2) + s(7) + s(9);
    const double b3 = tx * dx + ty * dy + tz * dz;
    const double inv_r7 = inv_r5 * inv_r2;
    const double radial =
        -mass * inv_r3 - 2.5 * dqd * inv_r7 - 17.5 * a3 * inv_r7 * inv_r2 + 7.5 * b3 * inv_r7;
    GravityField f;
    f.ax = radial * dx + qx * inv_r5 + 7.5 * sx * inv_r7 - 1.5 * tx * inv_r5;
    f.ay = radial * dy + qy * inv_r5 + 7.5 * sy * inv_r7 - 1.5 * ty * inv_r5;
    f.az = radial * dz + qz * inv_r5 + 7.5 * sz * inv_r7 - 1.5 * tz * inv_r5;
    f.phi = -(mass * inv_r + 0.5 * dqd * inv_r5 + 2.5 * a3 * inv_r7 - 1.5 * b3 * inv_r5);
    return f;
}

EXASPH_HD inline void add_multipole_field(const Multipole& mp, double dx, double dy, double dz,
                                          GravityField& f) {
    add_field(f, multipole_field(
                     mp.mass, [&](int c) { return mp.q[c]; }, [&](int c) { return mp.s[c]; }, dx,
                     dy, dz));
}

} // namespace exasph
