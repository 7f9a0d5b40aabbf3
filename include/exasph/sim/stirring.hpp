#pragma once
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "exasph/io/restart_state.hpp"
#include "exasph/sim/diagnostics.hpp"
#include "exasph/sph/eos.hpp"
#include "exasph/sph/stir_kern.hpp"
#include "exasph/util/box.hpp"
#include "exasph/util/checksum.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// Fraction of the stirring that is solenoidal (1: divergence-free; 0: compressive).
inline constexpr double kStirSolenoidal = 1.0;
// rms acceleration of the stirring for a target Mach number M: kStirGain M^2 c_s^2 / L, with
// L the largest box length (the driving scale is L/2, its turnover time L / (2 M c_s)).
// Measured: Mach_rms in steady state (docs/validation.md, driven turbulence).
inline constexpr double kStirGain = 2.2;

// Large-scale Ornstein-Uhlenbeck stirring (Eswaran & Pope 1988; Federrath et al. 2010): the
// modes 1 < |k| L / 2 pi < 3 of the periodic box, each a complex 3-vector c_k with a parabolic
// amplitude peaking at |k| L / 2 pi = 2, evolved every step as
//   c_k <- f c_k + sqrt(1 - f^2) sigma_k P(g),  f = exp(-dt / t_corr),
// with g six unit normal deviates and P the projection onto the solenoidal (and compressive)
// part. The deviates of step n are a hash of (seed, n, mode, component): every rank draws the
// same, and a restart continues them with nothing stored but the coefficients.
class Stirring {
  public:
    // The stirring of a new run for a target rms Mach number with sound speed c_s; starts from
    // a draw of the stationary distribution.
    template <class T>
    static Stirring for_mach(const Box<T>& box, double mach, double c_s, std::uint64_t seed) {
        const double l = max_length(box);
        const double v = mach * c_s;
        Stirring s(box, kStirGain * v * v / l, l / (2 * v), mach, seed);
        s.state_.coeff.assign(6 * s.amp_.size(), 0.0);
        for (std::size_t q = 0; q < s.amp_.size(); ++q) s.add_kick(q, 0, 1.0);
        return s;
    }

    // The stirring of a checkpoint or rollback point.
    template <class T>
    static Stirring resumed(const Box<T>& box, const StirState& st, double mach,
                            std::uint64_t seed) {
        Stirring s(box, st.accel_rms, st.t_corr, mach, seed);
        if (st.coeff.size() != 6 * s.amp_.size())
            throw std::runtime_error("stirring state: " + std::to_string(st.coeff.size()) +
                                     " coefficients, expected " +
                                     std::to_string(6 * s.amp_.size()));
        s.state_ = st;
        return s;
    }

    // The OU update over a step of length dt, after step `step` (its deviates: draw step + 1).
    void advance(std::int64_t step, double dt) {
        const double f = std::exp(-dt / state_.t_corr);
        for (double& c : state_.coeff) c *= f;
        const double kick = std::sqrt(std::max(0.0, 1 - f * f));
        for (std::size_t q = 0; q < amp_.size(); ++q) add_kick(q, std::uint64_t(step) + 1, kick);
    }

    // Energy bookkeeping: the work of the stirring force in a step.
    void add_energy(double e) { state_.energy_in += e; }
    const StirState& state() const { return state_; }
    double mach() const { return mach_; }
    void restore(const StirState& st) { state_ = st; }

    StirModes modes() const {
        StirModes m{wave_.data(), state_.coeff.data(), std::uint32_t(amp_.size()), {}};
        for (int d = 0; d < 3; ++d) m.k0[d] = k0_[d];
        return m;
    }

  private:
    template <class T>
    Stirring(const Box<T>& box, double accel_rms, double t_corr, double mach, std::uint64_t seed)
        : seed_(seed), mach_(mach) {
        state_.accel_rms = accel_rms;
        state_.t_corr = t_corr;
        const double l = max_length(box);
        for (int d = 0; d < 3; ++d) k0_[d] = 2 * std::numbers::pi / double(box.length(d));
        choose_modes(l);
    }

    template <class T>
    static double max_length(const Box<T>& box) {
        return std::max({double(box.length(0)), double(box.length(1)), double(box.length(2))});
    }

