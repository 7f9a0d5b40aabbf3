#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "exasph/gravity/ewald_sum.hpp"
#include "exasph/gravity/multipole.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// The periodic correction of EwaldSum, with its first three derivatives, on a grid over the
// positive octant of the half box [0, L_d / 2] (cubic cells, kIntervals along the shortest
// axis), read by a second-order Taylor expansion about the nearest grid point (one record per
// lookup) and unfolded to the other octants by the symmetries of the box: a component with an odd
// number of x indices changes sign with x, likewise y and z. Measured in test_ewald: the force's
// largest error is 1.4e-4 of the nearest image's Newtonian force at the same distance (1.6e-5
// with 32 intervals, at eight times the table and its build time; the tree's own errors are
// ~1e-3). The table is exactly odd, so a symmetric distribution's errors cancel.
class EwaldTable {
    // A symmetric 3 x 3 matrix and a symmetric rank-3 tensor, by their independent components.
    struct Sym2 {
        double xx, yy, zz, xy, xz, yz;
        EXASPH_HD void times(double u, double v, double w, double& x, double& y, double& z) const {
            x = xx * u + xy * v + xz * w;
            y = xy * u + yy * v + yz * w;
            z = xz * u + yz * v + zz * w;
        }
        EXASPH_HD double dot(const Sym2& o) const {
            return xx * o.xx + yy * o.yy + zz * o.zz + 2 * (xy * o.xy + xz * o.xz + yz * o.yz);
        }
    };
    struct Sym3 {
        double xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz, zzz;
        // c_i = T_ijk M_jk.
        EXASPH_HD void contract(const Sym2& mm, double& x, double& y, double& z) const {
            x = xxx * mm.xx + xyy * mm.yy + xzz * mm.zz +
                2 * (xxy * mm.xy + xxz * mm.xz + xyz * mm.yz);
            y = xxy * mm.xx + yyy * mm.yy + yzz * mm.zz +
                2 * (xyy * mm.xy + xyz * mm.xz + yyz * mm.yz);
            z = xxz * mm.xx + yyz * mm.yy + zzz * mm.zz +
                2 * (xyz * mm.xy + xzz * mm.xz + yzz * mm.yz);
        }
    };

  public:
    static constexpr int kIntervals = 16;

    EwaldTable() = default;
    explicit EwaldTable(std::array<double, 3> L) : len_(L) {
        const EwaldSum sum(L);
        const double shortest = std::min({L[0], L[1], L[2]});
        for (int d = 0; d < 3; ++d) n_[d] = int(std::lround(kIntervals * L[d] / shortest));
        const std::int64_t p0 = n_[0] + 1, p1 = n_[1] + 1, p2 = n_[2] + 1;
        values_.resize(std::size_t(kEwaldValues * p0 * p1 * p2));
#pragma omp parallel for schedule(dynamic, 16)
        for (std::int64_t p = 0; p < p0 * p1 * p2; ++p) {
            const std::int64_t g[3] = {p / (p1 * p2), p / p2 % p1, p % p2};
            double x[3];
            for (int d = 0; d < 3; ++d) x[d] = double(g[d]) * 0.5 * L[d] / n_[d];
            const EwaldRecord r = sum.correction(x[0], x[1], x[2]);
            std::copy(r.begin(), r.end(), values_.begin() + p * kEwaldValues);
        }
    }

    const std::array<double, 3>& lengths() const {
        return len_;
    }

    // Read-only view for the walks. Requires a built table (not the default one).
    struct View {
        const double* values;
        double step[3]; // grid spacing per axis
        int n[3];       // intervals per axis

        // phi_c(0): the potential of a particle's own images and the background, per unit mass.
        EXASPH_HD double phi_at_origin() const { return values[ewald_slot::phi]; }

