#pragma once
#include <cstdint>
#include <string>
#include <type_traits>

#include "exasph/particles/particle_set.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/density_kern.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/launch.hpp"
#include "exasph/sph/momentum_energy_kern.hpp"
#include "exasph/sph/skin_kern.hpp"
#include "exasph/sph/softening_correction_kern.hpp"
#include "exasph/sph/stir_kern.hpp"
#include "exasph/sph/update_kern.hpp"
#include "exasph/util/error.hpp"

// The SPH passes of a step: each builds its kernel (a functor from sph/*_kern.hpp) over a view of
// the particles and hands it to the launcher L (sph/launch.hpp). Neighbour passes run over the
// particles that have lists (the owned ones, or with block time steps the active ones).
namespace exasph {

// The particles a particle-wise pass runs over: the first n, or the n listed in idx (block time
// steps: the active ones; a FieldArray, which the CUDA backend's device reads).
struct ParticleRange {
    std::size_t n = 0;
    const std::uint32_t* idx = nullptr;
    ParticleRange(std::size_t count) : n(count) {} // NOLINT: a count converts implicitly
    ParticleRange(const std::uint32_t* list, std::size_t count) : n(count), idx(list) {}
};

template <class L, class Kernel>
void for_each_in(const ParticleRange& r, const Kernel& k) {
    if (r.idx)
        L::for_each_of(r.idx, r.n, k);
    else
        L::for_each(r.n, k);
}

// A neighbour kernel as it is (the default of compute_momentum_energy's `wrap`).
struct AsIs {
    template <class K>
    K operator()(K k) const {
        return k;
    }
};

// physics.md §3 and 4: density, EOS and the pressure-force coefficient (DensityEosKernel).
template <class L = DefaultLauncher, class T, class Lists>
void compute_density(ParticleSet<T>& ps, const Lists& nl, const Box<T>& box, const KernelView<T>& k,
                     const EosParams& eos = {}, bool capture_rho0 = false) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        L::for_each_neighbourhood(nl, DensityEosKernel<T, N>{p, box, k, eos, capture_rho0});
    });
}

// physics.md §5. Throws Error naming a particle whose tau is singular. With `with_gradient`, also
// stores the velocity gradient for the reconstructed artificial viscosity; with `diss`'s
// stress_matrix, the artificial stress's matrix M (Field::s11..s33).
template <class L = DefaultLauncher, class T, class Lists>
void compute_iad(ParticleSet<T>& ps, const Lists& nl, const Box<T>& box, const KernelView<T>& k,
                 bool with_gradient = false, bool own_k = false, const Dissipation<T>& diss = {}) {
    // the artificial stress's own matrix (tensile_stress.hpp), with --torque-free
    const T stress_inv_w0 = diss.stress_matrix ? diss.stress_inv_w0(k) : T(0);
    const int stress_exponent = diss.tensile_exponent;
    if (with_gradient) ps.enable(kHaloGrad);
    if (stress_inv_w0 > T(0))
        for (int c = 0; c < 9; ++c) ps.enable(stress_matrix_field(c));
    const FoundIndex singular = with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        return L::for_each_neighbourhood(
            nl, IadKernel<T, N>{p, box, k, with_gradient, own_k, stress_inv_w0, stress_exponent});
    });
    if (singular.found()) {
        const std::uint32_t i = singular.index;
        const bool with_stress = stress_inv_w0 > T(0);
        throw Error(std::string(with_stress ? "IAD matrix tau or the artificial stress's tau'"
                                            : "IAD matrix tau") +
                    " is singular for particle id " + std::to_string(ps.id[i]) + " (" +
                    std::to_string(nl.list(i).size()) +
                    " neighbours): too few or coplanar neighbours" +
                    (with_stress ? " (or a --tensile-exponent too high for them)" : ""));
    }
}

// physics.md §6; returns the Courant time step of physics.md §7 (min over the particles). One
// instantiation of the pair loop per combination of options, chosen once per pass. `wrap` may wrap
// the kernel (block time steps: StoreResultKernel keeps each particle's limit).
template <class L = DefaultLauncher, class T, class Lists, class Wrap = AsIs>
double compute_momentum_energy(ParticleSet<T>& ps, const Lists& nl, const Box<T>& box,
                               const KernelView<T>& k, const Dissipation<T>& diss = {},
                               T courant = T(0.2), Wrap wrap = {}) {
    return with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        auto pass = [&](auto terms, auto alpha, auto ve) {
            return L::for_each_neighbourhood(
                nl,
                wrap(MomentumEnergyKernel<T, terms(), alpha(), ve(), N>{p, box, k, diss, courant}));
        };
        auto with_ve = [&](auto terms, auto alpha) {
            return p[Field::kx] ? pass(terms, alpha, std::true_type{})
                                : pass(terms, alpha, std::false_type{});
        };
        auto with_alpha = [&](auto terms) {
            return p[Field::alpha] ? with_ve(terms, std::true_type{})
                                   : with_ve(terms, std::false_type{});
        };
        using Terms = PairTerms;
        switch (diss.terms()) {
        case Terms::plain:
            return with_alpha(std::integral_constant<Terms, Terms::plain>{});
        case Terms::limited:
            return with_alpha(std::integral_constant<Terms, Terms::limited>{});
        default:
            return with_alpha(std::integral_constant<Terms, Terms::any>{});
        }
    });
}

