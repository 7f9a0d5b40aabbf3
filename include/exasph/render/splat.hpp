#pragma once
#include <algorithm>
#include <cmath>

#include "exasph/kernel/kernel_table.hpp"
#include "exasph/render/projected_kernel.hpp"
#include "exasph/render/render_plane.hpp"

namespace exasph {

// One particle as the renderer sees it: position, smoothing length, volume m / rho and the
// value of the rendered field.
struct SplatParticle {
    double pos[3];
    double h, vol, a;
};

// Calls add(pixel index, squared distance in the plane) for every pixel centre of the grid
// within `radius` of (cu, cv).
template <class Add>
void for_pixels_within(const RenderPlane& g, double cu, double cv, double radius, Add&& add) {
    int first[2], last[2];
    const double c[2] = {cu, cv};
    for (int k = 0; k < 2; ++k) {
        const double a = std::clamp((c[k] - radius - g.lo[k]) / g.d[k] - 0.5, -1.0, g.n[k] + 1.0);
        const double b = std::clamp((c[k] + radius - g.lo[k]) / g.d[k] - 0.5, -1.0, g.n[k] + 1.0);
        first[k] = std::max(0, int(std::ceil(a)));
        last[k] = std::min(g.n[k] - 1, int(std::floor(b)));
    }
    const double r2 = radius * radius;
    for (int j = first[1]; j <= last[1]; ++j) {
        const double dv = g.lo[1] + (j + 0.5) * g.d[1] - cv;
        for (int i = first[0]; i <= last[0]; ++i) {
            const double du = g.lo[0] + (i + 0.5) * g.d[0] - cu;
            const double d2 = du * du + dv * dv;
            if (d2 < r2) add(std::size_t(j) * std::size_t(g.n[0]) + std::size_t(i), d2);
        }
    }
}

// The particle's position in the plane and its periodic images (shifted by a period along each
// periodic axis of the plane), each passed to fn(u, v).
template <class Fn>
void for_images(const RenderPlane& g, const SplatParticle& p, Fn&& fn) {
    const int nu = g.periodic[0] ? 3 : 1, nv = g.periodic[1] ? 3 : 1;
    const double shift[3] = {0.0, -1.0, 1.0};
    for (int a = 0; a < nu; ++a)
        for (int b = 0; b < nv; ++b)
            fn(p.pos[g.u] + shift[a] * g.period[0], p.pos[g.v] + shift[b] * g.period[1]);
}

// The smoothing length a particle is drawn with: at least one pixel, so that every particle
// reaches a pixel centre (the field is smoothed to the image's resolution).
inline double drawn_h(const RenderPlane& g, double h) {
    return std::max(h, g.pixel_size());
}

// A slice: the particle's kernel W(|x_pixel - x_b|, h_b) at every pixel centre of the plane,
// times its volume, into the Shepard sum `den` and times its value into `num`
// (value = num / den: SPH interpolation normalised by the kernel's sum).
inline void splat_slice(const RenderPlane& g, const KernelView<double>& k, const SplatParticle& p,
                        double* num, double* den) {
    double dn = p.pos[g.w] - g.at;
    if (g.normal_periodic) dn -= g.normal_period * std::round(dn / g.normal_period);
    const double h = drawn_h(g, p.h);
    if (!(std::abs(dn) < 2 * h)) return;
    const double inv_h = 1 / h, norm = p.vol * inv_h * inv_h * inv_h;
    const double dn2 = dn * dn, reach = std::sqrt(4 * h * h - dn2);
    for_images(g, p, [&](double cu, double cv) {
        for_pixels_within(g, cu, cv, reach, [&](std::size_t idx, double d2) {
            const double w = norm * k.value(std::sqrt(d2 + dn2) * inv_h);
            num[idx] += w * p.a;
            den[idx] += w;
        });
    });
}

// A projection: the particle's column of the field, vol a F(R / h) / h^2, at every pixel centre
// within 2h (F: ProjectedKernel; for rho, vol a = m: the column density).
inline void splat_column(const RenderPlane& g, const ProjectedKernel& f, const SplatParticle& p,
                         double* num) {
    const double h = drawn_h(g, p.h), inv_h = 1 / h, weight = p.vol * p.a * inv_h * inv_h;
    for_images(g, p, [&](double cu, double cv) {
        for_pixels_within(g, cu, cv, 2 * h, [&](std::size_t idx, double d2) {
            num[idx] += weight * f(std::sqrt(d2) * inv_h);
        });
    });
}

} // namespace exasph