        // The correction (G = 1) at displacement d (the nearest image, |d_k| <= L_k / 2) of a
        // mass m with traceless quadrupole q(c) (Multipole::q order) and second moment d2m
        // (Multipole::d2) about its centre: Taylor's expansion of phi_c to second order in the
        // mass distribution, a_i = m a_c,i - Q_jk d_ijk phi_c / 6,
        // phi = m phi_c + (Q_jk d_jk phi_c + d2m laplacian(phi_c)) / 6.
        template <class Q>
        EXASPH_HD EXASPH_INLINE GravityField at(double dx, double dy, double dz, double m, Q q,
                                                double d2m) const {
            // Written out component by component (no index loops) so that the walk's loops
            // vectorise.
            const double ux = std::fabs(dx) / step[0], uy = std::fabs(dy) / step[1],
                         uz = std::fabs(dz) / step[2];
            const int gx = std::min(int(ux + 0.5), n[0]), gy = std::min(int(uy + 0.5), n[1]),
                      gz = std::min(int(uz + 0.5), n[2]);
            const double sx = dx < 0 ? -1.0 : 1.0, sy = dy < 0 ? -1.0 : 1.0,
                         sz = dz < 0 ? -1.0 : 1.0;
            const double u = dx - sx * gx * step[0], v = dy - sy * gy * step[1],
                         w = dz - sz * gz * step[2];
            // Indexed loads from one base (gathers), not loads through a pointer moved per lane.
            const int base = kEwaldValues * ((gx * (n[1] + 1) + gy) * (n[2] + 1) + gz);
            const double* t = values;
            const double ax = t[base] * sx, ay = t[base + 1] * sy, az = t[base + 2] * sz;
            const Sym2 hh{t[base + 4],           t[base + 7],           t[base + 9],
                          t[base + 5] * sx * sy, t[base + 6] * sx * sz, t[base + 8] * sy * sz};
            const Sym3 tt{t[base + 10] * sx, t[base + 11] * sy,           t[base + 12] * sz,
                          t[base + 13] * sx, t[base + 14] * sx * sy * sz, t[base + 15] * sx,
                          t[base + 16] * sy, t[base + 17] * sz,           t[base + 18] * sy,
                          t[base + 19] * sz};
            const Sym2 dd{u * u, v * v, w * w, u * v, u * w, v * w};
            const Sym2 qq{q(0), q(3), q(5), q(1), q(2), q(4)};
            double hx, hy, hz, sx3, sy3, sz3, qx, qy, qz;
            hh.times(u, v, w, hx, hy, hz);
            tt.contract(dd, sx3, sy3, sz3);
            tt.contract(qq, qx, qy, qz);
            GravityField f;
            f.ax = m * (ax - hx - 0.5 * sx3) - qx / 6;
            f.ay = m * (ay - hy - 0.5 * sy3) - qy / 6;
            f.az = m * (az - hz - 0.5 * sz3) - qz / 6;
            const double phi = t[base + 3] - (ax * u + ay * v + az * w) +
                               0.5 * (hx * u + hy * v + hz * w) + (sx3 * u + sy3 * v + sz3 * w) / 6;
            f.phi = m * phi + (hh.dot(qq) + d2m * (hh.xx + hh.yy + hh.zz)) / 6;
            return f;
        }

        // The correction of a point mass m.
        EXASPH_HD EXASPH_INLINE GravityField at(double dx, double dy, double dz, double m) const {
            return at(
                dx, dy, dz, m, [](int) { return 0.0; }, 0.0);
        }
    };

    View view() const {
        View v{values_.data(), {0, 0, 0}, {0, 0, 0}};
        for (int d = 0; d < 3; ++d) {
            v.step[d] = n_[d] > 0 ? 0.5 * len_[d] / n_[d] : 0.0;
            v.n[d] = n_[d];
        }
        return v;
    }

  private:
    std::array<double, 3> len_{0, 0, 0};
    std::array<int, 3> n_{0, 0, 0}; // intervals per axis
    std::vector<double> values_;    // EwaldRecord of grid point (i, j, k), k fastest
};

} // namespace exasph