// The gravitational softening's correction (sph/softening_correction_kern.hpp): xi after the
// density pass, before its halo exchange ...
template <class L = DefaultLauncher, class T, class Lists>
void compute_softening_zeta(ParticleSet<T>& ps, const Lists& nl, const SofteningView<T>& soft,
                            double G) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        L::for_each_neighbourhood(nl, SofteningZetaKernel<T, N>{p, soft, T(G)});
    });
}

// ... and its force, added to the accelerations after the momentum-energy pass.
template <class L = DefaultLauncher, class T, class Lists>
void add_softening_correction(ParticleSet<T>& ps, const Lists& nl, const KernelView<T>& k) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        L::for_each_neighbourhood(nl, SofteningForceKernel<T, N>{p, k});
    });
}

// physics.md §7: positions, velocities and u of the first n particles, one axis at a time
// (PressAxisKernel), then u (EnergyUpdateKernel).
template <class L = DefaultLauncher, class T>
void update_state(ParticleSet<T>& ps, std::size_t n, const Box<T>& box, double dt, double dt_m1) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        for (int axis = 0; axis < 3; ++axis)
            L::for_each(n, PressAxisKernel<T, N>{p, box, T(dt), T(dt_m1), axis});
        L::for_each(n, EnergyUpdateKernel<T, N>{p, T(dt), T(dt_m1)});
    });
}

// physics.md §2 (SmoothingLengthKernel).
template <class L = DefaultLauncher, class T>
void update_smoothing_lengths(ParticleSet<T>& ps, const ParticleRange& r, double ng0) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        for_each_in<L>(r, SmoothingLengthKernel<T, N>{p, T(ng0)});
    });
}

// The AV switch (ViscosityKernel), alpha between alpha_min and alpha_max; dt < 0: each
// particle's own step (Field::dtc, block time steps).
template <class L = DefaultLauncher, class T>
void update_viscosity(ParticleSet<T>& ps, const ParticleRange& r, double dt, double alpha_min,
                      double alpha_max) {
    with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        const T* own = dt < 0 ? p[Field::dtc] : nullptr;
        for_each_in<L>(
            r, ViscosityKernel<T, N>{p, T(dt), T(alpha_min), T(alpha_max), T(kAlphaDecay), own});
    });
}

// The stirring force of driven turbulence, added to the acceleration (sph/stir_kern.hpp).
template <class L = DefaultLauncher, class T>
void add_stirring(ParticleSet<T>& ps, std::size_t n, const StirModes& modes) {
    with_view(ps, [&](auto p) {
        L::for_each(n, StirKernel<T, typename decltype(p)::narrow_type>{p, modes});
    });
}

// Volume elements for the next step (VolumeWeightKernel; `energy`: X = m u).
template <class L = DefaultLauncher, class T>
void update_volume_weights(ParticleSet<T>& ps, const ParticleRange& r, bool energy) {
    with_view(ps, [&](auto p) {
        for_each_in<L>(r, VolumeWeightKernel<T, typename decltype(p)::narrow_type>{p, energy});
    });
}

// Volume elements start from X = m, standard SPH's weights: before the first forces, a few
// density passes, each with X = (m/rho)^0.7 of the pass before, let the weights settle, so that
// a contact discontinuity of the initial conditions (the isobaric cube, the Kelvin-Helmholtz
// layers) does not start with standard SPH's full pressure blip. exchange_x() sends X to the
// halos. Energy weights (X = m u) need no density: one pass sets them.
template <class L = DefaultLauncher, class T, class Lists, class ExchangeX>
void settle_volume_weights(ParticleSet<T>& ps, const Lists& nl, const Box<T>& box,
                           const KernelView<T>& k, const EosParams& eos, std::size_t n, bool energy,
                           ExchangeX exchange_x) {
    for (int pass = 0; pass < (energy ? 1 : 4); ++pass) {
        if (!energy) compute_density<L>(ps, nl, box, k, eos);
        update_volume_weights<L>(ps, n, energy);
        exchange_x();
    }
}

// The smallest acceleration time-step limit of the first n particles (AccelerationStepKernel).
template <class L = DefaultLauncher, class T>
double acceleration_time_step_min(ParticleSet<T>& ps, std::size_t n, double eps) {
    return with_view(ps, [&](auto p) {
        return L::reduce(n, AccelerationStepKernel<T, typename decltype(p)::narrow_type>{p, eps});
    });
}

// --sync-every: each owned particle's use of the halo skin by the end of a coming step no longer
// than dt (SkinUseKernel, added to used[i]); returns the largest.
template <class L = DefaultLauncher, class T>
double skin_use_max(ParticleSet<T>& ps, std::size_t n, float* used, double dt, double dt_m1,
                    double ng0) {
    if (n == 0) return 0.0;
    return with_view(ps, [&](auto p) {
        using N = typename decltype(p)::narrow_type;
        return L::reduce(n, SkinUseKernel<T, N>{p, used, T(dt), T(dt_m1), T(ng0)});
    });
}

} // namespace exasph
