#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/particles/particle_view.hpp"

// The stirring force of driven turbulence (sim/stirring.hpp evolves its Fourier modes): a
// per-particle kernel called as k(i) by a launcher (sph/launch.hpp).
namespace exasph {

// Largest |n_d| of a stirred mode's integer wave vector n (k = 2 pi n / L).
inline constexpr int kMaxStirWave = 3;

// The modes of the stirring field a(x) = sum_k 2 Re(c_k exp(i k.x)) over half of k-space (the
// other half is the complex conjugate).
struct StirModes {
    const std::int8_t* wave; // 3 per mode: n_x, n_y, n_z
    const double* coeff;     // 6 per mode: Re c_x, Re c_y, Re c_z, Im c_x, Im c_y, Im c_z
    std::uint32_t count;
    double k0[3]; // 2 pi / L_d
};

// Adds the stirring acceleration at the particle's position to a, and keeps v.a_stir in the
// field stir (the power per unit mass, for the energy books). exp(i n_d k0_d x_d) for every
// n_d comes from one sine and cosine per axis by complex multiplication.
template <class T, class N = float>
struct StirKernel {
    ParticleView<T, N> p;
    StirModes modes;

    EXASPH_HD void operator()(ParticleIndex i) const {
        constexpr int K = kMaxStirWave;
        const Field pos[3] = {Field::x, Field::y, Field::z};
        double er[3][2 * K + 1], ei[3][2 * K + 1]; // exp(i n k0 x) at index n + K
        for (int d = 0; d < 3; ++d) {
            const double th = modes.k0[d] * double(p[pos[d]][i]);
            const double c = std::cos(th), s = std::sin(th);
            er[d][K] = 1, ei[d][K] = 0;
            for (int n = 1; n <= K; ++n) {
                er[d][K + n] = er[d][K + n - 1] * c - ei[d][K + n - 1] * s;
                ei[d][K + n] = er[d][K + n - 1] * s + ei[d][K + n - 1] * c;
                er[d][K - n] = er[d][K + n], ei[d][K - n] = -ei[d][K + n];
            }
        }
        double a[3] = {0, 0, 0};
        for (std::uint32_t q = 0; q < modes.count; ++q) {
            const std::int8_t* n = modes.wave + 3 * q;
            const double xr = er[0][K + n[0]], xi = ei[0][K + n[0]];
            const double yr = er[1][K + n[1]], yi = ei[1][K + n[1]];
            const double zr = er[2][K + n[2]], zi = ei[2][K + n[2]];
            const double xyr = xr * yr - xi * yi, xyi = xr * yi + xi * yr;
            const double pr = xyr * zr - xyi * zi, pi = xyr * zi + xyi * zr;
            const double* c = modes.coeff + 6 * q;
            for (int d = 0; d < 3; ++d) a[d] += 2 * (c[d] * pr - c[3 + d] * pi);
        }
        const Field acc[3] = {Field::ax, Field::ay, Field::az};
        const Field vel[3] = {Field::vx, Field::vy, Field::vz};
        double power = 0;
        for (int d = 0; d < 3; ++d) {
            p[acc[d]][i] += T(a[d]);
            power += double(p[vel[d]][i]) * a[d];
        }
        p[Field::stir][i] = T(power);
    }
};

} // namespace exasph
