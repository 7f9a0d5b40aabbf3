#pragma once
#include <cmath>
#include <cstdint>

#include "exasph/particles/particle_view.hpp"
#include "exasph/sph/kernel_table.hpp"
#include "exasph/sph/neighbour_view.hpp"
#include "exasph/util/box.hpp"

namespace exasph {

// The six independent components of the symmetric IAD matrix C_a = tau_a^{-1}.
template <class T>
struct IadResult {
    T c11, c12, c13, c22, c23, c33;
    bool singular;
};

// Inverse of a symmetric 3x3 matrix by its adjugate. Reports singular when |det| is below a
// tiny fraction of the scale (trace/3)^3, i.e. when neighbours are too few or coplanar.
template <class T>
EXASPH_HD IadResult<T> invert_symmetric3(T t11, T t12, T t13, T t22, T t23, T t33) {
    T a11 = t22 * t33 - t23 * t23;
    T a12 = t13 * t23 - t12 * t33;
    T a13 = t12 * t23 - t13 * t22;
    T det = t11 * a11 + t12 * a12 + t13 * a13;
    T scale = (t11 + t22 + t33) / T(3);
    bool singular = !(std::abs(det) > T(1e-12) * scale * scale * scale);
    T inv = singular ? T(0) : T(1) / det;
    return {a11 * inv,
            a12 * inv,
            a13 * inv,
            (t11 * t33 - t13 * t13) * inv,
            (t12 * t13 - t11 * t23) * inv,
            (t11 * t22 - t12 * t12) * inv,
            singular};
}

// SPEC 5, with the volume V_b = X_b / k_b (= m_b / rho_b for standard SPH):
// tau_a = sum_b V_b (x_b - x_a) (x) (x_b - x_a) W_ab(h_a), C_a = tau_a^{-1}.
template <class T>
EXASPH_HD IadResult<T> iad_kern(std::uint32_t a, NeighbourSpan nb, const ParticleView<T>& p,
                                const Box<T>& box, const KernelView<T>& k) {
    const T* x = p[Field::x];
    const T* y = p[Field::y];
    const T* z = p[Field::z];
    const T* xm = p[Field::xm];
    const T* kx = p[Field::kx];
    const T ha = p[Field::h][a];
    const T inv_h = T(1) / ha;
    T t11 = 0, t12 = 0, t13 = 0, t22 = 0, t23 = 0, t33 = 0;
    for (std::uint32_t n = 0; n < nb.count; ++n) {
        std::uint32_t b = nb.index[n];
        T dx = box.min_image(x[b] - x[a], 0);
        T dy = box.min_image(y[b] - y[a], 1);
        T dz = box.min_image(z[b] - z[a], 2);
        T r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= T(4) * ha * ha) continue;
        T vw = xm[b] / kx[b] * k.value(std::sqrt(r2) * inv_h); // V_b W_ab(h_a)
        t11 += dx * dx * vw;
        t12 += dx * dy * vw;
        t13 += dx * dz * vw;
        t22 += dy * dy * vw;
        t23 += dy * dz * vw;
        t33 += dz * dz * vw;
    }
    // W = w / h^3: the 1/h^3 factor is applied once here instead of per pair.
    T s = inv_h * inv_h * inv_h;
    return invert_symmetric3(t11 * s, t12 * s, t13 * s, t22 * s, t23 * s, t33 * s);
}

} // namespace exasph
