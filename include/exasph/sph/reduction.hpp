#pragma once
#include <cstdint>
#include <limits>
#include <type_traits>

#include "exasph/particles/particle_index.hpp"
#include "exasph/util/annotate.hpp"

// Typed reductions: what a launcher (sph/launch.hpp) makes of the values a kernel returns. A
// kernel that returns a value names its reduction as the member type `Reduction`; the launcher
// starts each part from Reduction::identity() and combines values and parts with
// Reduction::combine, which must be associative and commutative. Min, max and first index give
// the same result in any order; a sum's parts are combined in thread (or block) order, so a
// run is reproducible for a given thread count.
namespace exasph {

// The smallest value (identity: +infinity, or the type's largest value).
template <class V>
struct MinOf {
    using value_type = V;
    EXASPH_HD static constexpr V identity() {
        return std::numeric_limits<V>::has_infinity ? std::numeric_limits<V>::infinity()
                                                    : std::numeric_limits<V>::max();
    }
    EXASPH_HD static constexpr V combine(V a, V b) { return b < a ? b : a; }
};

// The largest value (identity: -infinity, or the type's lowest value).
template <class V>
struct MaxOf {
    using value_type = V;
    EXASPH_HD static constexpr V identity() {
        return std::numeric_limits<V>::has_infinity ? -std::numeric_limits<V>::infinity()
                                                    : std::numeric_limits<V>::lowest();
    }
    EXASPH_HD static constexpr V combine(V a, V b) { return b > a ? b : a; }
};

template <class V>
struct SumOf {
    using value_type = V;
    EXASPH_HD static constexpr V identity() { return V(0); }
    EXASPH_HD static constexpr V combine(V a, V b) { return a + b; }
};

// A particle index that a kernel found (a singular matrix, a step below the shortest rung), or
// none.
struct FoundIndex {
    static constexpr ParticleIndex kNone = std::numeric_limits<ParticleIndex>::max();
    ParticleIndex index = kNone;

    EXASPH_HD static constexpr FoundIndex none() { return {}; }
    EXASPH_HD static constexpr FoundIndex at(ParticleIndex i) { return {i}; }
    EXASPH_HD constexpr bool found() const { return index != kNone; }
};

// The smallest index found by any particle's call: the same whatever the order of the calls.
struct FirstIndexWhere {
    using value_type = FoundIndex;
    EXASPH_HD static constexpr FoundIndex identity() { return FoundIndex::none(); }
    EXASPH_HD static constexpr FoundIndex combine(FoundIndex a, FoundIndex b) {
        return b.index < a.index ? b : a;
    }
};

// A kernel's reduction (its member type Reduction), or NoReduction for a kernel that returns
// nothing; ResultOf is what the launcher returns for it (void: nothing).
struct NoReduction {
    using value_type = void;
};
template <class Kernel, class = void>
struct ReductionOfKernel {
    using type = NoReduction;
};
template <class Kernel>
struct ReductionOfKernel<Kernel, std::void_t<typename Kernel::Reduction>> {
    using type = typename Kernel::Reduction;
};
template <class Kernel>
using ReductionOf = typename ReductionOfKernel<Kernel>::type;
template <class Kernel>
using ResultOf = typename ReductionOf<Kernel>::value_type;
template <class Kernel>
inline constexpr bool kReduces = !std::is_void_v<ResultOf<Kernel>>;

} // namespace exasph
