#pragma once
#include <array>
#include <cstddef>

#include "exasph/particles/field_list.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// Raw pointers to every field of a ParticleSet: what kernels receive instead of containers, so
// that the same kernel runs on host memory and (later) device memory. A disabled optional field
// is a null pointer.
template <class T>
struct ParticleView {
    T* ptr[kNumFields];
    float* nptr[kNumFields]; // the single-precision fields (is_narrow)

    EXASPH_HD T* operator[](Field f) const { return ptr[static_cast<std::size_t>(f)]; }
    EXASPH_HD float* narrow(Field f) const { return nptr[static_cast<std::size_t>(f)]; }
};

template <class T>
ParticleView<T> make_view(ParticleSet<T>& ps) {
    ParticleView<T> v{};
    for (std::size_t i = 0; i < kNumFields; ++i) {
        const auto f = static_cast<Field>(i);
        const bool on = ps.enabled(f); // disabled optional fields: null
        v.ptr[i] = on && !is_narrow(f) ? ps.data(f) : nullptr;
        v.nptr[i] = on && is_narrow(f) ? ps.narrow(f) : nullptr;
    }
    return v;
}

} // namespace exasph
