#pragma once
#include <cmath>
#include <cstdint>
#include <numbers>
#include <type_traits>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/iad_kern.hpp"
#include "exasph/sph/momentum_energy_pair.hpp"
#include "exasph/sph/momentum_energy_simd.hpp"
#include "exasph/sph/pair_dissipation.hpp"
#include "exasph/sph/reduction.hpp"
#include "exasph/sph/tensile_stress.hpp"
#include "exasph/sph/timestep.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

template <class T>
struct MomentumEnergyResult {
    T ax, ay, az;
    T du;
    T vsig_max;
    T divv; // sum_b V_b (v_b - v_a) . A_ab(h_a)
};

// physics.md §6 with IAD gradients, with a per-particle alpha (physics.md §6's "later switch")
// (physics.md §5), over a symmetric neighbour list (r_ab < 2 max(h_a, h_b)), which makes every
// pair's contribution appear with opposite sign in b's sum: momentum is conserved to round-off and
// energy up to time-integration error.
//   A_ab(h_a) = C_a (x_b - x_a) W_ab(h_a),  A_ab(h_b) = C_b (x_b - x_a) W_ab(h_b)
//   dv_a/dt = -sum_b m_b [P_a/(Om_a rho_a^2) A_ab(h_a) + P_b/(Om_b rho_b^2) A_ab(h_b)]
//             (with volume elements: -sum_b (X_a X_b / m_a) [P_a/(Om_a k_a^2) A_ab(h_a) + ...])
//             -1/2 sum_b m_b Pi_ab [A_ab(h_a)/rho_a + A_ab(h_b)/rho_b]
//   du_a/dt = P_a/(Om_a rho_a^2) sum_b m_b v_ab . A_ab(h_a)
//             +1/4 sum_b m_b Pi_ab v_ab . [A_ab(h_a)/rho_a + A_ab(h_b)/rho_b]
// kTerms: the options the loop carries (PairTerms). kAlphaField: alpha per particle (the AV
// switch, which also wants the velocity divergence), else the constant diss.alpha (divv is
// then not computed). kVolumeElements: X and k are fields; without them X = m is read once per
// neighbour (not twice through an aliased pointer) and X_a / m_a = 1. P/(Om k^2) comes
// precomputed per particle (Field::pgrad, set by the density pass).
template <class T, PairTerms kTerms = PairTerms::any, bool kAlphaField = true,
          bool kVolumeElements = true, class N, class Span>
EXASPH_HD MomentumEnergyResult<T>
momentum_energy_portable(std::uint32_t a, Span nb, const ParticleView<T, N>& p, const Box<T>& box,
                         const KernelView<T>& k, const Dissipation<T>& diss = {}) {
    using Particle = MomentumEnergyParticle<T, kTerms, kAlphaField, kVolumeElements, N>;
    const Particle own(a, p, box, k, diss); // what the pairs read of particle a
    T ax = 0, ay = 0, az = 0, du_p = 0, du_av = 0, vsig_max = 0, divv = 0, du_cond = 0, du_ts = 0;
    // simdlen(8): on AVX2 GCC 12 emulates the gathers, and only with as many lanes as a vector
    // of the 32-bit indices (8) does it accept the float fields' ones; with its own choice (4
    // doubles) the loop stayed scalar there (2x slower on Zen 2, docs/performance-log.md).
#pragma omp simd simdlen(8) reduction(+ : ax, ay, az, du_p, du_av, divv, du_cond, du_ts) \
    reduction(max : vsig_max)
    for (std::uint32_t n = 0; n < nb.count; ++n) {
        const std::uint32_t b = nb[n];
        const MomentumEnergyPairGeometry<T> q = own.geometry(b);
        const T vsig = T(own.c[a]) + T(own.c[b]) - T(3) * q.w_ab;
        vsig_max = vsig > vsig_max ? vsig : vsig_max;
        const T pi_ab = own.viscosity(b, q, vsig), half_pi = T(0.5) * pi_ab;
        const Vec3<T> g = own.viscous_gradient(b, q);
        const T mb = own.m[b], xb = kVolumeElements ? own.xm[b] : mb;
        const MomentumEnergyStress<T> st = own.stress(b, q, T(own.pgrad[b]) * own.xa_ma);
        ax -= xb * (st.qa * q.aax + st.qb * q.abx + st.tax) + mb * half_pi * g.x;
        ay -= xb * (st.qa * q.aay + st.qb * q.aby + st.tay) + mb * half_pi * g.y;
        az -= xb * (st.qa * q.aaz + st.qb * q.abz + st.taz) + mb * half_pi * g.z;
        const T v_dot_a = q.vabx * q.aax + q.vaby * q.aay + q.vabz * q.aaz;
        du_p += xb * v_dot_a;
        du_ts += xb * st.tv;
        if constexpr (kAlphaField) { // the AV switch's input only
            const T kb = kVolumeElements ? own.kx[b] : T(own.rho[b]);
            divv -= xb / kb * v_dot_a;
        }
        du_av += mb * pi_ab * (q.vabx * g.x + q.vaby * g.y + q.vabz * g.z);
        // With kLimited on every pair, times alpha_u = 0 where it is off: a branch on alpha_u
        // keeps GCC from vectorising the loop.
        if (Particle::kLimited || (Particle::kExtras && own.alpha_u > T(0)))
            du_cond -= own.conduction(b, q);
    }
    const T du = own.pa * du_p + own.ra * du_ts + T(0.25) * du_av + du_cond;
    return {ax, ay, az, du, vsig_max, divv};
}

