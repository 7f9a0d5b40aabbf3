#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/av_switch.hpp"
#include "exasph/sph/integrator.hpp"
#include "exasph/sph/reduction.hpp"
#include "exasph/sph/smoothing_length.hpp"
#include "exasph/sph/timestep.hpp"
#include "exasph/util/box.hpp"

// Per-particle kernels of the step that need no neighbours: the update of the state (physics.md
// §7), of h (physics.md §2), of the AV switch's alpha (physics.md §6) and of the volume-element
// weights, and the acceleration time-step limit. Each is a functor called as k(i) by a launcher
// (sph/launch.hpp).
namespace exasph {

// physics.md §7: Press scheme for x and v along one axis, with the periodic wrap of x and x_{n-1}.
// The update runs one axis at a time, and the energy apart (EnergyUpdateKernel): four arrays per
// loop instead of eleven, which the hardware prefetchers follow (all in one loop, the update phase
// of Sedov 125k took 11.5 ms per step on 2 Zen 2 cores, mostly waiting for memory; split, 4.3 ms).
template <class T, class N = float>
struct PressAxisKernel {
    ParticleView<T, N> p;
    Box<T> box;
    T dt, dt_m1;
    int axis;

    EXASPH_HD void operator()(ParticleIndex i) const {
        const Field pos[3] = {Field::x, Field::y, Field::z};
        const Field prev[3] = {Field::x_m1, Field::y_m1, Field::z_m1};
        const Field vel[3] = {Field::vx, Field::vy, Field::vz};
        const Field acc[3] = {Field::ax, Field::ay, Field::az};
        const T x = p[pos[axis]][i];
        const auto r = press_update(x, p[prev[axis]][i], p[acc[axis]][i], dt, dt_m1);
        const T shift = box.wrap_shift(r.x, axis);
        p[pos[axis]][i] = r.x + shift;
        p[prev[axis]][i] = x + shift;
        p[vel[axis]][i] = r.v;
    }
};

// physics.md §7: Adams-Bashforth for u; du becomes du_{n-1}.
template <class T, class N = float>
struct EnergyUpdateKernel {
    ParticleView<T, N> p;
    T dt, dt_m1;

    EXASPH_HD void operator()(ParticleIndex i) const {
        p[Field::u][i] =
            adams_bashforth_energy(p[Field::u][i], p[Field::du][i], p[Field::du_m1][i], dt, dt_m1);
        p[Field::du_m1][i] = p[Field::du][i];
    }
};

// physics.md §2: h from this step's neighbour count.
template <class T, class N = float>
struct SmoothingLengthKernel {
    ParticleView<T, N> p;
    T ng0;

    EXASPH_HD void operator()(ParticleIndex i) const {
        p[Field::h][i] = update_smoothing_length(p[Field::h][i], T(p.narrow(Field::nc)[i]), ng0);
    }
};

// The AV switch: alpha follows the compression of the step (sph/av_switch.hpp).
template <class T, class N = float>
struct ViscosityKernel {
    ParticleView<T, N> p;
    T dt, alpha_min, alpha_max, decay;
    const T* own_dt = nullptr; // block time steps: each particle's own step (Field::dtc)

    EXASPH_HD void operator()(ParticleIndex i) const {
        T* alpha = p[Field::alpha];
        alpha[i] =
            evolve_alpha(alpha[i], p[Field::divv][i], p[Field::h][i], T(p.narrow(Field::c)[i]),
                         own_dt ? own_dt[i] : dt, alpha_min, alpha_max, decay);
    }
};

// Decay rate of the AV switch in sound-crossing times of h (Morris & Monaghan 1997).
inline constexpr double kAlphaDecay = 0.2;

// Generalised volume elements: X_a = (m_a / rho_a)^p from this step's density, used by the
// next step (Hopkins 2013 / Cabezon et al. 2017 with p = 0.7). With `energy` (--energy-weights)
// X_a = m_a u_a, pressure-energy SPH (Saitoh & Makino 2013): rho_a = m_a k_a / X_a gives
// P_a = (gamma - 1) rho_a u_a = (gamma - 1) k_a = (gamma - 1) sum_b m_b u_b W_ab(h_a), the
// pressure smoothed directly, so a contact in pressure balance has no pressure blip; and X
// needs no density, so it is exact from the first step.
inline constexpr double kVolumeElementExponent = 0.7;
template <class T, class N = float>
struct VolumeWeightKernel {
    ParticleView<T, N> p;
    bool energy = false;

    EXASPH_HD void operator()(ParticleIndex i) const {
        if (energy) {
            p[Field::xm][i] = p[Field::m][i] * p[Field::u][i];
            return;
        }
        const double v = double(p[Field::m][i] / p.narrow(Field::rho)[i]);
        p[Field::xm][i] = T(std::pow(v, kVolumeElementExponent));
    }
};

// physics.md §7 with gravity: the acceleration limit sqrt(eps h / |a|) of particle i.
template <class T, class N = float>
struct AccelerationStepKernel {
    ParticleView<T, N> p;
    double eps;
    using Reduction = MinOf<double>;

    EXASPH_HD double operator()(ParticleIndex i) const {
        return acceleration_time_step(double(p[Field::h][i]), double(p[Field::ax][i]),
                                      double(p[Field::ay][i]), double(p[Field::az][i]), eps);
    }
};

} // namespace exasph
