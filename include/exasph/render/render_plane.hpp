#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "exasph/util/box.hpp"
#include "exasph/util/error.hpp"

namespace exasph {

// What `exasph render` draws: `field` on a plane normal to `axis` (a slice at `at`, normalised
// with the kernel's Shepard sum) or integrated along `axis` (a projection, e.g. the column
// density for rho), on nx x ny pixels covering `region` (u lo, u hi, v lo, v hi in the plane's
// axes u, v: for axis z they are x, y; for y: x, z; for x: y, z).
struct RenderSpec {
    std::string field = "rho";
    bool project = false;
    int axis = 2;
    double at = NAN;                   // slice position (NaN: the middle of the box)
    int nx = 512;                      // pixels along u
    int ny = 0;                        // pixels along v (0: square pixels)
    std::array<double, 4> region{NAN}; // NaN: the box's extent
    bool log = false;                  // the picture's colour scale (the data stay linear)
};

// The pixel grid of a spec on a box. Pixel (i, j) has its centre at
// (lo[0] + (i + 1/2) d[0], lo[1] + (j + 1/2) d[1]) and the value image[j * n[0] + i].
struct RenderPlane {
    int u = 0, v = 1, w = 2; // the plane's axes and its normal
    double lo[2], hi[2], d[2];
    int n[2];
    bool periodic[2];
    double period[2];
    bool normal_periodic;
    double normal_period, at;

    RenderPlane(const RenderSpec& s, const Box<double>& box) {
        w = s.axis;
        u = s.axis == 0 ? 1 : 0;
        v = s.axis == 2 ? 1 : 2;
        const int ax[2] = {u, v};
        for (int k = 0; k < 2; ++k) {
            lo[k] = std::isnan(s.region[0]) ? box.lo[ax[k]] : s.region[2 * k];
            hi[k] = std::isnan(s.region[0]) ? box.hi[ax[k]] : s.region[2 * k + 1];
            if (!(hi[k] > lo[k])) throw input_error("render: --region needs lo < hi on both axes");
            periodic[k] = box.periodic[ax[k]];
            period[k] = box.length(ax[k]);
        }
        n[0] = s.nx;
        n[1] = s.ny > 0 ? s.ny
                        : std::max(1, int(std::lround(s.nx * (hi[1] - lo[1]) / (hi[0] - lo[0]))));
        for (int k = 0; k < 2; ++k) d[k] = (hi[k] - lo[k]) / n[k];
        normal_periodic = box.periodic[w];
        normal_period = box.length(w);
        at = std::isnan(s.at) ? 0.5 * (box.lo[w] + box.hi[w]) : s.at;
    }
    std::size_t pixels() const { return std::size_t(n[0]) * std::size_t(n[1]); }
    double pixel_size() const { return std::max(d[0], d[1]); }
};

} // namespace exasph
