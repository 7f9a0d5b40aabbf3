#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/reduction.hpp"
#include "exasph/sph/smoothing_length.hpp"

namespace exasph {

// --sync-every (sim/sync_schedule.hpp): how much of the halo skin particle i may have used by
// the end of the coming step, added to what it used since the last sync. Halos found with a
// skin s stay sufficient while every particle's displacement plus the growth of its h stays
// below s / 2 (a pair's distance then shrank by at most s minus the growth of 2 max(h_i, h_j)).
// The coming step is bounded by dt (at least the step the collective will choose):
//   physics.md §7: x_{n+1} - x_n = dt (x_n - x_{n-1}) / dt_{n-1} + a_n dt (dt + dt_{n-1}) / 2,
// whose length is at most the sum of its terms' lengths, and physics.md §2's h_{n+1} from this
// step's neighbour count. Returns the use (the pass takes the largest).
template <class T, class N = float>
struct SkinUseKernel {
    ParticleView<T, N> p;
    float* used; // per owned particle, since the last sync
    T dt, dt_m1, ng0;
    using Reduction = MaxOf<double>;

    EXASPH_HD double operator()(ParticleIndex i) const {
        const Field pos[3] = {Field::x, Field::y, Field::z};
        const Field prev[3] = {Field::x_m1, Field::y_m1, Field::z_m1};
        const Field acc[3] = {Field::ax, Field::ay, Field::az};
        T dx2 = 0, a2 = 0;
        for (int d = 0; d < 3; ++d) {
            const T dx = p[pos[d]][i] - p[prev[d]][i]; // x_{n-1} is wrapped with x_n
            dx2 += dx * dx;
            a2 += p[acc[d]][i] * p[acc[d]][i];
        }
        const T move = dt / dt_m1 * std::sqrt(dx2) + std::sqrt(a2) * dt * (dt + dt_m1) * T(0.5);
        const T h = p[Field::h][i];
        const T h_next = update_smoothing_length(h, T(p.narrow(Field::nc)[i]), ng0);
        const T grow = h_next > h ? h_next - h : T(0);
        // Rounded up: the sum is kept in float.
        const float u = used[i] + float(move + grow) * (1.0f + 1e-6f);
        used[i] = u;
        return double(u);
    }
};

} // namespace exasph
