#pragma once
#include <cstdint>
#include <vector>

#include "exasph/gravity/gravity_kern.hpp"
#include "exasph/particles/particle_set.hpp"

namespace exasph::testref {

// Direct summation over all pairs with the same softened pair law as the tree (G = 1): the
// reference for the tree's multipole approximation.
inline std::vector<GravityField> direct_gravity(const ParticleSet<double>& ps, std::size_t n,
                                                const SofteningView<double>& soft) {
    GravityTreeView<double> tv{nullptr,           ps.data(Field::x), ps.data(Field::y),
                               ps.data(Field::z), ps.data(Field::m), ps.data(Field::h)};
    std::vector<GravityField> out(n);
    const auto nn = std::int64_t(n);
#pragma omp parallel for schedule(dynamic, 64)
    for (std::int64_t i = 0; i < nn; ++i) {
        GravityField f;
        for (std::uint32_t j = 0; j < n; ++j)
            if (j != std::uint32_t(i))
                add_pair_field(tv, soft, j, tv.x[i], tv.y[i], tv.z[i], tv.h[i], f);
        out[i] = f;
    }
    return out;
}

} // namespace exasph::testref
