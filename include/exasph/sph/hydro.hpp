#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>

#include "exasph/particles/particle_set.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/density_kern.hpp"
#include "exasph/sph/eos.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/momentum_energy_kern.hpp"
#include "exasph/sph/timestep.hpp"
#include "exasph/tree/neighbour_lists.hpp"
#include "exasph/util/error.hpp"

// OpenMP drivers of the SPH phases: thin loops over the particles that have neighbour lists
// (the owned ones, [0, nl.size())) calling the pure kernels.
namespace exasph {

// Calls body(i, neighbours of i) for every particle with a list, in parallel over the leaf
// groups (each thread expands its groups' lists into its own buffer). Returns the minimum of
// the body's results, if it returns a number (else +infinity).
template <class T, class Body>
double for_each_neighbourhood(const NeighbourLists<T>& nl, Body&& body) {
    constexpr bool kReduces =
        !std::is_void_v<std::invoke_result_t<Body&, std::uint32_t, NeighbourSpan>>;
    const auto groups = static_cast<std::int64_t>(nl.num_groups());
    double least = std::numeric_limits<double>::infinity();
#pragma omp parallel reduction(min : least)
    {
        typename NeighbourLists<T>::Decoder dec(nl);
#pragma omp for schedule(dynamic, 8)
        for (std::int64_t g = 0; g < groups; ++g) {
            dec.start(std::size_t(g));
            for (std::uint32_t i = nl.group_begin(std::size_t(g)); i < nl.group_end(std::size_t(g));
                 ++i) {
                if constexpr (kReduces)
                    least = std::min(least, double(body(i, dec.next())));
                else
                    body(i, dec.next());
            }
        }
    }
    return least;
}

// SPEC 3 and 4 in one pass: ρ, Ω (and k with volume elements), then P and c from the equation
// of state, and the pressure-force coefficient P / (Ω k²) of SPEC 6 that momentum–energy reads for
// both members of a pair (Ω is not needed otherwise, so it is not stored: one float array and one
// division per pair less). With `capture_rho0` (Tait, first step) the density becomes the
// reference density rho0 first.
template <class T>
void compute_density(ParticleSet<T>& ps, const NeighbourLists<T>& nl, const Box<T>& box,
                     const KernelView<T>& k, const EosParams& eos = {}, bool capture_rho0 = false) {
    auto p = make_view(ps);
    const T gamma = T(eos.gamma), c0 = T(eos.c0);
    const bool tait = eos.kind == EosKind::tait;
    for_each_neighbourhood(nl, [&](std::uint32_t i, NeighbourSpan nb) {
        auto r = density_kern(i, nb, p, box, k);
        const float rho = float(r.rho); // single precision (is_narrow)
        p.narrow(Field::rho)[i] = rho;
        if (p[Field::kx]) p[Field::kx][i] = r.kx;
        p.narrow(Field::nc)[i] = float(r.nc);
        if (capture_rho0) p[Field::rho0][i] = T(rho);
        auto e = tait ? tait_eos(T(rho), p[Field::rho0][i], p[Field::p0][i], c0)
                      : ideal_gas_eos(T(rho), p[Field::u][i], gamma);
        p.narrow(Field::p)[i] = float(e.p);
        p.narrow(Field::c)[i] = float(e.c);
        // k = rho for standard SPH (the stored value, as the pair terms read it)
        const T kk = p[Field::kx] ? r.kx : T(rho);
        p.narrow(Field::pgrad)[i] = float(e.p / (r.omega * kk * kk));
    });
}

// Throws Error naming a particle whose tau is singular (SPEC 5). With `with_gradient`, also
// stores the velocity gradient (Field::gxx..gzz) for the reconstructed artificial viscosity.
template <class T>
void compute_iad(ParticleSet<T>& ps, const NeighbourLists<T>& nl, const Box<T>& box,
                 const KernelView<T>& k, bool with_gradient = false) {
    if (with_gradient) ps.enable(kHaloGrad);
    auto p = make_view(ps);
    const auto n = static_cast<std::uint32_t>(nl.size());
    std::uint32_t first_singular = n;
    for_each_neighbourhood(nl, [&](std::uint32_t i, NeighbourSpan nb) {
        VelocityGradient<T> g;
        auto r = iad_kern(i, nb, p, box, k, with_gradient ? &g : nullptr);
        if (with_gradient)
            for (int c = 0; c < 9; ++c) p[kVelocityGradientFields[c]][i] = g.g[c];
        if (r.singular) {
#pragma omp critical(exasph_iad_singular)
            first_singular = std::min(first_singular, i);
        }
        p.narrow(Field::c11)[i] = float(r.c11);
        p.narrow(Field::c12)[i] = float(r.c12);
        p.narrow(Field::c13)[i] = float(r.c13);
        p.narrow(Field::c22)[i] = float(r.c22);
        p.narrow(Field::c23)[i] = float(r.c23);
        p.narrow(Field::c33)[i] = float(r.c33);
    });
    if (first_singular < n)
        throw Error("IAD matrix tau is singular for particle id " +
                    std::to_string(ps.id[first_singular]) + " (" +
                    std::to_string(nl.list(first_singular).size()) +
                    " neighbours): too few or coplanar neighbours");
}

// Returns the Courant time step of SPEC 7 (min over the particles of courant h / max_b v^sig_ab,
// or h / c where no pair approaches) for the factor `courant`: the signal velocities are used
// where they are computed, not stored.
template <class T>
double compute_momentum_energy(ParticleSet<T>& ps, const NeighbourLists<T>& nl, const Box<T>& box,
                               const KernelView<T>& k, const Dissipation<T>& diss = {},
                               T courant = T(0.2)) {
    auto p = make_view(ps);
    const T* h = p[Field::h];
    const float* c = p.narrow(Field::c);
    const bool extras = diss.reconstruct || diss.alpha_u > T(0);
    const bool alpha_field = p[Field::alpha] != nullptr;
    const bool volume_elements = p[Field::kx] != nullptr;
    // One instantiation of the pair loop per combination of options, chosen once per pass.
    auto pass = [&](auto extras_c, auto alpha_c, auto ve_c) {
        return for_each_neighbourhood(nl, [&](std::uint32_t i, NeighbourSpan nb) {
            auto r = momentum_energy_kern<T, extras_c(), alpha_c(), ve_c()>(i, nb, p, box, k, diss);
            p[Field::ax][i] = r.ax;
            p[Field::ay][i] = r.ay;
            p[Field::az][i] = r.az;
            p[Field::du][i] = r.du;
            if (p[Field::divv]) p[Field::divv][i] = r.divv;
            return courant_time_step(h[i], r.vsig_max, T(c[i]), courant);
        });
    };
    auto with_ve = [&](auto extras_c, auto alpha_c) {
        return volume_elements ? pass(extras_c, alpha_c, std::true_type{})
                               : pass(extras_c, alpha_c, std::false_type{});
    };
    auto with_alpha = [&](auto extras_c) {
        return alpha_field ? with_ve(extras_c, std::true_type{})
                           : with_ve(extras_c, std::false_type{});
    };
    return extras ? with_alpha(std::true_type{}) : with_alpha(std::false_type{});
}

} // namespace exasph