// The pass's sums, with AVX2 or AVX-512 for the plain form (standard SPH, constant alpha) and
// the limited one (volume elements, the limiter and the conductivity, constant alpha) where the
// build targets it (sph/momentum_energy_simd.hpp: the same terms, in the same order per pair).
template <class T, PairTerms kTerms = PairTerms::any, bool kAlphaField = true,
          bool kVolumeElements = true, class N, class Span>
EXASPH_HD MomentumEnergyResult<T>
momentum_energy_kern(std::uint32_t a, Span nb, const ParticleView<T, N>& p, const Box<T>& box,
                     const KernelView<T>& k, const Dissipation<T>& diss = {}) {
#ifdef EXASPH_SIMD_LANES
    constexpr bool kSimdTypes = std::is_same_v<T, double> && std::is_same_v<N, float> &&
                                std::is_same_v<Span, ContiguousSpan>;
    if constexpr (kTerms == PairTerms::plain && !kAlphaField && !kVolumeElements && kSimdTypes) {
        const auto s = simd::MomentumEnergyPairs<simd::Native, false>(a, p, box, k, diss).sum(nb);
        return {s.ax, s.ay, s.az, s.du, s.vsig_max, T(0)};
    }
    if constexpr (kTerms == PairTerms::limited && !kAlphaField && kVolumeElements && kSimdTypes) {
        const auto s = simd::MomentumEnergyPairs<simd::Native, true>(a, p, box, k, diss).sum(nb);
        return {s.ax, s.ay, s.az, s.du, s.vsig_max, T(0)};
    }
#endif
    return momentum_energy_portable<T, kTerms, kAlphaField, kVolumeElements>(a, nb, p, box, k,
                                                                             diss);
}

// The momentum-energy pass of one particle: a, du/dt (and div v for the AV switch) stored;
// returns the particle's Courant time step (physics.md §7) for the factor `courant`, so that signal
// velocities are used where they are computed, not stored.
template <class T, PairTerms kTerms, bool kAlphaField, bool kVolumeElements, class N = float>
struct MomentumEnergyKernel {
    ParticleView<T, N> p;
    Box<T> box;
    KernelView<T> k;
    Dissipation<T> diss;
    T courant;
    using Reduction = MinOf<double>; // the Courant step of the pass

    template <class Span>
    EXASPH_HD T operator()(ParticleIndex i, Span nb) const {
        auto r =
            momentum_energy_kern<T, kTerms, kAlphaField, kVolumeElements>(i, nb, p, box, k, diss);
        p[Field::ax][i] = r.ax;
        p[Field::ay][i] = r.ay;
        p[Field::az][i] = r.az;
        p[Field::du][i] = r.du;
        if (p[Field::divv]) p[Field::divv][i] = r.divv;
        return courant_time_step(p[Field::h][i], r.vsig_max, T(p.narrow(Field::c)[i]), courant);
    }
};

} // namespace exasph
