#pragma once
#include <array>
#include <cstddef>

#include "exasph/particles/field_list.hpp"
#include "exasph/particles/particle_index.hpp"
#include "exasph/particles/particle_set.hpp"
#include "exasph/util/annotate.hpp"

namespace exasph {

// Raw pointers to every field of a ParticleSet: what kernels receive instead of containers, so
// that the same kernel runs on host memory and (later) device memory. A disabled optional field
// is a null pointer. N is the storage type of the is_narrow fields: float (the default,
// --precision mixed) or T (--precision double); kernels are instantiated for both.
template <class T, class N = float>
struct ParticleView {
    using narrow_type = N;
    T* ptr[kNumFields];
    N* nptr[kNumFields]; // the is_narrow fields

    EXASPH_HD T* operator[](Field f) const { return ptr[static_cast<std::size_t>(f)]; }
    EXASPH_HD N* narrow(Field f) const { return nptr[static_cast<std::size_t>(f)]; }
};

template <class N = float, class T>
ParticleView<T, N> make_view(ParticleSet<T>& ps) {
    ParticleView<T, N> v{};
    for (std::size_t i = 0; i < kNumFields; ++i) {
        const auto f = static_cast<Field>(i);
        const bool on = ps.enabled(f); // disabled optional fields: null
        v.ptr[i] = on && !is_narrow(f) ? ps.data(f) : nullptr;
        v.nptr[i] = on && is_narrow(f) ? ps.template narrow_as<N>(f) : nullptr;
    }
    return v;
}

// Calls fn with the view of ps whose narrow type matches ps's storage (float or T).
template <class T, class Fn>
decltype(auto) with_view(ParticleSet<T>& ps, Fn&& fn) {
    if (ps.narrow_single()) return fn(make_view<float>(ps));
    return fn(make_view<T>(ps));
}

} // namespace exasph
