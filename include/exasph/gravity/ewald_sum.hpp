#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace exasph {

// The correction of periodic gravity and its derivatives at one displacement: phi_c, a_c =
// -grad phi_c, the second derivatives d2_jk = d_j d_k phi_c (xx xy xz yy yz zz) and the third
// d3_ijk = d_i d_j d_k phi_c (in the order of kOctupoleIndex: xxx xxy xxz xyy xyz xzz yyy yyz yzz
// zzz), packed as one record of kEwaldValues numbers.
inline constexpr int kEwaldValues = 20;
namespace ewald_slot {
inline constexpr int a = 0, phi = 3, d2 = 4, d3 = 10;
}
using EwaldRecord = std::array<double, kEwaldValues>;
// The axes of the d2 and d3 components.
inline constexpr int kEwaldPairs[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
inline constexpr int kEwaldTriples[10][3] = {{0, 0, 0}, {0, 0, 1}, {0, 0, 2}, {0, 1, 1}, {0, 1, 2},
                                             {0, 2, 2}, {1, 1, 1}, {1, 1, 2}, {1, 2, 2}, {2, 2, 2}};

// Periodic gravity (physics.md §8): the field of a unit mass at the origin, its periodic replicas
// on the lattice n = (n_x L_x, n_y L_y, n_z L_z) and a uniform background of density -1/V that
// makes the box neutral (Poisson's equation with the mean density removed), G = 1. Ewald's split
// with parameter alpha (Hernquist, Bouchet & Suto 1991, ApJS 75, 231):
//   phi(x) = -sum_n erfc(alpha r_n) / r_n - (4 pi / V) sum_{k != 0} exp(-k^2 / 4 alpha^2) / k^2
//            cos(k.x) + pi / (alpha^2 V),     r_n = |x - n|,  k = 2 pi (h_x/L_x, h_y/L_y, h_z/L_z)
// (the constant makes phi's mean over the box zero). The tree walk takes the nearest image itself
// (Newton, softened); the rest, the correction phi_c(x) = phi(x) + 1/|x| (at 0 its limit), is
// smooth inside the half box. Terms are kept to about 1e-16 of the largest: erfc(alpha r) beyond
// alpha r = 6 and exp(-k^2 / 4 alpha^2) beyond k = 12 alpha are dropped.
class EwaldSum {
  public:
    explicit EwaldSum(std::array<double, 3> L) : len_(L) {
        alpha_ = 2.0 / std::min({L[0], L[1], L[2]});
        const double kmax = 12.0 * alpha_, vol = L[0] * L[1] * L[2];
        int hmax[3];
        for (int d = 0; d < 3; ++d) {
            images_[d] = int(std::ceil(6.0 / (alpha_ * L[d]) + 0.5));
            hmax[d] = int(std::ceil(kmax * L[d] / (2 * M_PI)));
        }
        for (int a = -hmax[0]; a <= hmax[0]; ++a)
            for (int b = -hmax[1]; b <= hmax[1]; ++b)
                for (int c = -hmax[2]; c <= hmax[2]; ++c) {
                    const Wave w{{2 * M_PI * a / L[0], 2 * M_PI * b / L[1], 2 * M_PI * c / L[2]}};
                    const double k2 = w.k[0] * w.k[0] + w.k[1] * w.k[1] + w.k[2] * w.k[2];
                    if (k2 == 0 || k2 > kmax * kmax) continue;
                    waves_.push_back(w);
                    waves_.back().coef =
                        4 * M_PI / vol * std::exp(-k2 / (4 * alpha_ * alpha_)) / k2;
                }
        background_ = M_PI / (alpha_ * alpha_ * vol);
    }

    // phi_c and its derivatives at x (inside the half periods).
    EwaldRecord correction(double x, double y, double z) const {
        EwaldRecord r{};
        const double p[3] = {x, y, z};
        for (int a = -images_[0]; a <= images_[0]; ++a)
            for (int b = -images_[1]; b <= images_[1]; ++b)
                for (int c = -images_[2]; c <= images_[2]; ++c) {
                    const double d[3] = {p[0] - a * len_[0], p[1] - b * len_[1],
                                         p[2] - c * len_[2]};
                    add_image(d, a == 0 && b == 0 && c == 0, r);
                }
        for (const Wave& w : waves_) add_wave(w, p, r);
        r[ewald_slot::phi] += background_;
        return r;
    }

  private:
    struct Wave {
        double k[3];
        double coef = 0; // (4 pi / V) exp(-k^2 / 4 alpha^2) / k^2
    };

    // A radial term f(r) and its derivatives as d_i f = D1 x_i, d_ij f = D2 x_i x_j + D1 delta_ij,
    // d_ijk f = D3 x_i x_j x_k + D2 (delta_ij x_k + delta_ik x_j + delta_jk x_i).
    struct Radial {
        double f, D1, D2, D3;
    };

    // A replica: f = -erfc(alpha r) / r, whose D_l are the B_l of the recursion
    // B_0 = erfc(alpha r)/r, B_l = ((2l - 1) B_{l-1} + (2 alpha^2)^l exp(-alpha^2 r^2)/(alpha sqrt
    // pi)) / r^2 with alternating signs: D1 = B_1, D2 = -B_2, D3 = B_3.
    Radial replica(double r) const {
        const double a2 = alpha_ * alpha_, r2 = r * r;
        const double e = std::exp(-a2 * r2) / (alpha_ * std::sqrt(M_PI));
        const double b0 = std::erfc(alpha_ * r) / r;
        const double b1 = (b0 + 2 * a2 * e) / r2;
        const double b2 = (3 * b1 + 4 * a2 * a2 * e) / r2;
        const double b3 = (5 * b2 + 8 * a2 * a2 * a2 * e) / r2;
        return {-b0, b1, -b2, b3};
    }

    // The nearest image less Newton: f = erf(alpha r) / r = 1/r - erfc(alpha r)/r. Near r = 0 the
    // two parts cancel, so there (alpha r < 1) its series in s = r^2 is summed:
    // f = (2 alpha / sqrt pi) sum_n (-alpha^2 s)^n / (n! (2n + 1)), D1 = 2 f', D2 = 4 f'', D3 = 8
    // f'''.
    Radial nearest(double r) const {
        const double a2 = alpha_ * alpha_, s = r * r;
        if (alpha_ * r >= 1) {
            const Radial rep = replica(r);
            return {1 / r + rep.f, rep.D1 - 1 / (s * r), rep.D2 + 3 / (s * s * r),
                    rep.D3 - 15 / (s * s * s * r)};
        }
        double f = 0, f1 = 0, f2 = 0, f3 = 0, term = 2 * alpha_ / std::sqrt(M_PI); // n = 0
        for (int n = 0; n < 30; ++n) {
            // term = (2 alpha / sqrt pi) (-alpha^2)^n / n!; coefficient of s^n: term / (2n + 1)
            const double c = term / (2 * n + 1);
            f += c * std::pow(s, n);
            if (n >= 1) f1 += c * n * std::pow(s, n - 1);
            if (n >= 2) f2 += c * n * (n - 1) * std::pow(s, n - 2);
            if (n >= 3) f3 += c * n * (n - 1) * (n - 2) * std::pow(s, n - 3);
            term *= -a2 / (n + 1);
        }
        return {f, 2 * f1, 4 * f2, 8 * f3};
    }

    // Adds the real-space term of the image at displacement d (beyond alpha r = 6: nothing).
    void add_image(const double* d, bool is_nearest, EwaldRecord& out) const {
        const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (!is_nearest && alpha_ * alpha_ * r2 > 36) return;
        const double r = std::sqrt(r2);
        const Radial f = is_nearest ? nearest(r) : replica(r);
        out[ewald_slot::phi] += f.f;
        for (int i = 0; i < 3; ++i) out[ewald_slot::a + i] -= f.D1 * d[i];
        for (int c = 0; c < 6; ++c) {
            const int j = kEwaldPairs[c][0], k = kEwaldPairs[c][1];
            out[ewald_slot::d2 + c] += f.D2 * d[j] * d[k] + (j == k ? f.D1 : 0.0);
        }
        for (int c = 0; c < 10; ++c) {
            const int i = kEwaldTriples[c][0], j = kEwaldTriples[c][1], k = kEwaldTriples[c][2];
            const double deltas =
                (i == j ? d[k] : 0.0) + (i == k ? d[j] : 0.0) + (j == k ? d[i] : 0.0);
            out[ewald_slot::d3 + c] += f.D3 * d[i] * d[j] * d[k] + f.D2 * deltas;
        }
    }

    // Adds the term -coef cos(k.x) and its derivatives.
    static void add_wave(const Wave& w, const double* p, EwaldRecord& out) {
        const double kx = w.k[0] * p[0] + w.k[1] * p[1] + w.k[2] * p[2];
        const double s = w.coef * std::sin(kx), c = w.coef * std::cos(kx);
        out[ewald_slot::phi] -= c;
        for (int i = 0; i < 3; ++i) out[ewald_slot::a + i] -= w.k[i] * s;
        for (int q = 0; q < 6; ++q)
            out[ewald_slot::d2 + q] += w.k[kEwaldPairs[q][0]] * w.k[kEwaldPairs[q][1]] * c;
        for (int q = 0; q < 10; ++q) {
            const auto& t = kEwaldTriples[q];
            out[ewald_slot::d3 + q] -= w.k[t[0]] * w.k[t[1]] * w.k[t[2]] * s;
        }
    }

    std::array<double, 3> len_;
    double alpha_ = 0, background_ = 0;
    std::array<int, 3> images_{0, 0, 0};
    std::vector<Wave> waves_;
};

} // namespace exasph
