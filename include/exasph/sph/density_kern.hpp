#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/kernel_table.hpp"
#include "exasph/tree/neighbour_span.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

template <class T>
struct DensityResult {
    T rho;
    T kx; // k_a = sum_b X_b W_ab(h_a): the volume-element normalisation (= rho when X = m)
    T omega;
    std::uint32_t nc; // neighbours with r < 2 h_a, self excluded (SPEC 2)
};

// SPEC 3 with generalised volume elements (Hopkins 2013; Cabezon et al. 2017): every particle
// carries a weight X (X = m gives standard SPH exactly), k_a = sum_b X_b W_ab(h_a) including
// b = a, V_a = X_a / k_a, rho_a = m_a / V_a, and the grad-h term
// Omega_a = 1 - 1/(3 k_a h_a^3) sum_b X_b (3 w(v) + v w'(v)).
template <class T>
EXASPH_HD DensityResult<T> density_kern(std::uint32_t a, NeighbourSpan nb, const ParticleView<T>& p,
                                        const Box<T>& box, const KernelView<T>& k) {
    const T* x = p[Field::x];
    const T* y = p[Field::y];
    const T* z = p[Field::z];
    // Standard SPH carries no X field: X = m.
    const T* xm = p[Field::xm] ? p[Field::xm] : p[Field::m];
    const T ha = p[Field::h][a];
    const T inv_h = T(1) / ha;
    const T w0 = k.value(T(0));
    double k_sum = xm[a] * w0; // w(v) sums, divided by h^3 at the end
    double dh_sum = xm[a] * T(3) * w0;
    std::uint32_t nc = 0;
    // Pairs beyond 2 h_a (listed because of h_b) are masked rather than skipped, so that the
    // loop vectorises.
    const PeriodicImage<T> image(box);
#pragma omp simd reduction(+ : k_sum, dh_sum, nc)
    for (std::uint32_t n = 0; n < nb.count; ++n) {
        std::uint32_t b = nb.index[n];
        T dx = image(x[b] - x[a], 0);
        T dy = image(y[b] - y[a], 1);
        T dz = image(z[b] - z[a], 2);
        T r2 = dx * dx + dy * dy + dz * dz;
        T inside = T(r2 < T(4) * ha * ha);
        nc += std::uint32_t(inside);
        T v = std::sqrt(r2) * inv_h;
        T w = k.value(v);
        T xb = xm[b] * inside;
        k_sum += xb * w;
        dh_sum += xb * (T(3) * w + v * k.derivative(v));
    }
    T h3 = ha * ha * ha;
    T kx = static_cast<T>(k_sum) / h3;
    T rho = kx * (p[Field::m][a] / xm[a]); // m/X = 1 exactly for standard SPH
    T omega = T(1) - static_cast<T>(dh_sum) / (T(3) * kx * h3);
    return {rho, kx, omega, nc};
}

} // namespace exasph