    // Half of k-space (n > 0 in the first non-zero component), 1 < kappa < 3 with kappa =
    // |k| L / 2 pi; amplitudes sigma (1 - (kappa - 2)^2) normalised so that the field's rms
    // (over the box and in time) is accel_rms.
    void choose_modes(double l) {
        constexpr int K = kMaxStirWave;
        double norm = 0;
        std::vector<double> shape;
        for (int nx = 0; nx <= K; ++nx)
            for (int ny = -K; ny <= K; ++ny)
                for (int nz = -K; nz <= K; ++nz) {
                    if (nx == 0 && (ny < 0 || (ny == 0 && nz <= 0))) continue;
                    const int n[3] = {nx, ny, nz};
                    double k2 = 0, khat[3];
                    for (int d = 0; d < 3; ++d) khat[d] = n[d] * k0_[d], k2 += khat[d] * khat[d];
                    const double kappa = std::sqrt(k2) * l / (2 * std::numbers::pi);
                    if (!(kappa > 1 && kappa < 3)) continue;
                    for (int d = 0; d < 3; ++d) {
                        wave_.push_back(std::int8_t(n[d]));
                        khat_.push_back(khat[d] / std::sqrt(k2));
                    }
                    const double a = 1 - (kappa - 2) * (kappa - 2);
                    shape.push_back(a);
                    norm += 2 * a * a; // the mode and its conjugate
                }
        // <|P g|^2> over the six deviates: 4 zeta^2 + 2 (1 - zeta)^2.
        const double z = kStirSolenoidal;
        const double sigma =
            state_.accel_rms / std::sqrt(norm * (4 * z * z + 2 * (1 - z) * (1 - z)));
        for (double a : shape) amp_.push_back(sigma * a);
    }

    // c_q += scale sigma_q P(g) with the deviates of draw `draw`.
    void add_kick(std::size_t q, std::uint64_t draw, double scale) {
        const double* k = khat_.data() + 3 * q;
        double* c = state_.coeff.data() + 6 * q;
        for (int part = 0; part < 2; ++part) { // real, imaginary
            double g[3], kg = 0;
            for (int d = 0; d < 3; ++d)
                g[d] = normal(draw, 6 * q + 3 * part + d), kg += k[d] * g[d];
            for (int d = 0; d < 3; ++d) {
                const double along = k[d] * kg;
                const double pg = kStirSolenoidal * (g[d] - along) + (1 - kStirSolenoidal) * along;
                c[3 * part + d] += scale * amp_[q] * pg;
            }
        }
    }

    // Unit normal deviate j of draw `draw` (Box-Muller on two hashed uniforms in (0, 1)).
    double normal(std::uint64_t draw, std::uint64_t j) const {
        auto uniform = [&](std::uint64_t half) {
            HashChain h(seed_);
            h.add(draw).add(2 * j + half);
            return (double(h.value() >> 11) + 0.5) * 0x1p-53;
        };
        return std::sqrt(-2 * std::log(uniform(0))) * std::cos(2 * std::numbers::pi * uniform(1));
    }

    std::uint64_t seed_;
    double mach_, k0_[3];
    std::vector<std::int8_t> wave_; // 3 per mode
    std::vector<double> khat_;      // 3 per mode: unit wave vector
    std::vector<double> amp_;       // sigma_q
    StirState state_;
};

// The stirring of a run with target Mach number `mach` (none if 0): resumed from the
// checkpoint, or new with the sound speed of the initial state's mean internal energy. The
// CUDA backend (on_device) does not stir.
template <class T>
std::optional<Stirring> start_stirring(const Box<T>& box, const EosParams& eos,
                                       const Diagnostics& d, double mach, std::uint64_t seed,
                                       const RestartState* restart, bool on_device = false) {
    if (!(mach > 0)) return std::nullopt;
    if (on_device) // its modes are in host memory
        throw input_error("driven turbulence (--stir-mach) needs --backend cpu", true);
    if (!(box.periodic[0] && box.periodic[1] && box.periodic[2]) || eos.kind != EosKind::ideal_gas)
        throw input_error("--stir-mach: stirring needs a box periodic on every axis and the "
                          "ideal-gas EOS",
                          true);
    if (!restart) {
        const double c_s = std::sqrt(eos.gamma * (eos.gamma - 1) * d.eint / d.mass);
        return Stirring::for_mach(box, mach, c_s, seed);
    }
    if (restart->stir.coeff.empty())
        throw input_error("--restart: the checkpoint has no stirring state", true);
    return Stirring::resumed(box, restart->stir, mach, seed);
}

} // namespace exasph
