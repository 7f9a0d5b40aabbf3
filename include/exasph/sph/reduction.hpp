#pragma once
#include <cstddef>
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

// The fixed tree of a launcher's reduce_tree(n, k): the values k(0) .. k(n - 1), padded with
// the reduction's identity to whole runs of kTreeFan, are folded one run at a time as a balanced
// binary tree over neighbours, ((v0 v1) (v2 v3)) ((v4 v5) (v6 v7)) ..., the earlier value always
// on the left of combine; the runs' values are the next level's values, folded the same way until
// one is left. The shape depends on n only, so a floating-point sum gives the same bits on every
// launcher and thread count (a CUDA block of kTreeFan threads folds one run in shared memory, the
// CPU streams it through one partial value per tree level), and nothing but the last value needs
// to leave the device.
inline constexpr std::size_t kTreeFan = 128;
inline constexpr int kTreeFanLevels = 7;
static_assert(kTreeFan == std::size_t(1) << kTreeFanLevels);

// The number of runs of kTreeFan that cover n values.
EXASPH_HD constexpr std::size_t tree_runs(std::size_t n) {
    return (n + kTreeFan - 1) / kTreeFan;
}

// One run of the tree folded on the host as its values arrive (add() exactly kTreeFan times,
// then value()): a value completes the subtrees whose last leaf it is.
template <class R>
class TreeRunFold {
  public:
    using V = typename R::value_type;
    TreeRunFold() {
        for (V& v : left_) v = R::identity();
    }
    void add(const V& v) {
        std::size_t t = added_++;
        if (!(t & 1)) { // a left leaf: kept until its right neighbour comes
            left_[0] = v;
            return;
        }
        V carry = R::combine(left_[0], v);
        int level = 1;
        for (t >>= 1; t & 1; t >>= 1, ++level) carry = R::combine(left_[level], carry);
        left_[level] = carry;
    }
    const V& value() const { return left_[kTreeFanLevels]; }

  private:
    V left_[kTreeFanLevels + 1]; // the finished left subtree of each level
    std::size_t added_ = 0;
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
