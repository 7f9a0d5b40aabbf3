#pragma once
#include <cmath>
#include <cstddef>
#include <limits>

#include "exasph/exact/exact_density.hpp"
#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/reduction.hpp"
#include "exasph/sph/smoothing_length.hpp"

// The per-particle terms of the step's diagnostics (physics.md §10) as a kernel that a launcher
// reduces where the particles live (sim/diagnostics.hpp turns the result into Diagnostics): one
// pass over the owned particles, only the record crosses to the host.
namespace exasph {

// What the diagnostics sum over the owned particles ...
enum class DiagSum : int {
    ekin, // m v^2 / 2
    eint, // m u
    px,
    py,
    pz, // m v
    lx,
    ly,
    lz,           // m x × v (about the origin)
    nc,           // neighbour counts (their mean)
    epot,         // m phi / 2 (each pair counted from both sides, physics.md §8)
    mass,         // m
    power_abs,    // m (|v . a| + |du|)
    momentum_abs, // m (|v| + c)
    force_abs,    // m |a|
    stir_power,   // m v . a_stir
    soft_abs,     // m |zeta dh| (the potential energy a change of h moves)
    l1_rho,       // |rho - rho_exact(r)| at the positions rho was computed at (x_m1)
    count
};
// ... and the largest values (a minimum as the largest of its negative).
enum class DiagMax : int { nc, neg_nc, rho, x, y, z, neg_x, neg_y, neg_z, count };

struct DiagnosticsRecord {
    double sum[int(DiagSum::count)];
    double max[int(DiagMax::count)];

    EXASPH_HD double& operator[](DiagSum k) { return sum[int(k)]; }
    EXASPH_HD double operator[](DiagSum k) const { return sum[int(k)]; }
    EXASPH_HD double& operator[](DiagMax k) { return max[int(k)]; }
    EXASPH_HD double operator[](DiagMax k) const { return max[int(k)]; }
};

// Sums add, maxima take the larger (identity: 0 and -infinity).
struct DiagnosticsReduction {
    using value_type = DiagnosticsRecord;
    EXASPH_HD static DiagnosticsRecord identity() {
        DiagnosticsRecord r;
        for (double& s : r.sum) s = 0;
        for (double& m : r.max) m = -std::numeric_limits<double>::infinity();
        return r;
    }
    EXASPH_HD static DiagnosticsRecord combine(const DiagnosticsRecord& a,
                                               const DiagnosticsRecord& b) {
        DiagnosticsRecord r;
        for (int k = 0; k < int(DiagSum::count); ++k) r.sum[k] = a.sum[k] + b.sum[k];
        for (int k = 0; k < int(DiagMax::count); ++k)
            r.max[k] = b.max[k] > a.max[k] ? b.max[k] : a.max[k];
        return r;
    }
};

// Requires: the view's state, rho, c, nc, accelerations, du, phi and x_m1 fields; stir, gsoft and
// kx are read when enabled (non-null). `exact` without a solution (valid() false) adds no L1.
template <class T, class N = float>
struct DiagnosticsKernel {
    ParticleView<T, N> p;
    ExactDensity::AtTime exact;
    double ng0;
    using Reduction = DiagnosticsReduction;

    EXASPH_HD DiagnosticsRecord operator()(ParticleIndex i) const {
        DiagnosticsRecord r;
        add_energies(i, r);
        add_scales(i, r);
        const double nc = derived(Field::nc, i), rho = derived(Field::rho, i);
        r[DiagSum::nc] = nc;
        r[DiagMax::nc] = nc, r[DiagMax::neg_nc] = -nc;
        r[DiagMax::rho] = rho;
        r[DiagSum::l1_rho] = exact.valid() ? std::abs(rho - exact(radius_m1(i))) : 0.0;
        r[DiagSum::soft_abs] = softening_moved(i, nc, rho);
        const double x = p[Field::x][i], y = p[Field::y][i], z = p[Field::z][i];
        r[DiagMax::x] = x, r[DiagMax::y] = y, r[DiagMax::z] = z;
        r[DiagMax::neg_x] = -x, r[DiagMax::neg_y] = -y, r[DiagMax::neg_z] = -z;
        return r;
    }

  private:
    // A derived field in its storage (float, or T with --double-precision).
    EXASPH_HD double derived(Field f, ParticleIndex i) const {
        return is_narrow(f) ? double(p.narrow(f)[i]) : double(p[f][i]);
    }
    EXASPH_HD double radius_m1(ParticleIndex i) const {
        const double x = p[Field::x_m1][i], y = p[Field::y_m1][i], z = p[Field::z_m1][i];
        return std::sqrt(x * x + y * y + z * z);
    }
    // Kinetic, internal and potential energy, momentum and angular momentum, the stirring's power.
    EXASPH_HD void add_energies(ParticleIndex i, DiagnosticsRecord& r) const {
        const double m = p[Field::m][i];
        const double x = p[Field::x][i], y = p[Field::y][i], z = p[Field::z][i];
        const double vx = p[Field::vx][i], vy = p[Field::vy][i], vz = p[Field::vz][i];
        r[DiagSum::ekin] = 0.5 * m * (vx * vx + vy * vy + vz * vz);
        r[DiagSum::eint] = m * double(p[Field::u][i]);
        r[DiagSum::px] = m * vx, r[DiagSum::py] = m * vy, r[DiagSum::pz] = m * vz;
        r[DiagSum::lx] = m * (y * vz - z * vy);
        r[DiagSum::ly] = m * (z * vx - x * vz);
        r[DiagSum::lz] = m * (x * vy - y * vx);
        const T* phi = p[Field::phi];
        r[DiagSum::epot] = phi ? 0.5 * m * double(phi[i]) : 0.0;
        const T* stir = p[Field::stir];
        r[DiagSum::stir_power] = stir ? m * double(stir[i]) : 0.0;
        r[DiagSum::mass] = m;
    }
    // The conservation watchdog's scales (sim/energy_watchdog.hpp).
    EXASPH_HD void add_scales(ParticleIndex i, DiagnosticsRecord& r) const {
        const double m = p[Field::m][i];
        const double vx = p[Field::vx][i], vy = p[Field::vy][i], vz = p[Field::vz][i];
        const double ax = p[Field::ax][i], ay = p[Field::ay][i], az = p[Field::az][i];
        const double va = vx * ax + vy * ay + vz * az;
        r[DiagSum::power_abs] = m * (std::abs(va) + std::abs(double(p[Field::du][i])));
        r[DiagSum::momentum_abs] =
            m * (std::sqrt(vx * vx + vy * vy + vz * vz) + derived(Field::c, i));
        r[DiagSum::force_abs] = m * std::sqrt(ax * ax + ay * ay + az * az);
    }
    // physics.md §8's softening follows h: E_pot moves by m zeta dh. The density pass left
    // gsoft = zeta (-h / (3 k Omega)) and physics.md §2 made dh / h = g(nc) - 1 from this
    // step's nc, so m |zeta dh| = 3 m k Omega |gsoft (g - 1)|, Omega ~ 1 (k = rho without kx).
    EXASPH_HD double softening_moved(ParticleIndex i, double nc, double rho) const {
        const T* gsoft = p[Field::gsoft];
        if (!gsoft) return 0.0;
        const T* kx = p[Field::kx];
        const double k = kx ? double(kx[i]) : rho;
        const double g = update_smoothing_length(1.0, nc, ng0);
        return 3 * double(p[Field::m][i]) * k * std::abs(double(gsoft[i]) * (g - 1));
    }
};

} // namespace exasph
